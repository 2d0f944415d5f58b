#pragma once
// `particles concat A.mp4 B.mp4 … -o ALL.mp4`: joins the segments of a split render
// (`particles render --frames A:B`) by stream copy (render/video/mp4_concat.hpp).
//
// Exit codes: 0 joined; 2 bad input (a segment that cannot be read or does not decode whole, or
// segments that differ in size, frame rate, codec or codec header: the message names the file; -o
// or --record naming a segment, refused before anything is read); 3 the output could not be written.

#include <string>
#include <vector>

#include "app/command.hpp"

namespace particles::app {

struct ConcatOptions {
  std::vector<std::string> segments;
  std::string output;
  bool quiet = false;
  JobOptions job;
};

extern const CommandDescriptor<ConcatOptions> kConcatCommand;

}  // namespace particles::app
