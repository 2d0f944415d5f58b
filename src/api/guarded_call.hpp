#pragma once
// The boundary between the public API (include/particles/) and the rooms: every API call runs its
// body through guardedCall, so that what leaves the library is a particles::Error of the public
// hierarchy with a message as good as the command line's, never another exception type.

#include <fmt/format.h>

#include <exception>
#include <new>
#include <string_view>

#include <particles/errors.hpp>

// A thread that is ended while inside a call (pthread_exit, pthread_cancel: CPython ends a daemon
// thread so when it asks for the GIL back during interpreter exit) unwinds with glibc's
// abi::__forced_unwind, which a catch (...) must pass on: swallowed or replaced, it aborts the
// process ("FATAL: exception not rethrown"). Put before a catch (...) that does not rethrow.
#if defined(__GLIBCXX__)
#include <cxxabi.h>
#define PARTICLES_PASS_FORCED_UNWIND \
  catch (abi::__forced_unwind&) {    \
    throw;                           \
  }
#else
#define PARTICLES_PASS_FORCED_UNWIND
#endif

namespace particles::api {

// Rethrows the exception in flight as a particles::Error: the public types as they are (the
// scenario loader, the solver and the writers throw them), out of memory and the rooms' other
// errors with `call` and their own message.
[[noreturn]] void rethrowAsPublicError(std::string_view call);

template <class Body>
decltype(auto) guardedCall(std::string_view call, Body&& body) {
  try {
    return body();
  }
  PARTICLES_PASS_FORCED_UNWIND catch (...) {
    rethrowAsPublicError(call);
  }
}

}  // namespace particles::api
