#include "render/video/png_sequence_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>

#include "output/confined_folder.hpp"
#include "render/errors.hpp"

namespace particles::render {

namespace fs = std::filesystem;

std::string sequenceFrameName(long index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06ld.png", index);
  return name;
}

std::optional<long> sequenceFrameIndex(const std::string& name) {
  const std::string prefix = "frame_", suffix = ".png";
  if (name.size() < prefix.size() + 6 + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix)) {
    return std::nullopt;
  }
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.size() > 18 ||
      !std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); })) {
    return std::nullopt;
  }
  return std::stol(digits);
}

PngSequenceWriter::PngSequenceWriter(const fs::path& directory, const FrameWriterOptions& options)
    : PipelinedFrameWriter(options.width, options.height, "the sequence"), directory_(directory) {
  if (options.png.compressionLevel < 0 || options.png.compressionLevel > 9) {
    throw std::invalid_argument("PNG compression level " + std::to_string(options.png.compressionLevel) +
                                " is out of range 0–9");
  }
  std::error_code ec;
  if (fs::exists(directory_, ec)) {
    if (!fs::is_directory(directory_, ec)) throw OutputError(directory_.string() + " exists and is not a directory");
  } else {
    createdDirectory_ = fs::create_directory(directory_, ec);
    if (ec) throw OutputError("cannot create directory " + directory_.string() + ": " + ec.message());
  }
  try {
    staging_.emplace(directory_ / "frames");
  } catch (const OutputError&) {
    abort();
    throw;
  }
  const fs::path staging = staging_->path();
  PngOptions png = options.png;
  png.alpha = png.alpha || options.alpha;  // frames with a transparent background: RGBA files
  const long firstIndex = options.firstIndex;
  firstIndex_ = firstIndex;
  wholeSequence_ = options.wholeSequence;
  slots_.resize(FramePipeline::slotCount(options.queueFrames));
  Image* slots = slots_.data();
  pipeline_ = std::make_unique<FramePipeline>(
      options.queueFrames,
      // assign() reuses the slot's memory once it has held a frame of this size.
      [slots](const Image& image, size_t slot) {
        slots[slot].width = image.width;
        slots[slot].height = image.height;
        slots[slot].rgba.assign(image.rgba.begin(), image.rgba.end());
      },
      [slots, staging, png, firstIndex](size_t slot, long index) {
        writePngDirect(staging / sequenceFrameName(firstIndex + index), slots[slot], png);
      });
}

PngSequenceWriter::~PngSequenceWriter() {
  if (!finished_) abort();
}

void PngSequenceWriter::publish() {
  // The frames are moved in, and an earlier run's extra frames removed, from the folders' own
  // descriptors (output/confined_folder.hpp): a frame's name that is a link in the folder is
  // replaced as a name, never followed, and the folder swapped for a link meanwhile changes nothing.
  const output::ConfinedFolder folder(directory_);
  const output::ConfinedFolder staged(staging_->path());
  for (long i = 0; i < frames_; ++i) {
    const std::string name = sequenceFrameName(firstIndex_ + i);
    if (::renameat(staged.fd(), name.c_str(), folder.fd(), name.c_str()) != 0) {
      throw OutputError("cannot move " + name + " into " + directory_.string() + ": " + std::strerror(errno));
    }
  }
  // Frames beyond this run's last, left by an earlier run (a range leaves the others' frames).
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory_, ec)) {
    if (!wholeSequence_) break;
    const std::string name = entry.path().filename().string();
    const std::optional<long> index = sequenceFrameIndex(name);
    if (!index || *index < frames_) continue;
    try {
      folder.remove(name);
    } catch (const OutputError&) {
      // Best effort: what cannot be removed (a folder of that name) is left; the frames are in.
    }
  }
  staging_->discard();
}

void PngSequenceWriter::discard() noexcept {
  if (staging_) staging_->discard();
  std::error_code ec;
  if (createdDirectory_ && fs::is_empty(directory_, ec)) fs::remove(directory_, ec);
}

}  // namespace particles::render
