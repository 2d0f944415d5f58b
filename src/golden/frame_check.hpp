#pragma once
// The frame checks of one entry: its scenario simulated once through the times the run selected,
// in increasing order, each frame drawn as `particles render --at T` draws it and compared with its
// reference as `particles compare` does. Internal to the golden room (golden/check.hpp runs it).

#include <vector>

#include "golden/check_context.hpp"
#include "golden/results.hpp"
#include "scenario/golden_manifest.hpp"

namespace particles::golden {

// The results of `checks` (frame checks of one entry, in time order), in order, with the files the
// report shows kept under the run's folder: frames/NAME.actual.png, .expected.png, .diff.png. A
// scenario that does not load, a simulation that blows up or a GL error is the `error` outcome of
// every check it leaves without one; a time after the scenario's duration that check's. Throws
// OutputError (a kept file) and std::bad_alloc: the run's failures, not the entry's.
std::vector<FrameResult> checkFrames(CheckContext& run, const std::vector<scenario::GoldenCheck>& checks);

}  // namespace particles::golden
