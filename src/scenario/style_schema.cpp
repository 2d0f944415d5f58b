// The JSON Schema of the `style` section and of render.view, from the names the style room knows
// (style/style.hpp, color.hpp, colormap.hpp) and the defaults of its structs, as style_reader.cpp
// reads them.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "scenario/schema_parts.hpp"
#include "style/color.hpp"
#include "style/colormap.hpp"
#include "style/style.hpp"
#include "style/view.hpp"

namespace particles::scenario::schema_parts {

namespace {

Json oneOf(std::vector<Json> cases) {
  Json all = Json::array();
  for (Json& c : cases) all.push_back(std::move(c));
  return {{"oneOf", all}};
}

Json names(const std::vector<std::string>& known) {
  return {{"enum", known}};
}

Json quantity(const std::vector<std::string>& known) {
  return withDescription(names(known), "the quantity that colours these shapes through the colormap");
}

Json colormap() {
  return withDescription(names(style::colormapNames()), "matplotlib's maps; `_r` reversed");
}

// Written once, in the schema's definitions: the 148 names would otherwise be repeated at every key.
Json color() {
  return {{"$ref", "#/definitions/color"}};
}

Json length() {
  return withDescription(
      oneOf({number(Bound{0, false}),
             {{"type", "string"}, {"pattern", "^[+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][+-]?[0-9]+)?(px|m)$"}}}),
      "3px: pixels; 0.02m or a bare number: metres of the world; > 0");
}

// A default length as a scenario writes it.
Json lengthText(const style::Length& l) {
  return fmt::format("{}{}", l.value, l.pixels ? "px" : "m");
}

Json range(const style::Range& d) {
  const Json bounds =
      object({{"min", number()}, {"max", number()}, {"scale", withDefault(names({"linear", "log"}), "linear")}}, {});
  Json j = withDescription(oneOf({{{"const", "auto"}}, pairOf(number()), bounds}),
                           "the values the colormap spans: auto (over every frame shown), [lo, hi], or "
                           "{min, max, scale} (min and max both or neither: then auto); lo < hi, and lo > 0 on a "
                           "log scale");
  return withDefault(std::move(j), d.automatic ? Json("auto") : Json::array({d.lo, d.hi}));
}

// One line of printable text: no control characters (C0, DEL, C1), at most kMaxLabelLength
// characters (JSON Schema counts code points, as the loader does).
Json label() {
  return {{"type", "string"},
          {"minLength", 1},
          {"maxLength", style::kMaxLabelLength},
          {"pattern", "^[^\\u0000-\\u001f\\u007f-\\u009f]*$"},
          {"description", "one line of printable text"}};
}

Json particles() {
  const style::ParticleStyle d;
  return object({{"color_by", quantity(style::particleQuantityNames())},
                 {"colormap", withDefault(colormap(), style::nameOf(d.colormap))},
                 {"range", range(d.range)},
                 {"radius", withDescription(length(), "default: render --particle-radius (4px)")},
                 {"color", withDescription(color(), "every particle's colour, when not coloured by a quantity")}},
                {});
}

Json springs() {
  const style::SpringStyle d;
  return object(
      {{"color_by", withDefault(quantity(style::springQuantityNames()), std::string(style::nameOf(d.colorBy)))},
       {"colormap", withDescription(colormap(), "default: the theme's three strain colours")},
       {"range", range(d.range)},
       {"width", withDescription(length(), "default: 1.5px")},
       {"color", withDescription(color(), "one colour for every spring, instead of a quantity's")}},
      {});
}

Json bodies() {
  const style::BodyStyle d;
  return object({{"color", withDescription(color(), "the fill, when not coloured by a quantity")},
                 {"outline", color()},
                 {"color_by", quantity(style::bodyQuantityNames())},
                 {"colormap", withDefault(colormap(), style::nameOf(d.colormap))},
                 {"range", range(d.range)}},
                {});
}

Json colorbar() {
  const style::ColorbarStyle d;
  const Json bar =
      object({{"for", withDescription(names(style::colorbarSubjectNames()),
                                      "the shapes it explains; default: the first of these coloured by a quantity")},
              {"label", withDescription(label(), "default: the quantity's name and unit")},
              {"position", withDefault(names(style::colorbarPositionNames()), std::string(style::nameOf(d.position)))}},
             {});
  return oneOf({{{"type", "boolean"}}, bar});
}

Json selection() {
  const style::TrailStyle trail;
  const style::ArrowStyle arrow;
  const Json seconds = oneOf({number(Bound{0, false}), {{"const", "all"}}});
  const Json trailMap = object({{"seconds", withDefault(withDescription(seconds, "how far back, s"), "all")},
                                {"width", withDefault(length(), lengthText(trail.width))},
                                {"color", withDescription(color(), "default: the shape's own")}},
                               {});
  const Json arrowMap = object(
      {{"of", withDefault(names(style::arrowQuantityNames()), std::string(style::nameOf(arrow.of)))},
       {"scale", withDefault(withDescription(number(Bound{0, false}), "metres of arrow per unit (m per m/s, m per N)"),
                             arrow.scale)},
       {"max", withDefault(withDescription(length(), "the longest arrow drawn"), lengthText(arrow.max))},
       {"color", color()}},
      {});
  Json j = object({{"particles", withDescription(referenceOrList(), "the particles selected")},
                   {"bodies", withDescription(referenceOrList(), "the rigid bodies selected, by name")},
                   {"color", color()},
                   {"radius", withDescription(length(), "particles only")},
                   {"trail", trailMap},
                   {"arrow", oneOf({names(style::arrowQuantityNames()), arrowMap})},
                   {"label", label()}},
                  {});
  j["oneOf"] = Json::array({{{"required", {"particles"}}}, {{"required", {"bodies"}}}});
  return withDescription(std::move(j), "particles or bodies (one of them) and their own look; later entries win");
}

}  // namespace

Json styleDefinitions() {
  const Json color = withDescription(
      oneOf({names(style::colorNames()), {{"type", "string"}, {"pattern", "^#([0-9A-Fa-f]{6}|[0-9A-Fa-f]{8})$"}}}),
      "a CSS colour name or #rrggbb / #rrggbbaa (quote it: # starts a YAML comment)");
  return {{"color", color}};
}

Json styleSchema() {
  return withDescription(object({{"particles", particles()},
                                 {"springs", springs()},
                                 {"bodies", bodies()},
                                 {"colorbar", colorbar()},
                                 {"title", label()},
                                 {"scale_bar", withDefault({{"type", "boolean"}}, false)},
                                 {"select", listOf(selection())}},
                                {}),
                         "what a frame shows beyond its geometry (docs/scenarios.md, Style)");
}

Json viewSchema(const RenderSettings& defaults) {
  const style::ViewStyle d;
  const Json key = object({{"t", withDescription(number(Bound{0, true}), "s, increasing from key to key")},
                           {"center", withDescription(vec2(), "m; default: the key before's (the view's, first)")},
                           {"height", withDescription(number(Bound{0, false}), "m; default: the key before's")}},
                          {"t"});
  Json j = object(
      {{"center",
        withDefault(withDescription(vec2(), "world point at the fixed frame's centre, m (the first key's by default)"),
                    vec2Value(defaults.viewCenter))},
       {"height",
        withDefault(withDescription(number(Bound{0, false}),
                                    "world height shown vertically, m (fixed, follow; the first key's by default)"),
                    defaults.viewHeight)},
       {"fit", withDescription(oneOf({{{"const", "all"}}, referenceOrList()}),
                               "keep these points (all: every one) in the frame over the whole run")},
       {"margin", withDefault(withDescription(number(Bound{0, true}),
                                              "fit's room on each side of the points, a share of their extent"),
                              d.margin)},
       {"follow", withDescription(reference(), "a particle or a rigid body the camera follows")},
       {"smoothing",
        withDefault(withDescription(number(Bound{0, true}), "follow's time constant, s (0: locked)"), d.smoothing)},
       {"keys", withDescription({{"type", "array"}, {"items", key}, {"minItems", 1}},
                                "keyframes of the centre and height, eased between")}},
      {});
  // One camera mode at most.
  j["not"] = {{"anyOf", Json::array({{{"required", {"fit", "follow"}}},
                                     {{"required", {"fit", "keys"}}},
                                     {{"required", {"follow", "keys"}}}})}};
  return j;
}

}  // namespace particles::scenario::schema_parts
