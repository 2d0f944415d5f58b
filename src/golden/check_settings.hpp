#pragma once
// The settings a check runs with, from the manifest (scenario::renderSettingsOf,
// frameToleranceOf, stateToleranceOf: an entry's own over the run's command line over the
// manifest's defaults) into what the renderer and the comparisons take, with the programs'
// defaults for what nothing sets. Internal to the golden room; checkRenderSettings is check.hpp's.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "golden/check.hpp"
#include "golden/state_table.hpp"
#include "render/image_compare.hpp"
#include "render/render_options.hpp"
#include "scenario/golden_manifest.hpp"

namespace particles::golden {

// A render setting as `particles render` takes it: a row of render::lookOptions(), its text, and
// where the manifest writes it.
struct LookSetting {
  std::string_view flag;
  std::string text;
  scenario::GoldenPosition at;
};
// The settings `render` sets: size, msaa, theme, raster, background, those written.
std::vector<LookSetting> lookSettingsOf(const scenario::GoldenRenderSettings& render);

// The look of a frame of `entry`: its settings, the run's --raster between its own and the
// defaults, read as `particles render` reads its options, over the scenario's size (width, height)
// and the program's defaults. Throws std::invalid_argument for a setting the renderer does not
// take (checkRenderSettings refuses those first).
render::RenderOptions frameLookOf(const scenario::GoldenManifest& manifest, const scenario::GoldenEntry& entry,
                                  const CheckOverrides& overrides, std::pair<int, int> scenarioSize);

// A frame entry's tolerance, the run's --threshold and --max-share between its own and the
// defaults, `particles compare`'s defaults below.
render::CompareTolerance compareToleranceOf(const scenario::GoldenManifest& manifest,
                                            const scenario::GoldenEntry& entry, const CheckOverrides& overrides);

// A state entry's tolerances.
StateTolerance stateCompareToleranceOf(const scenario::GoldenManifest& manifest, const scenario::GoldenEntry& entry);

}  // namespace particles::golden
