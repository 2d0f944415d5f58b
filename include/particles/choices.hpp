#pragma once
/// @file
/// The library's closed sets of choices, as types: a C++ caller cannot misspell an integrator, a
/// theme or a raster path. The rooms use these same enums. Each value has the name scenarios, the
/// command line and Python spell it with (name(), and its reverse fromName()): the snake_case of
/// the value, except Raster::automatic and GlBackend::automatic, which are `auto` (a C++ keyword).
///
/// @code
/// particles::Renderer renderer({.theme = particles::Theme::light, .raster = particles::Raster::cpu});
/// if (sim.integrator() == particles::Integrator::backwardEuler) { … }
/// std::cout << particles::name(sim.integrator());          // backward_euler
/// @endcode

#include <optional>
#include <string_view>

#include <particles/export.hpp>

namespace particles {

/// The integrators (docs/physics.md): explicit Euler, midpoint, RK4, symplectic Euler, Verlet,
/// backward Euler, BDF2.
enum class Integrator { euler, midpoint, rk4, symplecticEuler, verlet, backwardEuler, bdf2 };

/// A frame's colours: dark for the screen, light for printed reports.
enum class Theme { dark, light };

/// What is behind the scene: the theme's colour, or nothing (alpha = coverage).
enum class Background { theme, transparent };

/// How a frame is drawn (docs/cli.md, "What every command shares"): automatic (the cpu raster without a GPU, resident
/// with one), GL triangles, GL tiles, the resident GPU path, or the cpu raster with no GL at all.
enum class Raster { automatic, triangles, tiles, resident, cpu };

/// The GL backend: automatic (EGL, else OSMesa), EGL or OSMesa.
enum class GlBackend { automatic, egl, osmesa };

namespace golden {

/// A golden check's result: passed, failed, missing (no reference yet) or error (it could not be
/// checked: the scenario did not load, the simulation blew up, the reference is not a PNG).
enum class Outcome { passed, failed, missing, error };

/// The K-th of N near-equal parts of a manifest's checks (`--shard K/N`): 1 ≤ index ≤ count.
struct Shard {
  int index = 1;  ///< K: which part, from 1
  int count = 1;  ///< N: into how many parts
  bool operator==(const Shard&) const = default;  ///< the same part of the same count
};

}  // namespace golden

/// @name Names of the choices
//@{
/// The value's name as scenarios, the command line and Python write it: "backward_euler", "auto".
PARTICLES_API std::string_view name(Integrator integrator) noexcept;
PARTICLES_API std::string_view name(Theme theme) noexcept;
PARTICLES_API std::string_view name(Background background) noexcept;
PARTICLES_API std::string_view name(Raster raster) noexcept;
PARTICLES_API std::string_view name(GlBackend backend) noexcept;
PARTICLES_API std::string_view name(golden::Outcome outcome) noexcept;
//@}

/// @name Choices from their names
//@{
/// The value of that name, or nothing: fromName<Theme>("light"). Defined for Integrator, Theme,
/// Background, Raster, GlBackend and golden::Outcome.
template <class Choice>
std::optional<Choice> fromName(std::string_view text) noexcept;
template <>
PARTICLES_API std::optional<Integrator> fromName<Integrator>(std::string_view text) noexcept;
template <>
PARTICLES_API std::optional<Theme> fromName<Theme>(std::string_view text) noexcept;
template <>
PARTICLES_API std::optional<Background> fromName<Background>(std::string_view text) noexcept;
template <>
PARTICLES_API std::optional<Raster> fromName<Raster>(std::string_view text) noexcept;
template <>
PARTICLES_API std::optional<GlBackend> fromName<GlBackend>(std::string_view text) noexcept;
template <>
PARTICLES_API std::optional<golden::Outcome> fromName<golden::Outcome>(std::string_view text) noexcept;
//@}

}  // namespace particles
