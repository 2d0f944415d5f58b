#include "app/command_table.hpp"

#include "app/check_command.hpp"
#include "app/compare_command.hpp"
#include "app/concat_command.hpp"
#include "app/gather_command.hpp"
#include "app/golden_command.hpp"
#include "app/job_command.hpp"
#include "app/plot_command.hpp"
#include "app/render_command.hpp"
#include "app/run_command.hpp"
#include "app/schema_command.hpp"
#include "app/stability_command.hpp"
#include "app/sweep_command.hpp"

namespace particles::app {

namespace {

const AddCommand kRows[] = {
    addCommand<kCheckCommand>,   addCommand<kRunCommand>,    addCommand<kRenderCommand>, addCommand<kStabilityCommand>,
    addCommand<kCompareCommand>, addCommand<kGoldenCommand>, addCommand<kConcatCommand>, addCommand<kPlotCommand>,
    addCommand<kSchemaCommand>,  addCommand<kSweepCommand>,  addCommand<kGatherCommand>, addCommand<kRunJobCommand>,
};

}  // namespace

const std::span<const AddCommand> kCommands = kRows;

}  // namespace particles::app
