#include "scenario/schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/grid.hpp"
#include "core/integrators.hpp"
#include "core/system.hpp"
#include "scenario/golden_manifest.hpp"
#include "scenario/scenario.hpp"
#include "scenario/schema_parts.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

using namespace schema_parts;

std::string typeText(ParamType type) {
  switch (type) {
    case ParamType::number: return "number";
    case ParamType::vec2: return "[x, y]";
    case ParamType::particle:
    case ParamType::endpoint: return "reference";
    case ParamType::particles:
    case ParamType::endpoints: return "reference or list";
    case ParamType::path: return "list of [x, y]";
  }
  return "?";
}

std::string vec2Text(const Vec2& v) {
  return fmt::format("[{}, {}]", detail::formatNumber(v.x()), detail::formatNumber(v.y()));
}

std::string defaultText(const ParamSpec& p) {
  if (p.required) return "required";
  if (!p.insteadOf.empty()) return fmt::format("required, or `{}`", p.insteadOf);
  if (!p.defaultText.empty()) return std::string(p.defaultText);
  if (p.defaultNumber) return detail::formatNumber(*p.defaultNumber);
  if (p.defaultVec2) return vec2Text(*p.defaultVec2);
  return "none";
}

std::string allowedText(const ParamSpec& p) {
  std::string text = detail::boundsText(p.min, p.max);
  if (!p.note.empty()) text += (text.empty() ? "" : "; ") + std::string(p.note);
  return text;
}

Json paramSchema(const ParamSpec& p) {
  Json j;
  switch (p.type) {
    case ParamType::number: j = number(p.min, p.max); break;
    case ParamType::vec2: j = vec2(); break;
    case ParamType::particle:
    case ParamType::endpoint: j = reference(); break;
    case ParamType::particles:
    case ParamType::endpoints: j = referenceOrList(); break;
    case ParamType::path: j = {{"type", "array"}, {"items", vec2()}, {"minItems", 1}}; break;
  }
  std::vector<std::string> parts;
  if (!p.unit.empty()) parts.push_back(fmt::format("in {}", p.unit));
  if (!p.note.empty()) parts.emplace_back(p.note);
  if (!p.required) parts.push_back(fmt::format("default: {}", defaultText(p)));
  j = withDescription(std::move(j), fmt::format("{}", fmt::join(parts, "; ")));
  if (p.defaultNumber) j = withDefault(std::move(j), *p.defaultNumber);
  if (p.defaultVec2) j = withDefault(std::move(j), vec2Value(*p.defaultVec2));
  return j;
}

Json kindSchema(const KindSpec& kind, bool typed) {
  std::vector<std::pair<std::string, Json>> props;
  std::vector<std::string> required;
  if (typed) {
    props.emplace_back("type", Json{{"const", kind.type}});
    required.emplace_back("type");
  }
  Json eitherOr = Json::array();
  for (const ParamSpec& p : kind.params) {
    props.emplace_back(std::string(p.key), paramSchema(p));
    if (p.required) required.emplace_back(p.key);
    if (!p.insteadOf.empty() && p.key < p.insteadOf) {  // once per pair
      eitherOr.push_back({{"required", {p.key}}});
      eitherOr.push_back({{"required", {p.insteadOf}}});
    }
  }
  Json j = withDescription(object(props, required), std::string(kind.summary));
  if (!eitherOr.empty()) j["oneOf"] = eitherOr;
  return j;
}

Json kindSectionSchema(const KindSection& section) {
  const std::vector<const KindSpec*> kinds = kindsOf(section.key);
  if (!section.typed) return {{"type", "array"}, {"items", kindSchema(*kinds.front(), false)}};
  Json types = Json::array(), cases = Json::array();
  for (const KindSpec* k : kinds) {
    types.push_back(k->type);
    cases.push_back({{"if", {{"properties", {{"type", {{"const", k->type}}}}}, {"required", {"type"}}}},
                     {"then", kindSchema(*k, true)}});
  }
  Json item = {{"type", "object"},
               {"required", {"type"}},
               {"properties", {{"type", {{"enum", types}, {"description", "the kind of entry"}}}}},
               {"allOf", cases}};
  return {{"type", "array"}, {"items", item}};
}

Json simulationSchema() {
  const SimulationSettings d;
  Json integrators = Json::array();
  for (Integrator i : allIntegrators()) integrators.push_back(integratorName(i));
  return object(
      {{"integrator", withDefault({{"enum", integrators}}, integratorName(d.integrator))},
       {"dt", withDefault(withDescription(number(Bound{0, false}), "time step, s"), d.dt)},
       {"duration", withDefault(withDescription(number(Bound{0, false}), "simulated seconds"), d.duration)},
       {"implicit_solver",
        withDefault(withDescription({{"enum", {"auto", "direct", "cg"}}},
                                    "backward_euler's and bdf2's linear solve: a sparse LDLT factorisation (direct), "
                                    "conjugate gradients (cg), or CG until a step needs more iterations than "
                                    "the direct solve costs at that size, then direct (auto)"),
                    implicitSolverName(d.implicitSolver))}},
      {});
}

Json renderSchema() {
  const RenderSettings d;
  const Json view = viewSchema(d);
  return object({{"size", withDefault(withDescription(pairOf(wholeNumber(1, kMaxImageSide)), "[width, height] in px"),
                                      Json::array({d.width, d.height}))},
                 {"fps", withDefault(withDescription(number(Bound{kMinFps, true}, Bound{kMaxFps, true}),
                                                     "frames per simulated second"),
                                     d.fps)},
                 {"view", view}},
                {});
}

Json particleSchema() {
  const ParticleSpec d;
  return object({{"name", name()},
                 {"pos", withDescription(vec2(), "m")},
                 {"vel", withDefault(withDescription(vec2(), "m/s"), vec2Value(d.vel))},
                 {"mass", withDefault(withDescription(number(Bound{0, false}), "kg"), d.mass)},
                 {"fixed", withDefault({{"type", "boolean"}}, d.fixed)}},
                {"pos"});
}

Json gridSchema() {
  const GridSpec d;
  const Json stiffness = {{"oneOf", Json::array({number(Bound{0, true}), pairOf(number(Bound{0, true}))})},
                          {"description", "N/m: a number, or [top, bottom] varying linearly with height"}};
  const Json family = object({{"ks", stiffness}, {"kd", withDefault(withDescription(number(Bound{0, true}), "N·s/m"), 0)}},
                             {"ks"});
  return object({{"name", name()},
                 {"origin", withDefault(withDescription(vec2(), "position of row 0, column 0, m"), vec2Value(d.origin))},
                 {"size", withDescription(pairOf(wholeNumber(1, kMaxGridSide)),
                                          "[columns, rows]; the scene's particles count toward --limit particles")},
                 {"spacing", withDefault(withDescription(pairOf(number(Bound{0, false})), "m"), vec2Value(d.spacing))},
                 {"mass", withDefault(withDescription(number(Bound{0, false}), "kg per particle"), d.mass)},
                 {"springs", object({{"structural", family}, {"shear", family}, {"flexion", family}}, {})}},
                {"name", "size"});
}

Json bodySchema() {
  const RigidBodySpec d;
  return object({{"name", name()},
                 {"pos", withDescription(vec2(), "centre of mass, m")},
                 {"size", withDescription(pairOf(number(Bound{0, false})), "[width, height], m")},
                 {"angle", withDefault(withDescription(number(), "rad, counter-clockwise"), d.angle)},
                 {"mass", withDefault(withDescription(number(Bound{0, false}), "kg"), d.mass)},
                 {"vel", withDefault(withDescription(vec2(), "m/s"), vec2Value(d.vel))},
                 {"omega", withDefault(withDescription(number(), "rad/s"), d.omega)}},
                {"pos", "size"});
}

// A golden manifest's parts (golden_manifest.cpp reads them).
// A frame side from 1 to 16384 px, leading zeros allowed, as the loader reads `WxH`.
constexpr const char* kFrameSidePattern = "0*([1-9][0-9]{0,3}|1[0-5][0-9]{3}|16[0-2][0-9]{2}|163[0-7][0-9]|1638[0-4])";
static_assert(kMaxImageSide == 16'384, "kFrameSidePattern spells out kMaxImageSide");

Json goldenRenderSchema() {
  Json msaa = Json::array();
  for (int n : kGoldenSampleCounts) msaa.push_back(n);
  const std::string side = kFrameSidePattern;
  return withDescription(
      object({{"size", withDescription({{"type", "string"}, {"pattern", "^" + side + "[xX]" + side + "$"}},
                                       fmt::format("WIDTHxHEIGHT in px, each 1 to {}", kMaxImageSide))},
              {"msaa", withDescription({{"enum", msaa}}, "samples per pixel (1: off)")},
              {"theme", withDescription(text(), "the renderer's theme: dark or light")},
              {"background", withDescription(text(), "theme or transparent")},
              {"raster", withDescription(text(), "auto, triangles, tiles, resident or cpu")}},
             {}),
      "as `particles render`'s options; what is not set is render's default");
}

Json goldenToleranceSchema() {
  return withDescription(
      object(
          {{"threshold", withDescription(wholeNumber(0, 255), "the largest channel difference that is no difference")},
           {"max_share",
            withDescription(number(Bound{0, true}, Bound{1, true}), "the share of pixels that may differ")}},
          {}),
      "as `particles compare --threshold --max-share`");
}

Json goldenStateToleranceSchema() {
  auto bound = [](const char* what) { return withDescription(number(Bound{0, true}), what); };
  return withDescription(
      object({{"position", bound("m")}, {"velocity", bound("m/s")}, {"angle", bound("rad")}, {"omega", bound("rad/s")}},
             {}),
      "absolute tolerances: a quantity differs when |actual − expected| exceeds its own");
}

Json goldenEntrySchema(bool frames) {
  const std::string placeholders = frames ? "|\\{scenario\\}|\\{time\\}" : "|\\{scenario\\}";
  const Json name = {{"type", "string"},
                     {"pattern", "^([A-Za-z0-9_+-]" + placeholders + ")([A-Za-z0-9._+-]" + placeholders + ")*$"},
                     {"description", frames ? "the frames' names (NAME.png): {scenario} is the scenario file's stem, "
                                              "{time} the time as written"
                                            : "the state's name (NAME.csv): {scenario} is the scenario file's stem"},
                     {"default", frames ? "{scenario}_t{time}" : "{scenario}"}};
  const Json setValue = {{"type", Json::array({"string", "number", "boolean", "array"})}};
  const Json set = {
      {"oneOf", Json::array({{{"type", "object"}, {"additionalProperties", setValue}},
                             {{"type", "array"}, {"items", {{"type", "string"}, {"pattern", "^[^=]+=.+$"}}}}})},
      {"description", "--set overrides, in order: {PATH: VALUE, …} or [PATH=VALUE, …]"}};
  std::vector<std::pair<std::string, Json>> properties = {
      {"scenario", withDescription(text(), "the scenario file, relative to the manifest")},
      {"times", withDescription({{"type", "array"},
                                 {"items", number(Bound{0, true})},
                                 {"minItems", 1},
                                 {"maxItems", kMaxGoldenChecks},
                                 {"uniqueItems", true}},
                                "seconds of simulated time")},
      {"name", name},
      {"set", set}};
  if (frames) {
    properties.emplace_back("render", goldenRenderSchema());
    properties.emplace_back("tolerance", goldenToleranceSchema());
    properties.emplace_back("expect",
                            withDefault(withDescription({{"enum", {"match", "differ"}}},
                                                        "differ: a control, passing only when the frame differs"),
                                        "match"));
    properties.emplace_back(
        "reference", withDescription(text(), "compare with the reference NAME.png of another frame (one time only)"));
  } else {
    properties.emplace_back("state_tolerance", goldenStateToleranceSchema());
  }
  return object(properties, {"scenario", "times"});
}

}  // namespace

std::string scenarioJsonSchema() {
  std::vector<std::pair<std::string, Json>> sections = {
      {"name", withDescription(text(), "the scenario's name")},
      {"description", withDescription({{"type", "string"}}, "one line for people")},
      {"simulation", simulationSchema()},
      {"render", renderSchema()},
      {"particles", listOf(particleSchema())},
      {"grids", listOf(gridSchema())},
      {"rigid_bodies", listOf(bodySchema())},
  };
  for (const KindSection& section : kindSections()) sections.emplace_back(section.key, kindSectionSchema(section));
  sections.emplace_back("style", styleSchema());
  Json schema = {{"$schema", "http://json-schema.org/draft-07/schema#"},
                 {"title", "particles scenario"},
                 {"description", "A particles scenario file (docs/scenarios.md)"}};
  schema.update(object(sections, {"name"}));
  schema["definitions"] = styleDefinitions();
  return schema.dump(2) + "\n";
}

std::string goldenManifestJsonSchema() {
  auto entries = [](bool frames) {
    return withDescription({{"type", "array"}, {"items", goldenEntrySchema(frames)}, {"maxItems", kMaxGoldenChecks}},
                           frames ? "frames rendered and compared with references/NAME.png"
                                  : "simulation states compared with references/NAME.csv");
  };
  const Json defaults = object({{"render", goldenRenderSchema()},
                                {"tolerance", goldenToleranceSchema()},
                                {"state_tolerance", goldenStateToleranceSchema()}},
                               {});
  Json schema = {{"$schema", "http://json-schema.org/draft-07/schema#"},
                 {"title", "particles golden manifest"},
                 {"description",
                  "Which frames and states of which scenarios `particles golden check` compares with "
                  "stored references (golden/README.md)"}};
  schema.update(object({{"references", withDefault(withDescription(text(),
                                                                   "the references' folder, relative to the "
                                                                   "manifest"),
                                                   ".")},
                        {"defaults", withDescription(defaults, "for every entry that does not set its own")},
                        {"frames", entries(true)},
                        {"states", entries(false)}},
                       {}));
  // At least one check: frames or states, not empty.
  schema["anyOf"] = Json::array();
  for (const char* list : {"frames", "states"}) {
    schema["anyOf"].push_back({{"required", {list}}, {"properties", {{list, {{"type", "array"}, {"minItems", 1}}}}}});
  }
  return schema.dump(2) + "\n";
}

std::string kindDocsTable(const KindSpec& kind) {
  std::vector<std::array<std::string, 5>> rows = {{"key", "type", "unit", "default", "allowed"}};
  for (const ParamSpec& p : kind.params) {
    rows.push_back({fmt::format("`{}`", p.key), typeText(p.type), std::string(p.unit), defaultText(p), allowedText(p)});
  }
  // Pad by characters, not bytes: units and bounds hold ≥, ², · and the like.
  auto width = [](const std::string& s) {
    return size_t(std::count_if(s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
  };
  std::array<size_t, 5> widths{};
  for (const auto& row : rows) {
    for (size_t c = 0; c < 5; ++c) widths[c] = std::max(widths[c], width(row[c]));
  }
  std::string out;
  auto line = [&](const std::array<std::string, 5>& row) {
    out += "|";
    for (size_t c = 0; c < 5; ++c) out += " " + row[c] + std::string(widths[c] - width(row[c]), ' ') + " |";
    out += "\n";
  };
  line(rows[0]);
  out += "|";
  for (size_t c = 0; c < 5; ++c) out += std::string(widths[c] + 2, '-') + "|";
  out += "\n";
  for (size_t r = 1; r < rows.size(); ++r) line(rows[r]);
  return out;
}

}  // namespace particles::scenario
