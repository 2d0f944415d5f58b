#include "app/gl_options.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <stdexcept>

#include "app/exit_codes.hpp"

namespace particles::app {

render::GlRequest glRequestOf(const std::string& option, bool gpu) {
  std::string name = "auto", source;  // source: where the name came from, for messages
  if (!option.empty()) {
    name = option;
    source = "--gl " + option;
  } else if (const char* environment = std::getenv(kGlEnvironmentVariable); environment && *environment) {
    name = environment;
    source = fmt::format("{}={}", kGlEnvironmentVariable, environment);
  }
  const auto backend = render::glBackendFromName(name);
  if (!backend) throw InputError(fmt::format("{}: expected {}", source, fmt::join(render::glBackendNames(), ", ")));
  const render::GlRequest request{*backend, gpu};
  try {
    render::validate(request);
  } catch (const std::invalid_argument& e) {
    if (gpu) source += source.empty() ? "--gpu" : " with --gpu";
    throw InputError(fmt::format("{}: {}", source, e.what()));
  }
  return request;
}

std::string glVersionLine() {
  const char* environment = std::getenv(kGlEnvironmentVariable);
  const std::string label =
      environment && *environment ? fmt::format("GL ({}={})", kGlEnvironmentVariable, environment) : "GL";
  try {
    return fmt::format("{}: {}", label, render::describe(render::probeGl(glRequestOf("", false))));
  } catch (const std::exception& e) {
    return fmt::format("{}: none available: {}", label, e.what());
  }
}

}  // namespace particles::app
