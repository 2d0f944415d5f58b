#include "app/exit_codes.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <exception>

#include "core/solver.hpp"
#include "output/distinct_files.hpp"
#include "output/output_error.hpp"
#include "plot/errors.hpp"
#include "render/errors.hpp"
#include "scenario/scenario.hpp"

namespace particles::app {

int runReportingErrors(const ErrorContext& context, const std::function<int()>& command) {
  auto report = [&](ExitCode code, const std::string& message) {
    fmt::print(stderr, "{}\n", message);
    if (context.printed) *context.printed = message;
    return code;
  };
  auto failed = [&](const std::exception& e) { return fmt::format("{}: error: {}", context.scenario, e.what()); };
  auto error = [](const std::exception& e) { return fmt::format("error: {}", e.what()); };
  try {
    return command();
  } catch (const SimulationError& e) {
    return report(kSimulationFailed, failed(e));
  } catch (const SimulationFailure& e) {
    return report(kSimulationFailed, failed(e));
  } catch (const scenario::ScenarioError& e) {
    return report(kBadInput, e.what());  // the loader's message names file, line and key
  } catch (const InputError& e) {
    return report(kBadInput, error(e));
  } catch (const plot::CsvError& e) {
    return report(kBadInput, error(e));
  } catch (const output::SameFileError& e) {  // an output that is an input or another output
    return report(kBadInput, error(e));
  } catch (const output::OutputError& e) {
    return report(kOutputFailed, error(e));
  } catch (const render::RenderError& e) {
    return report(kOutputFailed, error(e));
  } catch (const plot::FigureError& e) {
    return report(kOutputFailed, error(e));
  } catch (const std::exception& e) {
    // Every expected failure has a type above; this is a bug, reported rather than aborted.
    return report(kSimulationFailed, fmt::format("particles: internal error: {}", e.what()));
  }
}

}  // namespace particles::app
