#pragma once
// What a frame looks like: the camera (which part of the world) and the options (size,
// anti-aliasing, theme, radii and line widths). Shared by the renderer (render/renderer.hpp) and
// the frame's mesh (render/frame_mesh.hpp).

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <particles/choices.hpp>

#include "core/drawing.hpp"
#include "core/state.hpp"
#include "render/theme.hpp"

namespace particles::render {

// The world-to-pixel mapping: `center` appears at the centre of the image and `height` world
// units span the image vertically; pixels are square, world y points up.
struct Camera {
  Vec2 center = Vec2::Zero();
  double height = 3.0;  // world units shown vertically, > 0
};

struct Length {
  enum class Unit { pixels, world };
  double value;
  Unit unit;
};

// The largest frame side in pixels: particles::kMaxImageSide (core/drawing.hpp), one bound for
// the renderer, the images read back (golden frames) and the scenario loader.
using particles::kMaxImageSide;

// The anti-aliasing sample counts there is a pattern for (RenderOptions::msaa, samplePattern in
// render/shader_program.hpp).
inline constexpr std::array<int, 5> kSampleCounts = {1, 2, 4, 8, 16};
// "1 (off), 2, 4, 8 or 16": kSampleCounts, for help texts and messages.
std::string sampleCountsText();

// How shapes reach the pixels (render/renderer.hpp): triangles, one GL primitive per piece of a
// shape; tiles, shapes binned into screen tiles on the CPU and one full-screen pass
// (render/tile_bins.hpp); resident, the scene's springs and particles kept in GL's buffers, only
// their positions sent each frame, particles drawn as instances and springs expanded in the
// vertex shader (render/resident_program.hpp); cpu, the tiles composited by the program's own
// threads into the image, without GL (render/tile_composite.hpp); automatic, resident on a GPU,
// else cpu.
using Raster = particles::Raster;  // include/particles/choices.hpp
// The shape count from which the GL paths' automatic choice (where the cpu path is not taken: a
// GPU's resident path that cannot hold the frame) draws with tiles: about where the two cost the
// same for the cloth at 1280×720 on llvmpipe, between the 80 × 80 and the 100 × 100 cloth
// (bench/README.md, "Tiles from 20,000 shapes").
inline constexpr size_t kTilesFromShapes = 20000;

struct RenderOptions {
  int width = 1280;  // pixels
  int height = 720;
  int msaa = 4;  // samples per pixel: one of kSampleCounts (1 is off)
  Raster raster = Raster::automatic;
  ThemeName themeName = ThemeName::dark;
  // The background left transparent instead of the theme's colour (`render --background
  // transparent`): the image's alpha is then each pixel's coverage, 0 where nothing is drawn, 255
  // under an opaque shape, in between on anti-aliased edges, and its colour is straight (not
  // premultiplied) as PNG and VP9's alpha want it. Off, every pixel has alpha 255.
  bool transparentBackground = false;
  Length particleRadius{4.0, Length::Unit::pixels};
  double springWidthPx = 1.5;
  double rodWidthPx = 3.5;
  double guideWidthPx = 1.5;    // wires and rails
  double outlineWidthPx = 1.5;  // bodies, colliders, cursor
  // |strain| at which a spring reaches the full compressed / stretched colour; in between the
  // colour is interpolated from the at-rest colour.
  double strainForFullColor = 0.2;
};

// The names the command line and golden manifests give the themes, raster paths and backgrounds
// (render/render_options.cpp's name tables), and back.
std::optional<ThemeName> themeFromName(std::string_view name);
std::optional<Raster> rasterFromName(std::string_view name);
std::string_view themeNameOf(ThemeName theme);
std::string_view rasterNameOf(Raster raster);
std::vector<std::string> rasterNames();  // "auto", "triangles", "tiles", "resident", "cpu"
// The path a frame of `raster` is drawn on, with or without a GPU asked for: automatic is resident
// with a GPU (which draws a scene the resident path cannot hold with tiles from kTilesFromShapes
// shapes, else triangles), else cpu; the others are themselves.
Raster rasterTaken(Raster raster, bool gpu);

// The look options of `particles render`, one row each: its command-line word, what its text may
// be, how the text sets RenderOptions and how RenderOptions writes it back. The render command
// reads its look through these rows and golden's reproduce commands write theirs with them, so a
// frame `golden check` draws and the command it prints for it draw the same; a new look option is
// one row here.
struct LookOption {
  std::string_view flag;  // "--theme"
  std::string expected;   // what `read` takes, for messages: "dark or light"
  // Sets the option in `look` from its text; false, `look` unchanged, for a text it does not take.
  bool (*read)(std::string_view text, RenderOptions& look);
  // The text that sets `look`'s value, or nothing where the command leaves the option out: the
  // background, raster path and particle radius at the program's defaults. The size (which is
  // otherwise the scenario's), samples and theme are always written, so a command shows the look.
  std::optional<std::string> (*write)(const RenderOptions& look);
};

// --size, --msaa, --theme, --background, --raster, --particle-radius: the order lookWords writes.
const std::vector<LookOption>& lookOptions();
// The row of `flag`, one of lookOptions()'; throws std::invalid_argument for another.
const LookOption& lookOption(std::string_view flag);
// The words that give `look` to `particles render`: {"--size", "320x240", "--msaa", "4", "--theme",
// "dark"} and the options off their defaults after them.
std::vector<std::string> lookWords(const RenderOptions& look);

// Throws std::invalid_argument when a size, width or sample count is out of range.
void validate(const RenderOptions& options);

}  // namespace particles::render
