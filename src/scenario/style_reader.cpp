// The `style` section, render.view's camera modes and style files (docs/scenarios.md, "Style").
// Every name a style writes (a quantity, a colormap, a colour) is checked against the names the
// style room knows, with the closest one suggested; every selection and camera point resolves
// through the references' machinery, so it names points as forces and constraints do.
#include "scenario/style_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <set>

#include "input/printable_text.hpp"
#include "scenario/style_values.hpp"

namespace particles::scenario::detail {

namespace {

// --- selections and camera points ----------------------------------------------------------------
// Particles and rigid bodies that a selector or the camera's fit names, as indices, and the
// references as written.
struct Selected {
  std::vector<int> particles, bodies;
  std::vector<std::string> written;
};

void sortUnique(std::vector<int>& indices) {
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
}

// A body is selected whole: its style, trail and arrow are the centre of mass's, so an anchor
// (`link0@[0.2, 0]`) would select something that has none.
void refuseAnchor(const Value& ref, const std::string& text) {
  const size_t at = text.find('@');
  if (at == std::string::npos) return;
  ref.fail(fmt::format("reference {} is a point on a rigid body; select the body by its name alone ({})",
                       input::quotedValue(text), input::quotedValue(text.substr(0, at))));
}

// `v`: a reference or a list of them. Particles (one, a grid, a row or a column) where `particles`,
// rigid bodies (by name) where `bodies`.
Selected selectShapes(const Value& v, const NamedObjects& names, bool particles, bool bodies) {
  std::vector<Value> refs;
  if (v.isSequence()) {
    refs = v.items();
    if (refs.empty()) v.fail("expected at least one reference, got an empty list");
  } else {
    refs.push_back(v);
  }
  Selected out;
  for (const Value& ref : refs) {
    if (!ref.isScalar())
      ref.fail(fmt::format("expected a reference (a name, grid[row][col] or #index), {}", ref.found()));
    const std::string text = ref.node().Scalar();
    const PointKind kind = bodies ? PointKind::endpoint : PointKind::particle;
    for (const Endpoint& point : resolvePoints(ref, names, kind, true)) {
      if (point.isParticle() && !particles) {
        ref.fail(
            fmt::format("reference {} names particles; 'bodies' selects rigid bodies (select particles with "
                        "'particles')",
                        input::quotedValue(text)));
      }
      (point.isParticle() ? out.particles : out.bodies).push_back(point.isParticle() ? point.particle : point.body);
    }
    refuseAnchor(ref, text);
    out.written.push_back(text);
  }
  sortUnique(out.particles);
  sortUnique(out.bodies);
  return out;
}

// --- the style section ---------------------------------------------------------------------------
// Two ways of colouring one class of shapes cannot both hold: say which key to drop.
void refuseBothColorings(const MapReader& m) {
  if (m.has("color") && m.has("color_by")) {
    m.optional("color")->fail(
        "'color' and 'color_by' both colour these shapes; give one (a style file or --set clears the other with "
        "null: color: ~)");
  }
}

// The keys the three classes of shapes share: one colour, or a quantity through a colormap over a
// range.
template <class ShapeStyle, class FromName>
void readColoring(const MapReader& m, ShapeStyle& s, std::string_view quantity, FromName fromName,
                  const std::vector<std::string>& known) {
  refuseBothColorings(m);
  if (auto q = m.optional("color_by")) s.colorBy = named(*q, quantity, fromName, known);
  if (auto c = m.optional("colormap")) s.colormap = readColormap(*c);
  if (auto r = m.optional("range")) s.range = readRange(*r);
  if (auto c = m.optional("color")) s.color = readColor(*c);
}

style::ParticleStyle readParticleStyle(const Value& v) {
  const MapReader m(v, {"color_by", "colormap", "range", "radius", "color"});
  style::ParticleStyle p;
  readColoring(m, p, "particle quantity", style::particleQuantityFromName, style::particleQuantityNames());
  if (auto r = m.optional("radius")) p.radius = readLength(*r);
  return p;
}

style::SpringStyle readSpringStyle(const Value& v) {
  const MapReader m(v, {"color_by", "colormap", "range", "width", "color"});
  style::SpringStyle s;
  readColoring(m, s, "spring quantity", style::springQuantityFromName, style::springQuantityNames());
  s.rangeGiven = m.has("range");
  if (auto w = m.optional("width")) s.width = readLength(*w);
  return s;
}

style::BodyStyle readBodyStyle(const Value& v) {
  const MapReader m(v, {"color", "outline", "color_by", "colormap", "range"});
  style::BodyStyle b;
  readColoring(m, b, "body quantity", style::bodyQuantityFromName, style::bodyQuantityNames());
  if (auto c = m.optional("outline")) b.outline = readColor(*c);
  return b;
}

style::TrailStyle readTrail(const Value& v) {
  const MapReader m(v, {"seconds", "width", "color"});
  style::TrailStyle t;
  if (auto s = m.optional("seconds")) {
    if (s->isScalar() && s->node().Scalar() == "all") {
      t.seconds = std::numeric_limits<double>::infinity();
    } else {
      if (!isNumber(*s))
        s->fail(fmt::format("expected a number of seconds > 0, or all (the whole run), {}", s->found()));
      t.seconds = s->positive();
    }
  }
  if (auto w = m.optional("width")) t.width = readLength(*w);
  if (auto c = m.optional("color")) t.color = readColor(*c);
  return t;
}

style::ArrowStyle readArrow(const Value& v) {
  style::ArrowStyle a;
  if (v.isScalar()) {
    a.of = named(v, "arrow quantity", style::arrowQuantityFromName, style::arrowQuantityNames());
    return a;
  }
  if (!v.isMap()) v.fail(fmt::format("expected velocity, force or a map {{of, scale, max, color}}, {}", v.found()));
  const MapReader m(v, {"of", "scale", "max", "color"});
  if (auto q = m.optional("of")) {
    a.of = named(*q, "arrow quantity", style::arrowQuantityFromName, style::arrowQuantityNames());
  }
  if (auto s = m.optional("scale")) a.scale = s->positive();
  if (auto x = m.optional("max")) a.max = readLength(*x);
  if (auto c = m.optional("color")) a.color = readColor(*c);
  return a;
}

style::Selection readSelection(const Value& item, const NamedObjects& names) {
  const MapReader m(item, {"particles", "bodies", "color", "radius", "trail", "arrow", "label"});
  const std::optional<Value> particles = m.optional("particles"), bodies = m.optional("bodies");
  if (particles && bodies) {
    bodies->fail(
        "'particles' and 'bodies' both select; an entry selects one of them (give the other an entry of "
        "its own)");
  }
  if (!particles && !bodies) item.fail("expected 'particles' or 'bodies': what the entry selects");
  style::Selection s;
  if (particles) {
    s.particlesSelector = commandLineText(particles->node());
    s.particles = selectShapes(*particles, names, true, false).particles;
  } else {
    s.bodiesSelector = commandLineText(bodies->node());
    s.bodies = selectShapes(*bodies, names, false, true).bodies;
  }
  if (auto c = m.optional("color")) s.color = readColor(*c);
  if (auto r = m.optional("radius")) {
    if (bodies) r->fail("'radius' is a particle's; a selection of bodies has none (their size is the scenario's)");
    s.radius = readLength(*r);
  }
  if (auto t = m.optional("trail")) s.trail = readTrail(*t);
  if (auto a = m.optional("arrow")) s.arrow = readArrow(*a);
  if (auto l = m.optional("label")) s.label = readLabel(*l);
  return s;
}

// Which classes of shapes are coloured by a quantity (what a colour bar explains), in the order
// a colour bar without `for` looks for one: springs are, by strain, unless one colour is given.
bool colouredByQuantity(const style::Style& s, const ShapeCounts& counts, style::ColorbarSubject subject) {
  switch (subject) {
    case style::ColorbarSubject::particles: return counts.particles > 0 && s.particles.colorBy.has_value();
    case style::ColorbarSubject::springs: return counts.springs > 0 && !s.springs.color;
    case style::ColorbarSubject::bodies: return counts.bodies > 0 && s.bodies.colorBy.has_value();
  }
  return false;
}

// Why a class of shapes has no colour bar to show.
std::string notColouredWhy(const style::Style& s, const ShapeCounts& counts, style::ColorbarSubject subject) {
  const std::string_view name = style::nameOf(subject);
  const long long count = subject == style::ColorbarSubject::particles ? counts.particles
                          : subject == style::ColorbarSubject::springs ? counts.springs
                                                                       : counts.bodies;
  if (count == 0) return fmt::format("the scene has no {}", name);
  if (subject == style::ColorbarSubject::springs && s.springs.color) {
    return "the springs have one colour (style.springs.color), not a quantity's";
  }
  return fmt::format("the {} are not coloured by a quantity (style.{}.color_by is not set)", name, name);
}

std::optional<style::ColorbarStyle> readColorbar(const Value& v, const style::Style& s, const ShapeCounts& counts) {
  style::ColorbarStyle bar;
  std::optional<Value> subject;
  if (v.isMap()) {
    const MapReader m(v, {"for", "label", "position"});
    subject = m.optional("for");
    if (auto l = m.optional("label")) bar.label = readLabel(*l);
    if (auto p = m.optional("position")) {
      bar.position = named(*p, "colour bar position", style::colorbarPositionFromName, style::colorbarPositionNames());
    }
  } else if (!isBoolean(v)) {
    v.fail(fmt::format("expected a map {{for, label, position}}, or true or false, {}", v.found()));
  } else if (!v.boolean()) {
    return std::nullopt;
  }
  if (subject) {
    bar.subject = named(*subject, "colour bar subject", style::colorbarSubjectFromName, style::colorbarSubjectNames());
    if (!colouredByQuantity(s, counts, *bar.subject)) {
      subject->fail(fmt::format("a colour bar explains shapes coloured by a quantity, and {}",
                                notColouredWhy(s, counts, *bar.subject)));
    }
    return bar;
  }
  for (const std::string& name : style::colorbarSubjectNames()) {
    const style::ColorbarSubject candidate = *style::colorbarSubjectFromName(name);
    if (colouredByQuantity(s, counts, candidate)) {
      bar.subject = candidate;
      return bar;
    }
  }
  v.fail(
      "a colour bar explains shapes coloured by a quantity, and none are: set style.particles.color_by or "
      "style.bodies.color_by (springs are coloured by strain unless style.springs.color is given)");
}

// --- render.view -----------------------------------------------------------------------------------
void readFit(const Value& v, const NamedObjects& names, style::ViewStyle& view) {
  view.mode = style::ViewStyle::Mode::fit;
  if (v.isScalar() && v.node().Scalar() == "all") {
    view.fitAll = true;
    return;
  }
  Selected fit = selectShapes(v, names, true, true);
  view.fitNames = std::move(fit.written);
  view.fitParticles = std::move(fit.particles);
  view.fitBodies = std::move(fit.bodies);
}

void readFollow(const Value& v, const NamedObjects& names, style::ViewStyle& view) {
  view.mode = style::ViewStyle::Mode::follow;
  const Endpoint point = resolvePoints(v, names, PointKind::endpoint, false).front();
  const std::string text = v.node().Scalar();
  refuseAnchor(v, text);
  view.followName = text;
  view.followParticle = point.isParticle() ? point.particle : -1;
  view.followBody = point.isParticle() ? -1 : point.body;
}

void readKeys(const Value& v, const RenderSettings& start, style::ViewStyle& view) {
  view.mode = style::ViewStyle::Mode::keys;
  const std::vector<Value> items = v.items();
  if (items.empty()) v.fail("expected at least one key {t, center, height}, got an empty list");
  // A key leaves out what does not change: the key before's center and height (the view's, first).
  Vec2 center = start.viewCenter;
  double height = start.viewHeight;
  for (const Value& item : items) {
    const MapReader k(item, {"t", "center", "height"});
    const Value t = k.required("t");
    const double time = t.nonNegative();
    if (!view.keys.empty() && !(time > view.keys.back().t)) {
      t.fail(fmt::format("expected t > {} (the key before's): keys are in increasing time, got {}",
                         formatNumber(view.keys.back().t), formatNumber(time)));
    }
    if (auto c = k.optional("center")) center = c->vec2();
    if (auto h = k.optional("height")) height = h->positive();
    view.keys.push_back({time, center, height});
  }
}

// Merges `given` (the style file's map at `path`) into `into`, the scenario's map there.
void mergeMaps(YAML::Node into, const YAML::Node& given, const std::string& path, const std::string& file,
               std::vector<std::pair<std::string, std::string>>& written) {
  std::set<std::string> seen;
  for (auto it = given.begin(); it != given.end(); ++it) {
    const YAML::Node key = it->first, value = it->second;
    const YAML::Mark at = key.Mark();
    if (!key.IsScalar())
      throw ScenarioError(file, at.line + 1, at.column + 1, path, "expected a key name, got a list or map as key");
    const std::string name = key.Scalar(), keyPath = path + "." + name;
    if (!seen.insert(name).second) {
      throw ScenarioError(file, at.line + 1, at.column + 1, keyPath,
                          fmt::format("duplicate key {}", input::quotedValue(name)));
    }
    const YAML::Node& scenarioMap = into;  // read without adding the key
    const YAML::Node existing = scenarioMap[name];
    if (existing.IsDefined() && existing.IsMap() && value.IsMap()) {
      mergeMaps(existing, value, keyPath, file, written);
      continue;
    }
    // The style file's own key node, so that a key without a value is still placed in its file.
    into.remove(name);
    into.force_insert(key, value);
    written.emplace_back(keyPath, file);
  }
}

}  // namespace

const std::vector<std::string_view>& viewKeys() {
  static const std::vector<std::string_view> keys = {"center", "height",    "fit", "margin",
                                                     "follow", "smoothing", "keys"};
  return keys;
}

style::Style readStyle(const std::optional<Value>& section, const NamedObjects& names, const ShapeCounts& counts) {
  style::Style s;
  if (!section) return s;
  const MapReader m(*section, {"particles", "springs", "bodies", "colorbar", "title", "scale_bar", "select"});
  if (auto v = m.optional("particles")) s.particles = readParticleStyle(*v);
  if (auto v = m.optional("springs")) s.springs = readSpringStyle(*v);
  if (auto v = m.optional("bodies")) s.bodies = readBodyStyle(*v);
  if (auto v = m.optional("title")) s.title = readLabel(*v);
  if (auto v = m.optional("scale_bar")) s.scaleBar = v->boolean();
  if (auto v = m.optional("select")) {
    for (const Value& item : v->items()) s.select.push_back(readSelection(item, names));
  }
  if (auto v = m.optional("colorbar")) s.colorbar = readColorbar(*v, s, counts);
  return s;
}

style::ViewStyle readViewStyle(const std::optional<Value>& view, const NamedObjects& names,
                               const RenderSettings& start) {
  style::ViewStyle out;
  if (!view) return out;
  const MapReader m(*view, viewKeys());
  std::optional<std::string_view> mode;
  for (const std::string_view key : {"fit", "follow", "keys"}) {
    const std::optional<Value> v = m.optional(key);
    if (!v) continue;
    if (mode) {
      v->fail(fmt::format("'{}' and '{}' are two camera modes; give one of fit, follow and keys", *mode, key));
    }
    mode = key;
  }
  if (auto v = m.optional("margin")) {
    if (mode != "fit") v->fail("'margin' is the fit mode's: it needs 'fit'");
    out.margin = v->nonNegative();
  }
  if (auto v = m.optional("smoothing")) {
    if (mode != "follow") v->fail("'smoothing' is the follow mode's: it needs 'follow'");
    out.smoothing = v->nonNegative();
  }
  if (auto v = m.optional("fit")) readFit(*v, names, out);
  if (auto v = m.optional("follow")) readFollow(*v, names, out);
  if (auto v = m.optional("keys")) readKeys(*v, start, out);
  return out;
}

std::vector<std::pair<std::string, std::string>> mergeStyleFile(YAML::Node root, const StyleFile& styleFile,
                                                                const NodeLimit& limit) {
  const YAML::Node given = loadOneDocument(styleFile.text, styleFile.file, nullptr, limit,
                                           "a style: a map of the style section's keys (particles, springs, …)");
  if (!given.IsMap()) {
    const YAML::Mark m = given.Mark();
    throw ScenarioError(styleFile.file, m.line + 1, m.column + 1, "",
                        "expected a style: a map of the style section's keys (particles, springs, bodies, colorbar, "
                        "title, scale_bar, select), as under `style:` in a scenario");
  }
  std::vector<std::pair<std::string, std::string>> written;
  const YAML::Node& scenarioRoot = root;
  if (const YAML::Node style = scenarioRoot["style"]; style.IsDefined() && style.IsMap()) {
    mergeMaps(style, given, "style", styleFile.file, written);
  } else {
    root["style"] = given;
    written.emplace_back("style", styleFile.file);
  }
  return written;
}

}  // namespace particles::scenario::detail
