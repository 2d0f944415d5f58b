#include "input/default_threads.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <string_view>

#include "input/available_cores.hpp"

namespace particles::input {

bool threadCountInEnvironment() {
  const char* environment = std::getenv(kThreadsEnvironmentVariable);
  return environment != nullptr && *environment != '\0';
}

int defaultThreads(int maxThreads) {
  if (!threadCountInEnvironment()) return std::min(availableCores(), maxThreads);
  const std::string_view text(std::getenv(kThreadsEnvironmentVariable));
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < 1 || value > maxThreads) {
    throw BadThreadCount(fmt::format("{}={:?}: the number of threads is a whole number from 1 to {}",
                                     kThreadsEnvironmentVariable, text, maxThreads));
  }
  return value;
}

}  // namespace particles::input
