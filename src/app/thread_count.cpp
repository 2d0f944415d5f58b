#include "app/thread_count.hpp"

#include "app/exit_codes.hpp"
#include "input/default_threads.hpp"

namespace particles::app {

int threadCountOf(int option) {
  if (option > 0) return option;
  try {
    return input::defaultThreads(kMaxThreads);
  } catch (const input::BadThreadCount& e) {
    throw InputError(e.what());
  }
}

bool threadCountGiven(int option) {
  return option > 0 || input::threadCountInEnvironment();
}

}  // namespace particles::app
