#pragma once
// A style (style/style.hpp) over a whole run: what every caller that draws styled frames (a render,
// a golden check, the library) does the same way, so that they draw the same frames.
//
//   1. Before the first frame, when the style needs it (an automatic colour range, a camera that
//      fits the run), one pass over every frame the output shows: the system steps from a
//      checkpoint to each frame's time, is drawn and observed, and is restored to the checkpoint
//      (System::checkpoint), so that the run then steps the same bits as without the pass
//      (runPass). A split render makes the whole render's pass: the same ranges and camera.
//   2. The run: the state at its start and after every time step feeds the trails and the camera
//      that follows (render/style_history.hpp: start, advanceTo), in a history of the StyledRun's
//      own or in one fed elsewhere (the library's Simulation keeps one from its start, and draws
//      each frame with a StyledRun made for the Renderer's settings).
//   3. Each frame: the camera at its time, the drawing with what the style colours by
//      (drawFrame), each shape's colour and the trails and arrows resolved into a FrameLook
//      (render/frame_look.hpp), and the text drawn over the image (colour bar, title, scale bar,
//      labels: plot/frame_annotations.hpp).
// A plain style (Style::isPlain, a fixed camera) changes nothing: the frames are today's.

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/drawing.hpp"
#include "core/integrators.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "plot/frame_annotations.hpp"
#include "render/frame_look.hpp"
#include "render/image.hpp"
#include "render/render_options.hpp"
#include "render/renderer.hpp"
#include "render/style_history.hpp"
#include "style/camera_path.hpp"
#include "style/quantity.hpp"
#include "style/style.hpp"
#include "style/view.hpp"

namespace particles::render {

class StyledRun {
 public:
  // `camera` is the scenario's fixed view; `look` the render's options (size, theme, radius);
  // `dt` and `steps` the run's, whose history the StyledRun keeps (start, advanceTo). Throws
  // OutOfMemory when the trails would exceed their limit (style/trail_history.hpp) and
  // std::invalid_argument for a style the options cannot draw.
  StyledRun(const style::Style& style, const style::ViewStyle& view, const Camera& camera, const RenderOptions& look,
            double dt, long steps);
  // The same, drawing from a history fed elsewhere, made for the same style and view, which must
  // outlive this StyledRun; null where StyleHistory::needed says the style keeps nothing of the run
  // (else std::logic_error). start and advanceTo are the history's owner's.
  StyledRun(const style::Style& style, const style::ViewStyle& view, const Camera& camera, const RenderOptions& look,
            const StyleHistory* history);

  // The render's options with the style's global radius and spring width.
  const RenderOptions& look() const { return look_; }
  // Whether the frames differ from an unstyled render's in any way.
  bool styled() const { return styled_; }

  // 1. The pass: whether one is needed, and making it over the frames at `times` (in order).
  bool needsPass() const;
  void runPass(System& system, Integrator integrator, double dt, const std::vector<double>& times);

  // A one-frame output (`render --at`, a golden frame) is its own pass: the ranges and the fitted
  // camera are its frame's, found from the frame itself (fitTo) without stepping twice; each call
  // fits to its frame alone.
  void fitTo(const Drawing& frame);

  // 2. The run, into the StyledRun's own history (std::logic_error for one that draws from another's).
  void start(const System& system);
  // Steps `stepper` to time t, feeding every step to the trails and the camera.
  void advanceTo(Stepper& stepper, System& system, double t);

  // 3. A frame.
  Camera camera(double t) const;
  // The system's state into `out` with what the style needs (velocities, masses, accelerations).
  void drawFrame(System& system, Drawing& out, SpringDetail springs) const;
  // The shapes' look for `frame` seen through `camera`.
  void resolve(const Drawing& frame, const Camera& camera, FrameLook& out) const;
  // The text and bars over the frame; none when the style has none.
  bool annotates() const;
  plot::FrameAnnotations annotations(const Drawing& frame, const Camera& camera) const;

 private:
  void setScales(const style::StyleRanges& ranges);
  void resolveParticles(const Drawing& frame, double pixelsPerUnit, FrameLook& out) const;
  void resolveSprings(const Drawing& frame, FrameLook& out) const;
  void resolveBodies(const Drawing& frame, FrameLook& out) const;
  void resolveTrails(const Drawing& frame, const Camera& camera, FrameLook& out) const;
  void resolveArrows(const Drawing& frame, const Camera& camera, FrameLook& out) const;
  Rgba mapped(double t, const std::optional<style::Colormap>& map) const;
  std::optional<plot::ColorbarSpec> colorbar() const;

  // The history start and advanceTo feed: the StyledRun's own, or none (std::logic_error for another's).
  StyleHistory* ownHistory(std::string_view call);

  style::Style style_;
  RenderOptions look_;
  Palette palette_;
  // The camera's modes that need no history: fixed, keys and fit (fitted by the pass, or to the
  // frame from `unfitted_`); follow is the history's.
  style::CameraPath camera_, unfitted_;
  bool follows_ = false;
  std::unique_ptr<StyleHistory> ownHistory_;  // on the heap: history_ stays valid when this is moved
  const StyleHistory* history_ = nullptr;     // ownHistory_'s, another's, or none
  DrawDetail detail_;
  style::ColorScale particleScale_, springScale_, bodyScale_;
  Camera fixed_;
  bool styled_ = false;
  mutable std::vector<double> values_;  // scratch of resolve (one thread resolves at a time)
};

// What drawStyledFrame keeps from frame to frame (their storage reused).
struct StyledFrameBuffers {
  Drawing drawing;
  FrameLook look;
  Image annotated;  // the renderer's image with the style's text over it
};

// The system's state now as one styled frame: drawn with what the style needs, fitted to itself
// when `oneFrame` (StyledRun::fitTo), seen through the camera of its time, its shapes' look resolved,
// rendered, and the style's text drawn over a copy. The image is the renderer's or buffers.annotated,
// valid until the next call.
const Image& drawStyledFrame(System& system, StyledRun& styled, Renderer& renderer, StyledFrameBuffers& buffers,
                             bool oneFrame, WorkerPool* pool = nullptr);

}  // namespace particles::render
