#include "output/pending_output.hpp"

#include <unistd.h>

#include <atomic>
#include <string>
#include <system_error>

#include "output/output_error.hpp"

namespace particles::output {

namespace {
std::atomic<unsigned> counter{0};
}

PendingOutput::PendingOutput(std::filesystem::path destination) : destination_(std::move(destination)) {
  temporary_ = destination_;
  temporary_ += ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

PendingOutput::~PendingOutput() {
  if (!done_) discard();
}

void PendingOutput::commit() {
  std::error_code ec;
  std::filesystem::rename(temporary_, destination_, ec);
  if (ec) {
    discard();
    throw OutputError("cannot rename " + temporary_.string() + " to " + destination_.string() + ": " + ec.message());
  }
  done_ = true;
}

void PendingOutput::discard() noexcept {
  std::error_code ec;
  std::filesystem::remove_all(temporary_, ec);
  done_ = true;
}

}  // namespace particles::output
