#include "render/frame_memory.hpp"

#include <fmt/format.h>
#include <sys/mman.h>

#include <new>
#include <utility>

#include "render/errors.hpp"

namespace particles::render {

namespace {

std::size_t mebibytes(std::size_t bytes) {
  return (bytes + (std::size_t(1) << 20) - 1) >> 20;
}

}  // namespace

std::size_t frameBytes(int width, int height) {
  return std::size_t(width) * std::size_t(height) * 4;
}

MemoryReservation::MemoryReservation(std::size_t bytes, const std::string& what) : bytes_(bytes) {
  if (bytes == 0) return;
  void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) {
    throw OutOfMemory(fmt::format("{} needs {} MiB, more than this process can allocate now", what, mebibytes(bytes)));
  }
  address_ = p;
}

MemoryReservation::~MemoryReservation() {
  if (address_) ::munmap(address_, bytes_);
}

MemoryReservation::MemoryReservation(MemoryReservation&& other) noexcept
    : address_(std::exchange(other.address_, nullptr)), bytes_(std::exchange(other.bytes_, 0)) {}

MemoryReservation& MemoryReservation::operator=(MemoryReservation&& other) noexcept {
  if (this != &other) {
    if (address_) ::munmap(address_, bytes_);
    address_ = std::exchange(other.address_, nullptr);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

Image allocateImage(int width, int height, const std::string& what) {
  try {
    return Image(width, height);
  } catch (const std::bad_alloc&) {
    throw OutOfMemory(fmt::format("{} ({}x{} pixels) needs {} MiB, which could not be allocated", what, width, height,
                                  mebibytes(frameBytes(width, height))));
  }
}

}  // namespace particles::render
