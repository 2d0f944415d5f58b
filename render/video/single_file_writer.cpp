#include "render/video/single_file_writer.hpp"

namespace particles::render {

SingleFileWriter::SingleFileWriter(const std::filesystem::path& path, int width, int height, std::string what)
    : PipelinedFrameWriter(width, height, std::move(what)), out_(path) {}

void SingleFileWriter::publish() {
  complete();
  release();
  out_.commit();
}

void SingleFileWriter::discard() noexcept {
  release();  // closes the file
  out_.discard();
}

}  // namespace particles::render
