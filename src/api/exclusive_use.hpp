#pragma once
// One call at a time on an API object that a call changes (a Simulation, a Renderer, a
// VideoWriter): a second thread's call while one is under way is refused with particles::Error,
// never a race (include/particles/simulation.hpp).

#include <fmt/format.h>

#include <atomic>
#include <string_view>

#include <particles/errors.hpp>

namespace particles {

// Holds `busy` for the life of a call; throws when another call holds it.
class ExclusiveUse {
 public:
  ExclusiveUse(std::atomic<bool>& busy, std::string_view call, std::string_view what = "Simulation") : busy_(busy) {
    if (busy_.exchange(true)) {
      throw Error(fmt::format("{}: this {} is in use by another thread's call; a {} is driven by one thread at a time",
                              call, what, what));
    }
  }
  ~ExclusiveUse() { busy_.store(false); }
  ExclusiveUse(const ExclusiveUse&) = delete;
  ExclusiveUse& operator=(const ExclusiveUse&) = delete;

 private:
  std::atomic<bool>& busy_;
};

}  // namespace particles
