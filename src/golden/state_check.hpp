#pragma once
// The state check of one entry: its scenario simulated once through its times, the state of every
// particle and rigid body at each (golden/state_table.hpp) compared value by value with the
// reference CSV. Internal to the golden room (golden/check.hpp runs it).

#include "golden/check_context.hpp"
#include "golden/results.hpp"
#include "scenario/golden_manifest.hpp"

namespace particles::golden {

// The result of `check` (a state check), with the files the report shows kept under the run's
// folder: states/NAME.actual.csv, .expected.csv. A scenario that does not load, a simulation that
// blows up or a time after the scenario's duration is the `error` outcome. Throws OutputError (a
// kept file) and std::bad_alloc: the run's failures, not the entry's.
StateResult checkState(CheckContext& run, const scenario::GoldenCheck& check);

}  // namespace particles::golden
