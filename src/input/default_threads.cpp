#include "input/default_threads.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <string_view>

#include "input/available_cores.hpp"

namespace particles::input {

int defaultThreads(int maxThreads) {
  const char* environment = std::getenv(kThreadsEnvironmentVariable);
  if (environment == nullptr || *environment == '\0') return std::min(availableCores(), maxThreads);
  const std::string_view text(environment);
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < 1 || value > maxThreads) {
    throw BadThreadCount(fmt::format("{}={:?}: the number of threads is a whole number from 1 to {}",
                                     kThreadsEnvironmentVariable, text, maxThreads));
  }
  return value;
}

}  // namespace particles::input
