#pragma once
/// @file
/// Draws a simulation's current state off screen (no display, no GPU unless asked), as
/// `particles render --at` draws a frame: the same options, the same pixels.
///
/// @code
/// particles::Renderer renderer({.width = 640, .height = 360, .theme = particles::Theme::light});
/// particles::Image frame = renderer.render(sim);    // RGBA, row by row from the top
/// frame.savePng("cloth.png");                        // written whole or not at all
/// @endcode

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <particles/choices.hpp>
#include <particles/export.hpp>

namespace particles {

class Simulation;

/// An RGBA image, 8 bits a channel, rows from the top, no padding: width × height × 4 bytes.
struct PARTICLES_API Image {
  int width = 0;                   ///< px
  int height = 0;                  ///< px
  std::vector<std::uint8_t> rgba;  ///< width × height × 4 bytes: R, G, B, A of each pixel

  /// Writes it as a PNG (with its alpha channel when `alpha`), under a temporary name renamed into
  /// place: the file is whole or absent. Throws OutputError naming the path.
  void savePng(const std::string& path, bool alpha = false) const;
  /// The same PNG file's bytes, in memory (a notebook's inline image, a web server's reply).
  std::vector<std::uint8_t> encodePng(bool alpha = false) const;
};

/// The options of `particles render` that set a frame's look; the names are the command line's.
struct RenderSettings {
  int width = 0;                              ///< px; 0 and 0: the scenario's render.size
  int height = 0;                             ///< px; 0 and 0: the scenario's render.size
  Theme theme = Theme::dark;                  ///< dark for screens, light for printed pages
  int msaa = 4;                               ///< samples per pixel: 1 (off), 2, 4, 8 or 16
  Background background = Background::theme;  ///< transparent: alpha = coverage
  Raster raster = Raster::automatic;          ///< how frames are drawn (`--raster`)
  GlBackend gl = GlBackend::automatic;        ///< the GL backend of the GL raster paths (`--gl`)
  bool gpu = false;                           ///< a hardware EGL device instead of llvmpipe

  bool operator==(const RenderSettings&) const = default;  ///< the same settings, field by field
};

/// Draws a simulation's state into an Image, as `particles render` draws its frames: the same
/// pixels for the same settings. Moved, never copied.
class PARTICLES_API Renderer {
 public:
  /// Checks the settings (ArgumentError naming the option and what it takes); the GL context is
  /// made at the first render(), and again when the frame size changes.
  explicit Renderer(const RenderSettings& settings = {});
  /// Takes over other's settings and GL context; other may then only be destroyed or assigned to.
  Renderer(Renderer&& other) noexcept;
  /// Takes over other's settings and GL context; other may then only be destroyed or assigned to.
  Renderer& operator=(Renderer&& other) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;
  ~Renderer();

  /// The simulation's state now, seen through its scenario's view and drawn with its style
  /// (Scenario::setStyle), as `particles render --at` draws it: automatic colour ranges and a fitted
  /// camera from this frame, trails and a followed camera from the simulation's steps since its
  /// start. Throws Error when the GL context cannot be made (naming the failing call), or when the
  /// style's trails would keep more positions than their limit (its message says which).
  Image render(const Simulation& simulation);
  /// What draws the frames, once one was drawn: "egl, software device: llvmpipe (…), OpenGL 4.5 …",
  /// or "none (the cpu raster)" where the frames are drawn without GL.
  std::string glDescription() const;

  struct Impl;  ///< the library's own, opaque here

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles
