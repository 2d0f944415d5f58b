#pragma once
// A directory of numbered PNGs, frame_000000.png, frame_000001.png, … (frame i at t = i / fps).
//
// Frames are written into a staging subdirectory "<dir>/frames.partial-<pid>-<n>"
// (output::StagingDirectory) and moved into <dir> by finish(); frame_NNNNNN.png files there from
// an earlier, longer run are removed then, so the directory holds exactly this run (a range of the
// frames, FrameWriterOptions::firstIndex, is named by its indices in the whole render and leaves
// every other frame file alone). Other files in <dir> are never touched, except staging
// directories that killed runs left there. The directory is created if missing (its parent must
// exist) and removed again on abort if it was created here and is empty.

#include <optional>
#include <string>
#include <vector>

#include "render/video/frame_pipeline.hpp"
#include "render/video/frame_writer.hpp"
#include "render/video/pipelined_frame_writer.hpp"
#include "output/staging_directory.hpp"

namespace particles::render {

// "frame_000042.png"
std::string sequenceFrameName(long index);
// 42 for "frame_000042.png" (six or more digits); nothing for any other name.
std::optional<long> sequenceFrameIndex(const std::string& name);

class PngSequenceWriter final : public PipelinedFrameWriter {
 public:
  // Throws OutputError if the directory cannot be created or is not a directory.
  PngSequenceWriter(const std::filesystem::path& directory, const FrameWriterOptions& options);
  ~PngSequenceWriter() override;  // abort() unless finished

  const std::filesystem::path& destination() const override { return directory_; }

 private:
  void publish() override;
  void discard() noexcept override;

  std::filesystem::path directory_;
  long firstIndex_ = 0;        // the first frame's index in the whole render (its file name)
  bool wholeSequence_ = true;  // finish() removes frames of an earlier, longer run
  bool createdDirectory_ = false;
  std::optional<output::StagingDirectory> staging_;
  // The pipeline's frames (FramePipeline::slotCount). The destructor stops the pipeline before
  // they go (abort(), or finish() has closed it).
  std::vector<Image> slots_;
};

}  // namespace particles::render
