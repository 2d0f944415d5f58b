#pragma once
// `particles compare EXPECTED.png ACTUAL.png [--diff D.png]` (docs/physics.md §10, §12): the golden-frame
// comparison as a tool of its own (render/image_compare.hpp).
//
// Exit codes: 0 the frames match; 1 they differ (more than --max-share of the pixels have a
// channel differing by more than --threshold): the counterpart of a simulation failure, "the
// result is wrong"; 2 bad input (an unreadable PNG, sizes that do not match, read from the two
// headers before either is decoded, bad options; a --diff not named .png, or naming one of the
// frames, refused before anything is read); 3 the --diff picture could not be written, or memory
// ran out (the frames decode to 4 bytes a pixel each, the --diff picture as much again).

#include <string>

#include "app/command.hpp"
#include "render/image_compare.hpp"

namespace particles::app {

struct CompareOptions {
  std::string expected;  // the golden frame
  std::string actual;    // the frame under test
  std::string diff;      // --diff D.png; empty: none
  int threshold = render::kDefaultThreshold;
  double maxShare = render::kDefaultMaxShare;
  bool quiet = false;
};

extern const CommandDescriptor<CompareOptions> kCompareCommand;

}  // namespace particles::app
