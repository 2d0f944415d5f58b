#pragma once
// The shell commands a result lists to reproduce it (FrameResult::reproduce, StateResult::reproduce),
// quoted for a POSIX shell and run where the check ran:
//   particles render SCENARIO -o NAME.png --at T LOOK [--set PATH=VALUE …] [--gl NAME]
//   particles compare REFERENCE NAME.png --threshold N --max-share S --diff NAME.diff.png
//   particles golden check MANIFEST --only NAME [--raster … --threshold … --max-share …] [--gl NAME]
// LOOK is the frame's look as render::lookWords writes it, so the render command draws the frame
// the check drew. And the command a missing reference's message names: golden update --missing.

#include <string>
#include <vector>

#include "golden/check.hpp"
#include "render/gl_backend.hpp"
#include "render/image_compare.hpp"
#include "render/render_options.hpp"
#include "scenario/golden_manifest.hpp"

namespace particles::golden {

// {"--gl", "egl"}, or nothing for the automatic backend; then "--gpu" when the frames are drawn on a GPU.
std::vector<std::string> glWords(const render::GlRequest& gl);

// Draws frame `name` of `entry` at `time` (as the manifest writes it) with `look`.
std::string renderCommand(const CheckOptions& options, const scenario::GoldenEntry& entry, const std::string& name,
                          const std::string& time, const render::RenderOptions& look);
// Compares the frame NAME.png the render command wrote with `reference` (as shownPath writes it).
std::string compareCommand(const CheckOptions& options, const std::string& reference, const std::string& name,
                           const render::CompareTolerance& tolerance);
// Checks `name` alone, with the run's overrides and backend.
std::string checkCommand(const CheckOptions& options, const std::string& name);

// "no reference REFERENCE yet: create it with particles golden update MANIFEST --missing".
std::string noReferenceYet(const CheckOptions& options, const std::string& reference);

}  // namespace particles::golden
