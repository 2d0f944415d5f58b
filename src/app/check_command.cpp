// `particles check`: see check_command.hpp.
#include "app/check_command.hpp"

#include <fmt/format.h>

#include "app/cli_support.hpp"
#include "scenario/scenario.hpp"

namespace particles::app {

namespace {

void addCheckOptions(CLI::App& command, CheckOptions& o) {
  addCommonOptions(command, o.common);
  addStyleOption(command, o.common);
  command.footer(
      "Examples:\n"
      "  particles check scenarios/cloth.yaml\n"
      "  particles check my.yaml --set simulation.dt=0.005 --set forces[1].kd=0.1\n");
}

int checkCommand(const CheckOptions& o) {
  const CommonOptions& common = o.common;
  const scenario::Scenario s = loadScenario(common);
  if (!common.quiet) fmt::print("{}\n", scenario::checkSummary(s, common.scenario));
  return kOk;
}

}  // namespace

const CommandDescriptor<CheckOptions> kCheckCommand = {
    .name = "check",
    .summary = "Validate a scenario file without simulating (exit 0 or 2)",
    .addOptions = addCheckOptions,
    .run = checkCommand,
    .common = &CheckOptions::common,
};

}  // namespace particles::app
