// `particles concat`: see concat_command.hpp.
#include "app/concat_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <stdexcept>

#include "app/exit_codes.hpp"
#include "app/job_record.hpp"
#include "render/video/frame_writer.hpp"
#include "render/video/mp4_concat.hpp"

namespace particles::app {

namespace {

void addConcatOptions(CLI::App& command, ConcatOptions& o) {
  command.add_option("segments", o.segments, "The segments, in order (MP4 files of the same size, rate and settings)")
      ->required();
  command.add_option("-o,--output", o.output, render::concatOutputHelp())->required();
  command.add_flag("-q,--quiet", o.quiet, "Print nothing on success");
  command.footer(
      "Exit codes: 0 joined, 2 bad input (a segment unreadable, truncated or damaged: every packet is\n"
      "decoded on its way; or unlike the first; or -o naming a segment), 3 the output failed. Segments are\n"
      "opened one at a time.\n"
      "Examples:\n"
      "  particles render scenarios/cloth.yaml -o part0.mp4 --frames 0:300\n"
      "  particles render scenarios/cloth.yaml -o part1.mp4 --frames 300:\n"
      "  particles concat part0.mp4 part1.mp4 -o cloth.mp4\n");
  addJobOptions(command, o.job);
}

int concatCommand(const ConcatOptions& o) {
  render::setLibavVerbose(false);  // the muxer's notes at "info" are not ours to print
  std::vector<std::filesystem::path> segments(o.segments.begin(), o.segments.end());
  render::ConcatSummary summary;
  try {
    render::checkConcatOutput(o.output);  // before any segment is opened
    summary = render::concatMp4(segments, o.output);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  reportHeadline("frames", double(summary.frames));
  reportHeadline("video_seconds", summary.seconds);
  if (!o.quiet) {
    fmt::print("{} segments, {} frames, {:.6g} s → {}\n", segments.size(), summary.frames, summary.seconds, o.output);
  }
  return kOk;
}

CommandFiles concatFiles(const ConcatOptions& o) {
  CommandFiles files{{{"-o", o.output}}, {}};
  for (const std::string& segment : o.segments) files.inputs.push_back({"the segment", segment});
  return files;
}

}  // namespace

const CommandDescriptor<ConcatOptions> kConcatCommand = {
    .name = "concat",
    .summary = "Join MP4 segments of a split render (render --frames A:B) into one video, without re-encoding",
    .addOptions = addConcatOptions,
    .run = concatCommand,
    .files = concatFiles,
    .job = &ConcatOptions::job,
};

}  // namespace particles::app
