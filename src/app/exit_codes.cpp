#include "app/exit_codes.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <exception>
#include <new>
#include <typeinfo>

#include "core/solver.hpp"
#include "output/confined_folder.hpp"
#include "output/distinct_files.hpp"
#include "output/output_error.hpp"
#include "input/printable_text.hpp"
#include "plot/errors.hpp"
#include "render/errors.hpp"
#include "scenario/scenario.hpp"

namespace particles::app {

int runReportingErrors(const ErrorContext& context, const std::function<int()>& command) {
  auto report = [&](ExitCode code, const std::string& message) {
    fmt::print(stderr, "{}\n", input::printableText(message));
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
  } catch (const ImplicitSolverError& e) {  // the scenario's implicit_solver cannot be honoured
    return report(kBadInput, failed(e));
  } catch (const scenario::ScenarioError& e) {
    return report(kBadInput, e.what());  // the loader's message names file, line and key
  } catch (const InputError& e) {
    return report(kBadInput, error(e));
  } catch (const plot::CsvError& e) {
    return report(kBadInput, error(e));
  } catch (const output::SameFileError& e) {  // an output that is an input or another output
    return report(kBadInput, error(e));
  } catch (const output::OutsideFolderError& e) {  // a file of a command's folder that leads out of it
    return report(kBadInput, error(e));
  } catch (const output::OutputError& e) {
    return report(kOutputFailed, error(e));
  } catch (const render::RenderError& e) {
    return report(kOutputFailed, error(e));
  } catch (const plot::FigureError& e) {
    return report(kOutputFailed, error(e));
  } catch (const std::bad_alloc& e) {
    // Before std::exception: a failed allocation is no bug and no result ("simulation failed",
    // "frames differ"), but the machine's or the cap's limit, like a full disk. render::OutOfMemory
    // says what needed the memory; a bare std::bad_alloc only that an allocation failed.
    return report(kOutputFailed, typeid(e) == typeid(std::bad_alloc)
                                     ? std::string("error: out of memory: an allocation failed (std::bad_alloc)")
                                     : fmt::format("error: out of memory: {}", e.what()));
  } catch (const std::exception& e) {
    // Every expected failure has a type above; this is a bug, reported rather than aborted.
    return report(kSimulationFailed, fmt::format("particles: internal error: {}", e.what()));
  }
}

}  // namespace particles::app
