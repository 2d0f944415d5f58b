#pragma once
// Joins MP4 segments (`particles render --frames A:B -o part.mp4`) into one video by stream copy:
// libavformat reads each segment's H.264 packets and writes them into one MP4, their timestamps
// moved on by the durations of the segments before, with no decoding or re-encoding. Every
// segment starts with a keyframe (an encoder's first frame is one), so the joined stream decodes
// from any segment's start.
//
// The segments must be alike, or the copy would be a broken stream: one video stream each, of the
// same codec, size, pixel format, frame rate and time base, and the same codec header (SPS/PPS,
// which the same encoder settings give). The output appears only when complete, as every output
// here does (output/pending_output.hpp).
//
// What is joined is checked, not trusted: every packet of every segment is decoded on its way to
// the output (libavcodec, errors not concealed), and a segment must give as many pictures as its
// index lists, so a truncated or damaged one is refused, named, instead of joined with its last
// frames missing. Segments are opened one at a time, so memory does not grow with their number.

#include <filesystem>
#include <vector>

namespace particles::render {

struct ConcatSummary {
  long frames = 0;       // video packets copied: one per frame
  double seconds = 0.0;  // the joined video's duration
};

// Throws std::invalid_argument for bad input: no segment, a segment that cannot be read as a video
// or does not decode whole (truncated, damaged), or segments that differ (the message names the
// offending file and what is wrong); OutputError when the output cannot be written.
ConcatSummary concatMp4(const std::vector<std::filesystem::path>& segments, const std::filesystem::path& output);

}  // namespace particles::render
