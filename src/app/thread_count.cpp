#include "app/thread_count.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>
#include <string_view>

#include "app/available_cores.hpp"
#include "app/exit_codes.hpp"

namespace particles::app {

int threadCountOf(int option) {
  if (option > 0) return option;
  const char* environment = std::getenv(kThreadsEnvironmentVariable);
  if (environment == nullptr || *environment == '\0') return availableCores();
  const std::string_view text(environment);
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < 1 || value > kMaxThreads) {
    throw InputError(fmt::format("{}={:?}: the number of threads is a whole number from 1 to {}",
                                 kThreadsEnvironmentVariable, text, kMaxThreads));
  }
  return value;
}

}  // namespace particles::app
