// The settings a check runs with: see check_settings.hpp.
#include "golden/check_settings.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "input/printable_text.hpp"

namespace particles::golden {

using scenario::GoldenEntry;
using scenario::GoldenManifest;

namespace {

// The run's settings over the manifest's defaults, as the manifest's settings.
scenario::GoldenRenderSettings commandLineRender(const CheckOverrides& o) {
  scenario::GoldenRenderSettings r;
  if (o.raster) r.raster = scenario::GoldenSetting<std::string>{std::string(render::rasterNameOf(*o.raster)), {}};
  return r;
}

scenario::GoldenFrameTolerance commandLineTolerance(const CheckOverrides& o) {
  scenario::GoldenFrameTolerance t;
  if (o.threshold) t.threshold = scenario::GoldenSetting<int>{*o.threshold, {}};
  if (o.maxShare) t.maxShare = scenario::GoldenSetting<double>{*o.maxShare, {}};
  return t;
}

}  // namespace

std::vector<LookSetting> lookSettingsOf(const scenario::GoldenRenderSettings& r) {
  std::vector<LookSetting> settings;
  if (r.size)
    settings.push_back({"--size", fmt::format("{}x{}", r.size->value.first, r.size->value.second), r.size->at});
  if (r.msaa) settings.push_back({"--msaa", fmt::format("{}", r.msaa->value), r.msaa->at});
  if (r.theme) settings.push_back({"--theme", r.theme->value, r.theme->at});
  if (r.raster) settings.push_back({"--raster", r.raster->value, r.raster->at});
  if (r.background) settings.push_back({"--background", r.background->value, r.background->at});
  return settings;
}

void checkRenderSettings(const GoldenManifest& manifest) {
  auto check = [&](const scenario::GoldenRenderSettings& r) {
    for (const LookSetting& setting : lookSettingsOf(r)) {
      const render::LookOption& option = render::lookOption(setting.flag);
      render::RenderOptions scratch;
      if (!option.read(setting.text, scratch)) {
        scenario::failInManifest(manifest, setting.at,
                                 fmt::format("expected {}, got {}", option.expected, input::quotedValue(setting.text)));
      }
    }
  };
  check(manifest.defaultRender);
  for (const GoldenEntry& e : manifest.frames) check(e.render);
}

render::RenderOptions frameLookOf(const GoldenManifest& manifest, const GoldenEntry& entry,
                                  const CheckOverrides& overrides, std::pair<int, int> scenarioSize) {
  render::RenderOptions look;
  look.width = scenarioSize.first;
  look.height = scenarioSize.second;
  const scenario::GoldenRenderSettings laid = scenario::renderSettingsOf(manifest, entry, commandLineRender(overrides));
  for (const LookSetting& setting : lookSettingsOf(laid)) {
    const render::LookOption& option = render::lookOption(setting.flag);
    if (!option.read(setting.text, look)) {
      throw std::invalid_argument(fmt::format("{}: expected {}, got {}", setting.at.keyPath, option.expected,
                                              input::quotedValue(setting.text)));
    }
  }
  return look;
}

render::CompareTolerance compareToleranceOf(const GoldenManifest& manifest, const GoldenEntry& entry,
                                            const CheckOverrides& overrides) {
  const scenario::GoldenFrameTolerance laid =
      scenario::frameToleranceOf(manifest, entry, commandLineTolerance(overrides));
  render::CompareTolerance t;
  if (laid.threshold) t.threshold = laid.threshold->value;
  if (laid.maxShare) t.maxShare = laid.maxShare->value;
  return t;
}

StateTolerance stateCompareToleranceOf(const GoldenManifest& manifest, const GoldenEntry& entry) {
  const scenario::GoldenStateToleranceValues v = scenario::stateToleranceOf(manifest, entry);
  return {v.position, v.velocity, v.angle, v.omega};
}

}  // namespace particles::golden
