// particles._particles: Renderer, frames and VideoWriter (python/src/bindings.hpp).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"

namespace particles::python {

using namespace pybind11::literals;

namespace {

// particles.Frame (python/particles/__init__.py), the ndarray subclass frames are viewed as; set
// by the package when it imports this module.
py::handle frameType;

// render's keyword arguments as the API's settings; size None is the scenario's render.size (0 × 0).
RenderSettings settingsOf(const py::object& size, const py::object& theme, const py::object& msaa,
                          const py::object& background, const py::object& raster, const py::object& gl, bool gpu) {
  RenderSettings settings{.theme = choiceOf(theme, "render", "theme", kThemes),
                          .msaa = wholeInt(msaa, "render", "msaa"),
                          .background = choiceOf(background, "render", "background", kBackgrounds),
                          .raster = choiceOf(raster, "render", "raster", kRasters),
                          .gl = choiceOf(gl, "render", "gl", kGlBackends),
                          .gpu = gpu};
  if (!size.is_none()) {
    try {
      std::tie(settings.width, settings.height) = size.cast<std::tuple<int, int>>();
    } catch (const py::cast_error&) {
      throw ArgumentError("render: size takes (width, height) in pixels, or None (the scenario's render.size)");
    }
  }
  return settings;
}

struct VideoHandle : Registered {
  VideoHandle(std::unique_ptr<VideoWriter> w, std::string p) : writer(std::move(w)), path(std::move(p)) {}
  std::unique_ptr<VideoWriter> writer;
  std::string path;
};

VideoHandle& handleOf(VideoHandle& handle) {
  Registered::require(&handle, "VideoWriter");
  return handle;
}
const VideoHandle& handleOf(const VideoHandle& handle) {
  Registered::require(&handle, "VideoWriter");
  return handle;
}

VideoWriter& writerOf(VideoHandle& handle) {
  return *handleOf(handle).writer;
}

Renderer& rendererOf(Object<Renderer>& renderer) {
  return valueOf(renderer, "Renderer");
}

}  // namespace

py::object frameOf(Image&& image) {
  auto* pixels = new std::vector<std::uint8_t>(std::move(image.rgba));
  py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<std::uint8_t>*>(p); });
  const py::ssize_t w = image.width, h = image.height;
  py::array frame(py::dtype::of<std::uint8_t>(), {h, w, py::ssize_t(4)}, {w * 4, py::ssize_t(4), py::ssize_t(1)},
                  pixels->data(), owner);
  if (!frameType) return frame;
  return frame.attr("view")(frameType);
}

Image imageOf(const py::handle& frame, const char* call) {
  const py::array array = py::array::ensure(frame);
  if (!array) {
    PyErr_Clear();
    throw ArgumentError(std::string(call) + ": a frame is an (h, w, 4) or (h, w, 3) uint8 array, not " + typeName(frame));
  }
  if (array.dtype().kind() != 'u' || array.itemsize() != 1) {
    throw ArgumentError(std::string(call) + ": a frame's dtype is uint8, this one's is " +
                        py::str(array.dtype()).cast<std::string>() + " (np.clip(a, 0, 255).astype(np.uint8) converts)");
  }
  if (array.ndim() != 3 || (array.shape(2) != 3 && array.shape(2) != 4) || array.shape(0) < 1 || array.shape(1) < 1) {
    throw ArgumentError(std::string(call) + ": a frame is (h, w, 4) RGBA or (h, w, 3) RGB, this one's shape is " +
                        py::str(py::tuple(array.attr("shape"))).cast<std::string>());
  }
  if (array.shape(0) > 1 << 20 || array.shape(1) > 1 << 20) {
    throw ArgumentError(std::string(call) + ": a frame is at most 1048576 pixels a side");
  }
  // numpy's own copy when the array is not one block of rows (a slice, a broadcast view): its
  // MemoryError, when it cannot allocate that, reaches the caller as it is.
  const py::array contiguous = py::module_::import("numpy").attr("ascontiguousarray")(array);
  Image image{int(array.shape(1)), int(array.shape(0)), {}};
  const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
  const auto* in = static_cast<const std::uint8_t*>(contiguous.data());
  if (array.shape(2) == 4) {
    image.rgba.assign(in, in + pixels * 4);
  } else {
    image.rgba.resize(pixels * 4);
    for (std::size_t i = 0; i < pixels; ++i) {
      std::memcpy(&image.rgba[i * 4], in + i * 3, 3);
      image.rgba[i * 4 + 3] = 255;
    }
  }
  return image;
}

namespace {

// The module's functions on frames: the type they are viewed as, and PNG bytes and files of them.
void bindFrameFunctions(py::module_& module) {
  module.def(
      "_set_frame_type", [](const py::handle& type) { frameType = type.inc_ref(); }, "type"_a,
      "Sets the ndarray subclass frames are returned as (the package sets particles.Frame).");
  module.def(
      "_encode_png",
      [](const py::handle& frame, bool alpha) {
        Image image = imageOf(frame, "Frame.png");
        const std::vector<std::uint8_t> png = withoutGil([&] { return image.encodePng(alpha); });
        return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
      },
      "frame"_a, "alpha"_a = false, "The bytes of a PNG file of the frame.");
  module.def(
      "_save_png",
      [](const py::handle& frame, const std::filesystem::path& path, bool alpha) {
        Image image = imageOf(frame, "Frame.save");
        withoutGil([&] { image.savePng(path.string(), alpha); });
      },
      "frame"_a, "path"_a, "alpha"_a = false, "Writes the frame as a PNG, whole or not at all.");
}

void bindRenderer(py::module_& module) {
  py::class_<Object<Renderer>>(module, "Renderer",
                               R"doc(Draws simulations off screen, as `particles render` does, into frames: (h, w, 4)
uint8 RGBA numpy arrays (particles.Frame). Simulation.render() keeps one for its last settings;
a Renderer of your own can draw several simulations with one GL context.

    renderer = particles.Renderer(size=(640, 360), theme="light")
    frame = renderer.render(sim)
)doc")
      .def(py::init([](const py::object& size, const py::object& theme, const py::object& msaa,
                       const py::object& background, const py::object& raster, const py::object& gl, bool gpu) {
             return Object<Renderer>(Renderer(settingsOf(size, theme, msaa, background, raster, gl, gpu)));
           }),
           py::kw_only(), "size"_a = py::none(), "theme"_a = "dark", "msaa"_a = 4, "background"_a = "theme",
           "raster"_a = "auto", "gl"_a = "auto", "gpu"_a = false,
           R"doc(size: (width, height) in pixels, or None for each scenario's render.size; theme:
dark or light; msaa: samples per pixel, 1, 2, 4, 8 or 16; background: theme, or transparent
(alpha = coverage); raster: auto, triangles, tiles, resident or cpu; gl: auto (EGL, else OSMesa), egl or osmesa;
gpu: a hardware EGL device instead of llvmpipe. Bad values raise ArgumentError.)doc")
      .def(
          "render",
          [](Object<Renderer>& object, const SimulationHandle& handle) {
            Renderer& renderer = rendererOf(object);
            const std::shared_ptr<Simulation> simulation = handle.get("render");
            return frameOf(withoutGil([&] { return renderer.render(*simulation); }));
          },
          "simulation"_a,
          "The simulation's state now, drawn through its scenario's view and style as `particles render --at` draws "
          "it: a Frame (h, w, 4) uint8.")
      .def_property_readonly(
          "gl_description", [](Object<Renderer>& renderer) { return text(rendererOf(renderer).glDescription()); },
          "The GL backend, device and renderer that drew the last frame ('' before the first; "
          "'none (the cpu raster)' where no GL drew it).");
}

// Simulation.render: defined here, beside the Renderer it keeps.
void bindSimulationRender(py::module_& module) {
  const py::object simulation = module.attr("Simulation");
  simulation.attr("render") = py::cpp_function(
      [](SimulationHandle& handle, const py::object& size, const py::object& theme, const py::object& msaa,
         const py::object& background, const py::object& raster, const py::object& gl, bool gpu) {
        const std::shared_ptr<Simulation> shared = handle.get("render");
        RenderSettings settings = settingsOf(size, theme, msaa, background, raster, gl, gpu);
        // The renderer is taken out while it draws: a second thread's render() then makes its own,
        // and Renderer::render refuses it while this one holds the simulation.
        std::optional<std::pair<RenderSettings, Renderer>> slot = std::move(handle.lastRenderer);
        handle.lastRenderer.reset();
        if (!slot || slot->first != settings) {
          Renderer renderer(settings);
          slot.emplace(std::move(settings), std::move(renderer));
        }
        Image image = withoutGil([&] { return slot->second.render(*shared); });
        if (handle.simulation == shared) handle.lastRenderer = std::move(slot);
        return frameOf(std::move(image));
      },
      py::name("render"), py::is_method(simulation), py::kw_only(), "size"_a = py::none(), "theme"_a = "dark",
      "msaa"_a = 4, "background"_a = "theme", "raster"_a = "auto", "gl"_a = "auto", "gpu"_a = false,
      R"doc(The state now, drawn as `particles render --at` draws it, through the scenario's view
and style (Scenario.set_style; trails and a followed camera from the simulation's start): a Frame,
an (h, w, 4) uint8 RGBA numpy array that a notebook shows. The options are Renderer's; the renderer
is kept for the next call with the same ones.)doc");
}

// VideoWriter(path, fps=…, crf=…, …): the keyword arguments checked, then the C++ writer opened.
VideoHandle openVideoWriter(const std::filesystem::path& path, const py::object& fps, const py::object& crf,
                            std::string preset, double keyintSeconds, bool alpha, bool verbose) {
  VideoSettings settings;
  if (!fps.is_none()) {
    settings.fps = wholeInt(fps, "VideoWriter", "fps (or None for the format's default)");
    if (settings.fps < 1) {
      throw ArgumentError("VideoWriter: fps must be 1 or more, or None for the format's default; got " +
                          std::to_string(settings.fps));
    }
  }
  if (!crf.is_none()) {
    const int quality = wholeInt(crf, "VideoWriter", "crf (or None for the format's default)");
    if (quality < 0) throw ArgumentError("VideoWriter: crf must be 0 or more, or None for the format's default");
    settings.crf = quality;  // the C++ constructor checks the format's range
  }
  settings.preset = std::move(preset);
  settings.keyintSeconds = keyintSeconds;
  settings.alpha = alpha;
  settings.verbose = verbose;
  return VideoHandle(std::make_unique<VideoWriter>(path.string(), settings), path.string());
}

void bindVideoWriter(py::module_& module) {
  py::class_<VideoHandle>(module, "VideoWriter",
                          R"doc(Writes frames to an MP4, WebM or GIF file (by its extension), as `particles
render` does. The file appears whole when the writer finishes; a writer that stops early (an
exception, Ctrl-C, abort()) leaves nothing, and an existing file stays as it was.

    with particles.VideoWriter("cloth.mp4", fps=30) as video:
        for _ in range(90):
            video.write(sim.render(size=(640, 360)))
            sim.advance(1 / 30)
)doc")
      .def(py::init(&openVideoWriter), "path"_a, py::kw_only(), "fps"_a = py::none(), "crf"_a = py::none(),
           "preset"_a = "medium", "keyint_seconds"_a = 2.0, "alpha"_a = false, "verbose"_a = false,
           R"doc(path: a .mp4, .webm or .gif file; fps: frames per second, 1 to 1000 (GIF: 1 to 50),
or None for the format's default (60; GIF 30, as `particles render`); crf: quality (the encoder's
constant rate factor), None for the format's default; preset: MP4's x264 preset; keyint_seconds:
the longest time between keyframes, s; alpha: keep the frames' alpha (WebM only); verbose:
libav's own messages on stderr.)doc")
      .def(
          "write",
          [](VideoHandle& handle, const py::handle& frame) {
            VideoWriter& writer = writerOf(handle);
            const Image image = imageOf(frame, "VideoWriter.write");
            withoutGil([&] { writer.write(image); });
          },
          "frame"_a,
          "Adds a frame: an (h, w, 4) RGBA or (h, w, 3) RGB uint8 array, the size of the first (even sides for MP4 "
          "and WebM).")
      .def(
          "finish",
          [](VideoHandle& handle) {
            VideoWriter& writer = writerOf(handle);
            withoutGil([&] { writer.finish(); });
          },
          "Writes the rest and puts the file in place. OutputError if that fails (then nothing is left).")
      .def(
          "abort",
          [](VideoHandle& handle) {
            VideoWriter& writer = writerOf(handle);
            withoutGil([&] { writer.abort(); });  // waits for another thread's write() or finish()
          },
          "Stops without a file: what was written is removed, and later write() and finish() calls are refused. "
          "Safe while another thread is in write() or finish(): it waits for that call to end.")
      .def_property_readonly(
          "frames", [](const VideoHandle& handle) { return handleOf(handle).writer->frames(); },
          "Frames written so far.")
      .def_property_readonly(
          "path", [](const VideoHandle& handle) { return pathText(handleOf(handle).path); }, "The video's path.")
      .def("__enter__", [](py::object self) { return self; })
      .def(
          "__exit__",
          [](VideoHandle& handle, const py::handle& type, const py::handle&, const py::handle&) {
            VideoWriter& writer = writerOf(handle);
            if (type.is_none()) {
              withoutGil([&] { writer.finish(); });
            } else {
              withoutGil([&] { writer.abort(); });
            }
            return false;
          },
          "exc_type"_a, "exc"_a, "traceback"_a, "Finishes the video, or aborts it when the block raised.")
      .def("__repr__", [](const VideoHandle& given) {
        const VideoHandle& handle = handleOf(given);
        return "<particles.VideoWriter " + py::repr(pathText(handle.path)).cast<std::string>() + ", " +
               std::to_string(handle.writer ? handle.writer->frames() : 0) + " frames>";
      });
}

}  // namespace

void bindRendering(py::module_& module) {
  bindFrameFunctions(module);
  bindRenderer(module);
  bindSimulationRender(module);
  bindVideoWriter(module);
}

}  // namespace particles::python
