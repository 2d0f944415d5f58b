// The choices' names: see include/particles/choices.hpp. Each is the room's own name table's (the
// core's integrators, the renderer's look options, the golden room's outcomes), so that the
// library, the command line and the scenario files spell a value one way.
#include <particles/choices.hpp>

#include "core/integrators.hpp"
#include "golden/results.hpp"
#include "render/gl_backend.hpp"
#include "render/render_options.hpp"

namespace particles {

namespace {

// The room's name of `value` when it reads back as `value`; empty for a value outside the enum
// (one cast in from a number), for which the rooms' tables give a placeholder.
template <class Choice, class NameOf, class FromName>
std::string_view roundTrip(Choice value, NameOf nameOf, FromName fromName) noexcept {
  try {
    const std::string_view text = nameOf(value);
    const std::optional<Choice> back = fromName(text);
    return back && *back == value ? text : std::string_view();
  } catch (...) {  // the tables do not throw; a name is no reason to leave a noexcept function
    return {};
  }
}

// Background is a flag inside the renderer (RenderOptions::transparentBackground); its names are
// --background's.
constexpr std::string_view kBackgroundNames[] = {"theme", "transparent"};

}  // namespace

std::string_view name(Integrator integrator) noexcept {
  return roundTrip(integrator, integratorName, integratorFromName);
}
std::string_view name(Theme theme) noexcept {
  return roundTrip(theme, render::themeNameOf, render::themeFromName);
}
std::string_view name(Background background) noexcept {
  const auto index = static_cast<unsigned>(background);
  return index < std::size(kBackgroundNames) ? kBackgroundNames[index] : std::string_view();
}
std::string_view name(Raster raster) noexcept {
  return roundTrip(raster, render::rasterNameOf, render::rasterFromName);
}
std::string_view name(GlBackend backend) noexcept {
  return roundTrip(backend, render::glBackendName, render::glBackendFromName);
}
std::string_view name(golden::Outcome outcome) noexcept {
  return roundTrip(outcome, golden::outcomeName, golden::outcomeFromName);
}

namespace {

// The value among `values` whose name is `text`.
template <class Choice, size_t N>
std::optional<Choice> named(std::string_view text, const Choice (&values)[N]) noexcept {
  for (const Choice value : values) {
    if (name(value) == text) return value;
  }
  return std::nullopt;
}

}  // namespace

template <>
std::optional<Integrator> fromName<Integrator>(std::string_view text) noexcept {
  return named(text, {Integrator::euler, Integrator::midpoint, Integrator::rk4, Integrator::symplecticEuler,
                      Integrator::verlet, Integrator::backwardEuler, Integrator::bdf2});
}
template <>
std::optional<Theme> fromName<Theme>(std::string_view text) noexcept {
  return named(text, {Theme::dark, Theme::light});
}
template <>
std::optional<Background> fromName<Background>(std::string_view text) noexcept {
  return named(text, {Background::theme, Background::transparent});
}
template <>
std::optional<Raster> fromName<Raster>(std::string_view text) noexcept {
  return named(text, {Raster::automatic, Raster::triangles, Raster::tiles, Raster::resident, Raster::cpu});
}
template <>
std::optional<GlBackend> fromName<GlBackend>(std::string_view text) noexcept {
  return named(text, {GlBackend::automatic, GlBackend::egl, GlBackend::osmesa});
}
template <>
std::optional<golden::Outcome> fromName<golden::Outcome>(std::string_view text) noexcept {
  return named(text,
               {golden::Outcome::passed, golden::Outcome::failed, golden::Outcome::missing, golden::Outcome::error});
}

}  // namespace particles
