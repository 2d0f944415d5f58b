#include "api/guarded_call.hpp"

#include <stdexcept>

#include "output/distinct_files.hpp"

namespace particles::api {

void rethrowAsPublicError(std::string_view call) {
  try {
    throw;
  } catch (const particles::Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw particles::Error(fmt::format("{}: out of memory", call));
  } catch (const output::SameFileError& e) {
    // An output that is one of the call's inputs: a bad argument, as the command line's exit 2.
    throw particles::ArgumentError(fmt::format("{}: {}", call, e.what()));
  } catch (const std::invalid_argument& e) {
    throw particles::ArgumentError(fmt::format("{}: {}", call, e.what()));
  } catch (const std::exception& e) {
    throw particles::Error(fmt::format("{}: {}", call, e.what()));
  } catch (...) {
    throw particles::Error(fmt::format("{}: an unknown error", call));
  }
}

}  // namespace particles::api
