#pragma once
// The `style` section and render.view's camera modes (docs/scenarios.md, "Style" and "Render"),
// read into style::Style and style::ViewStyle with every name resolved to indices, and a style
// file (`render --style FILE`) merged over the section before anything is read. Internal to the
// scenario loader.

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scenario/references.hpp"
#include "scenario/scenario.hpp"
#include "scenario/yaml_reader.hpp"
#include "style/style.hpp"
#include "style/view.hpp"

namespace particles::scenario::detail {

// What the scene holds, for a colour bar: it explains a class of shapes the scene has.
struct ShapeCounts {
  long long particles = 0, springs = 0, bodies = 0;
};

// The `style` section (absent: a plain style), read once every name is declared: selections
// resolve their references against `names`.
style::Style readStyle(const std::optional<Value>& section, const NamedObjects& names, const ShapeCounts& counts);

// The keys render.view takes: the fixed view's center and height, and the camera modes'.
const std::vector<std::string_view>& viewKeys();

// render.view's camera: fixed unless one of fit, follow and keys is given; `start` holds the view's
// center and height as read (the fixed mode's, and the first key's defaults).
style::ViewStyle readViewStyle(const std::optional<Value>& view, const NamedObjects& names,
                               const RenderSettings& start);

// Merges the style file's map over root["style"]: a key both have whose values are both maps is
// merged the same way, any other key of the file replaces the scenario's. Returns the canonical
// key paths it wrote, each with the style file's name (Source::fromFiles). Throws ScenarioError
// naming the style file when it is not one map of keys, or past `limit`.
std::vector<std::pair<std::string, std::string>> mergeStyleFile(YAML::Node root, const StyleFile& styleFile,
                                                                const NodeLimit& limit);

}  // namespace particles::scenario::detail
