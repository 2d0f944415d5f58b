#include "render/styled_run.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/errors.hpp"
#include "render/frame_mesh.hpp"
#include "style/colormap.hpp"

namespace particles::render {

namespace {

Rgba rgbaOf(const style::Color& c) {
  return {c.r, c.g, c.b, c.a};
}

// A length in pixels at `pixelsPerUnit`.
float pixelsOf(const style::Length& length, double pixelsPerUnit) {
  return float(length.pixels ? length.value : length.value * pixelsPerUnit);
}

// The arrows' colour where a selection gives none: warm, and visible on either theme's background.
Rgba defaultArrowColor(ThemeName theme) {
  return theme == ThemeName::dark ? Rgba(255, 196, 61) : Rgba(204, 85, 0);
}

// The name and unit a colour bar's label shows when the style gives none: "speed (m/s)".
std::string quantityLabel(std::string_view name, std::string_view unit) {
  std::string label(name);
  std::replace(label.begin(), label.end(), '_', ' ');
  if (!unit.empty()) label += " (" + std::string(unit) + ")";
  return label;
}

// Steps of the trails drawn closer than this (pixels) to the last point kept are skipped: a point
// per time step is far more than a smooth line needs where the body moves slowly.
constexpr double kTrailMinStepPx = 0.5;

}  // namespace

StyledRun::StyledRun(const style::Style& style, const style::ViewStyle& view, const Camera& camera,
                     const RenderOptions& look, double dt, long steps)
    : StyledRun(style, view, camera, look, nullptr) {
  if (StyleHistory::needed(style, view)) {
    ownHistory_ = std::make_unique<StyleHistory>(style, view, camera, dt, steps);
    history_ = ownHistory_.get();
  }
}

StyledRun::StyledRun(const style::Style& style, const style::ViewStyle& view, const Camera& camera,
                     const RenderOptions& look, const StyleHistory* history)
    : style_(style),
      look_(look),
      palette_(theme(look.themeName)),
      camera_(view, {camera.center, camera.height}, double(look.width) / double(look.height)),
      unfitted_(camera_),
      follows_(view.mode == style::ViewStyle::Mode::follow),
      history_(history),
      detail_(style::drawDetailFor(style)),
      fixed_(camera) {
  if (style.particles.radius) {
    const style::Length& r = *style.particles.radius;
    look_.particleRadius = {r.value, r.pixels ? Length::Unit::pixels : Length::Unit::world};
  }
  if (style.springs.width) look_.springWidthPx = pixelsOf(*style.springs.width, double(look.height) / camera.height);
  styled_ = !style.isPlain() || view.mode != style::ViewStyle::Mode::fixed;
  setScales(style::StyleRanges(style_));
}

StyleHistory* StyledRun::ownHistory(std::string_view call) {
  if (history_ != ownHistory_.get()) {
    throw std::logic_error(std::string(call) + ": this StyledRun draws from a history fed elsewhere");
  }
  return ownHistory_.get();
}

bool StyledRun::needsPass() const {
  return style::StyleRanges::needed(style_) || camera_.needsPass();
}

void StyledRun::runPass(System& system, Integrator integrator, double dt, const std::vector<double>& times) {
  const System::Checkpoint start = system.checkpoint();
  style::StyleRanges ranges(style_);
  {
    Stepper stepper(system, integrator, dt);
    Drawing frame;
    for (double t : times) {
      if (t > system.time()) stepper.advanceTo(t);
      drawFrame(system, frame, SpringDetail::topology);
      ranges.add(frame);
      camera_.observe(frame);
    }
  }
  system.restore(start);
  camera_.endPass();
  setScales(ranges);
}

void StyledRun::fitTo(const Drawing& frame) {
  if (!needsPass()) return;
  camera_ = unfitted_;  // the frame's own box, not grown by the frames fitted before
  style::StyleRanges ranges(style_);
  ranges.add(frame);
  camera_.observe(frame);
  camera_.endPass();
  setScales(ranges);
}

void StyledRun::setScales(const style::StyleRanges& ranges) {
  particleScale_ = style::scaleOf(style_.particles.range, ranges.particles());
  springScale_ = style::scaleOf(style::effectiveRange(style_.springs), ranges.springs());
  bodyScale_ = style::scaleOf(style_.bodies.range, ranges.bodies());
}

void StyledRun::start(const System& system) {
  if (StyleHistory* history = ownHistory("StyledRun::start")) history->start(system);
}

void StyledRun::advanceTo(Stepper& stepper, System& system, double t) {
  if (StyleHistory* history = ownHistory("StyledRun::advanceTo")) {
    history->advanceTo(stepper, system, t);
  } else if (t > system.time()) {
    stepper.advanceTo(t);
  }
}

Camera StyledRun::camera(double t) const {
  if (follows_ && history_ == nullptr) throw std::logic_error("a followed camera needs the run's history");
  const style::CameraPlacement c = (follows_ ? history_->camera() : camera_).at(t);
  return {c.center, c.height};
}

void StyledRun::drawFrame(System& system, Drawing& out, SpringDetail springs) const {
  system.draw(out, springs, detail_);
  if (detail_.accelerations) system.addAccelerations(out);
}

Rgba StyledRun::mapped(double t, const std::optional<style::Colormap>& map) const {
  if (map) return rgbaOf(style::colormapColor(*map, t));
  // The theme's strain colours as a diverging map: t = ½ at rest, 0 and 1 the full colours.
  const double s = 2.0 * t - 1.0;
  return mix(palette_.springRest, s < 0.0 ? palette_.springCompressed : palette_.springStretched, std::abs(s));
}

void StyledRun::resolveParticles(const Drawing& f, double pixelsPerUnit, FrameLook& out) const {
  const style::ParticleStyle& p = style_.particles;
  const size_t n = f.particles.size();
  const bool selectedColor = std::any_of(style_.select.begin(), style_.select.end(),
                                         [](const style::Selection& s) { return s.color && !s.particles.empty(); });
  if (p.colorBy) {
    style::particleValues(f, *p.colorBy, values_);
    out.particleColors.resize(n);
    for (size_t i = 0; i < n; ++i) out.particleColors[i] = mapped(particleScale_.position(values_[i]), p.colormap);
  } else if (p.color || selectedColor) {
    const Rgba plain = p.color ? rgbaOf(*p.color) : Rgba(palette_.particle);
    out.particleColors.assign(n, plain);
    if (!p.color) {
      for (size_t i = 0; i < n && i < f.particleFixed.size(); ++i) {
        if (f.particleFixed[i]) out.particleColors[i] = palette_.fixedParticle;
      }
    }
  }
  const bool selectedRadius = std::any_of(style_.select.begin(), style_.select.end(),
                                          [](const style::Selection& s) { return s.radius && !s.particles.empty(); });
  if (selectedRadius)
    out.particleRadiiPx.assign(n, particleRadiusPx({fixed_.center, double(look_.height) / pixelsPerUnit}, look_));
  for (const style::Selection& s : style_.select) {  // later selections win
    for (int i : s.particles) {
      if (i < 0 || size_t(i) >= n) continue;
      if (s.color) out.particleColors[size_t(i)] = rgbaOf(*s.color);
      if (s.radius) out.particleRadiiPx[size_t(i)] = pixelsOf(*s.radius, pixelsPerUnit);
    }
  }
}

void StyledRun::resolveSprings(const Drawing& f, FrameLook& out) const {
  const style::SpringStyle& s = style_.springs;
  const size_t n = f.springs.size() + f.springsByIndex();
  if (s.color) {
    out.springColors.assign(n, rgbaOf(*s.color));
    return;
  }
  // Strain over ±0.2 in the theme's colours is the renderer's own look, exactly.
  if (!s.colormap && s.colorBy == style::SpringQuantity::strain && !s.rangeGiven) return;
  style::springValues(f, s.colorBy, values_);
  out.springColors.resize(n);
  for (size_t i = 0; i < n; ++i) out.springColors[i] = mapped(springScale_.position(values_[i]), s.colormap);
}

void StyledRun::resolveBodies(const Drawing& f, FrameLook& out) const {
  const style::BodyStyle& b = style_.bodies;
  const size_t n = f.bodies.size();
  const bool selectedColor = std::any_of(style_.select.begin(), style_.select.end(),
                                         [](const style::Selection& s) { return s.color && !s.bodies.empty(); });
  if (b.colorBy) {
    style::bodyValues(f, *b.colorBy, values_);
    out.bodyFills.resize(n);
    for (size_t j = 0; j < n; ++j) out.bodyFills[j] = mapped(bodyScale_.position(values_[j]), b.colormap);
  } else if (b.color || selectedColor) {
    out.bodyFills.assign(n, b.color ? rgbaOf(*b.color) : Rgba(palette_.bodyFill));
  }
  for (const style::Selection& s : style_.select) {
    if (!s.color) continue;
    for (int j : s.bodies) {
      if (j >= 0 && size_t(j) < n) out.bodyFills[size_t(j)] = rgbaOf(*s.color);
    }
  }
  if (b.outline) out.bodyOutlines.assign(n, rgbaOf(*b.outline));
}

void StyledRun::resolveTrails(const Drawing& f, const Camera& camera, FrameLook& out) const {
  const style::TrailHistory* trails = history_ ? history_->trails() : nullptr;
  if (!trails) return;
  const double ppu = pixelsPerUnit(camera, look_);
  const double now = f.time;
  for (const style::TrailHistory::Trail& trail : trails->trails()) {
    const style::Selection& sel = style_.select[trail.selection];
    Rgba color = palette_.particle;
    if (trail.style->color) {
      color = rgbaOf(*trail.style->color);
    } else if (sel.color) {
      color = rgbaOf(*sel.color);
    } else if (trail.particle >= 0 && size_t(trail.particle) < out.particleColors.size()) {
      color = out.particleColors[size_t(trail.particle)];
    } else if (trail.body >= 0) {
      color = size_t(trail.body) < out.bodyFills.size() ? out.bodyFills[size_t(trail.body)] : Rgba(palette_.bodyFill);
    }
    const float width = pixelsOf(trail.style->width, ppu);
    const double window = trail.style->seconds;
    const auto& samples = trail.samples;
    size_t kept = 0;
    for (size_t k = 1; k < samples.size(); ++k) {
      if (samples[k].t > now) break;  // a frame drawn before the trail's last step (--at)
      const bool last = k + 1 == samples.size() || samples[k + 1].t > now;
      if (!last && (samples[k].p - samples[kept].p).norm() * ppu < kTrailMinStepPx) continue;
      const double age = now - 0.5 * (samples[k].t + samples[kept].t);
      // Fading: linearly to nothing at the window's end; a whole-run trail from a quarter at the start.
      double opacity = std::isfinite(window) ? 1.0 - age / window
                                             : 0.25 + 0.75 * (1.0 - age / std::max(now - history_->startTime(), 1e-12));
      opacity = std::clamp(opacity, 0.0, 1.0);
      Rgba c = color;
      c.a = (unsigned char)std::lround(color.a * opacity);
      if (c.a > 0) out.trails.push_back({samples[kept].p, samples[k].p, width, c});
      kept = k;
    }
  }
}

void StyledRun::resolveArrows(const Drawing& f, const Camera& camera, FrameLook& out) const {
  const double ppu = pixelsPerUnit(camera, look_);
  for (const style::Selection& s : style_.select) {
    if (!s.arrow) continue;
    const style::ArrowStyle& a = *s.arrow;
    const Rgba color = a.color ? rgbaOf(*a.color) : defaultArrowColor(look_.themeName);
    const double maxWorld = a.max.pixels ? a.max.value / ppu : a.max.value;
    const float width = 2.0f;
    auto add = [&](const Vec2& from, const Vec2& quantity) {
      Vec2 arrow = a.scale * quantity;
      const double length = arrow.norm();
      if (!(length > 0.0) || !std::isfinite(length)) return;
      if (length > maxWorld) arrow *= maxWorld / length;
      out.arrows.push_back({from, from + arrow, width, color});
    };
    const bool force = a.of == style::ArrowQuantity::force;
    for (int i : s.particles) {
      const size_t k = size_t(i);
      if (k >= f.particles.size()) continue;
      add(f.particles[k], force ? Vec2(f.particleMasses[k] * f.particleAccelerations[k]) : f.particleVelocities[k]);
    }
    for (int j : s.bodies) {
      const size_t k = size_t(j);
      if (k >= f.bodies.size()) continue;
      add(f.bodies[k].center, force ? Vec2(f.bodyMasses[k] * f.bodyAccelerations[k]) : f.bodyVelocities[k]);
    }
  }
}

void StyledRun::resolve(const Drawing& f, const Camera& camera, FrameLook& out) const {
  out = FrameLook{};
  if (!styled_) return;
  const double ppu = pixelsPerUnit(camera, look_);
  resolveParticles(f, ppu, out);
  resolveSprings(f, out);
  resolveBodies(f, out);
  resolveTrails(f, camera, out);
  resolveArrows(f, camera, out);
}

bool StyledRun::annotates() const {
  const bool labels = std::any_of(style_.select.begin(), style_.select.end(),
                                  [](const style::Selection& s) { return !s.label.empty(); });
  return style_.colorbar.has_value() || !style_.title.empty() || style_.scaleBar || labels;
}

std::optional<plot::ColorbarSpec> StyledRun::colorbar() const {
  if (!style_.colorbar) return std::nullopt;
  const style::ColorbarStyle& bar = *style_.colorbar;
  style::ColorbarSubject subject = bar.subject.value_or(style_.particles.colorBy ? style::ColorbarSubject::particles
                                                        : style_.bodies.colorBy  ? style::ColorbarSubject::bodies
                                                                                 : style::ColorbarSubject::springs);
  std::optional<style::Colormap> map;
  style::ColorScale scale;
  std::string label = bar.label;
  switch (subject) {
    case style::ColorbarSubject::particles:
      map = style_.particles.colormap;
      scale = particleScale_;
      if (label.empty() && style_.particles.colorBy) {
        label = quantityLabel(style::nameOf(*style_.particles.colorBy), style::unitOf(*style_.particles.colorBy));
      }
      break;
    case style::ColorbarSubject::springs:
      map = style_.springs.colormap;
      scale = springScale_;
      if (label.empty())
        label = quantityLabel(style::nameOf(style_.springs.colorBy), style::unitOf(style_.springs.colorBy));
      break;
    case style::ColorbarSubject::bodies:
      map = style_.bodies.colormap;
      scale = bodyScale_;
      if (label.empty() && style_.bodies.colorBy) {
        label = quantityLabel(style::nameOf(*style_.bodies.colorBy), style::unitOf(*style_.bodies.colorBy));
      }
      break;
  }
  plot::ColorbarSpec spec;
  for (int k = 0; k < style::kColormapEntries; ++k) {
    const Rgba c = mapped((k + 0.5) / style::kColormapEntries, map);
    spec.colors.push_back({c.r, c.g, c.b});
  }
  spec.lo = scale.lo;
  spec.hi = scale.hi;
  spec.logScale = scale.logScale;
  spec.label = label;
  spec.side = plot::ColorbarSpec::Side(int(bar.position));
  return spec;
}

plot::FrameAnnotations StyledRun::annotations(const Drawing& f, const Camera& camera) const {
  plot::FrameAnnotations a;
  a.darkTheme = look_.themeName == ThemeName::dark;
  a.title = style_.title;
  a.colorbar = colorbar();
  const double ppu = pixelsPerUnit(camera, look_);
  if (style_.scaleBar) a.scaleBar = plot::ScaleBarSpec{ppu};
  auto pixel = [&](const Vec2& p) {
    return std::array<double, 2>{0.5 * look_.width + (p.x() - camera.center.x()) * ppu,
                                 0.5 * look_.height - (p.y() - camera.center.y()) * ppu};
  };
  for (const style::Selection& s : style_.select) {
    if (s.label.empty()) continue;
    for (int i : s.particles) {
      if (size_t(i) < f.particles.size())
        a.labels.push_back({pixel(f.particles[size_t(i)])[0], pixel(f.particles[size_t(i)])[1], s.label});
    }
    for (int j : s.bodies) {
      if (size_t(j) < f.bodies.size())
        a.labels.push_back({pixel(f.bodies[size_t(j)].center)[0], pixel(f.bodies[size_t(j)].center)[1], s.label});
    }
  }
  return a;
}

const Image& drawStyledFrame(System& system, StyledRun& styled, Renderer& renderer, StyledFrameBuffers& buffers,
                             bool oneFrame, WorkerPool* pool) {
  styled.drawFrame(system, buffers.drawing, SpringDetail::topology);
  if (oneFrame) styled.fitTo(buffers.drawing);
  const Camera camera = styled.camera(system.time());
  styled.resolve(buffers.drawing, camera, buffers.look);
  const Image& image = renderer.render(buffers.drawing, camera, pool, buffers.look.empty() ? nullptr : &buffers.look);
  if (!styled.annotates()) return image;
  buffers.annotated = image;
  const plot::FrameAnnotations notes = styled.annotations(buffers.drawing, camera);
  plot::drawFrameAnnotations(buffers.annotated.rgba.data(), buffers.annotated.width, buffers.annotated.height, notes);
  return buffers.annotated;
}

}  // namespace particles::render
