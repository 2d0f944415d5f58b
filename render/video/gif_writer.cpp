#include "render/video/gif_writer.hpp"

#include <zlib.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/video/frame_pipeline.hpp"
#include "render/video/output_formats.hpp"
#include "render/video/video_encoder.hpp"

extern "C" {
#include <libavfilter/buffersink.h>
#include <libavfilter/buffersrc.h>
}

namespace particles::render {

using libav::check;

namespace {

// The filters' settings, and why: gif_writer.hpp.
constexpr const char* kPaletteGen = "max_colors=256:reserve_transparent=0:stats_mode=full";
constexpr const char* kPaletteUse = "dither=none:diff_mode=rectangle";
// Centiseconds: the unit of GIF frame delays.
constexpr AVRational kCentiseconds{1, 100};

// When frame i starts, cs: round(100·i / fps).
long startCs(long index, int fps) {
  return long(libav::ffmpeg().av_rescale_rnd(index, 100, fps, AV_ROUND_NEAR_INF));
}

AVFilterContext* addFilter(AVFilterGraph* graph, const char* filter, const std::string& args, const char* name) {
  AVFilterContext* context = nullptr;
  check(libav::ffmpeg().avfilter_graph_create_filter(&context, libav::ffmpeg().avfilter_get_by_name(filter), name,
                                                     args.empty() ? nullptr : args.c_str(), nullptr, graph),
        std::string("avfilter_graph_create_filter(") + filter + (args.empty() ? "" : "=" + args) + ")");
  return context;
}

void link(AVFilterContext* from, AVFilterContext* to, unsigned toPad = 0) {
  check(libav::ffmpeg().avfilter_link(from, 0, to, toPad),
        std::string("avfilter_link(") + from->filter->name + " → " + to->filter->name + ")");
}

// A buffer source's arguments for frames of `width` × `height` in `format`, timed in 1/fps.
std::string sourceArgs(int width, int height, int format, int fps) {
  return "video_size=" + std::to_string(width) + "x" + std::to_string(height) + ":pix_fmt=" + std::to_string(format) +
         ":time_base=1/" + std::to_string(fps) + ":pixel_aspect=1/1";
}

// A frame of the image's size holding a copy of its RGBA rows.
libav::FramePtr rgbaFrame(const Image& image, long pts) {
  libav::FramePtr frame(libav::ffmpeg().av_frame_alloc());
  if (!frame) throw OutputError("av_frame_alloc: out of memory");
  frame->format = AV_PIX_FMT_RGBA;
  frame->width = image.width;
  frame->height = image.height;
  check(libav::ffmpeg().av_frame_get_buffer(frame.get(), 0), "av_frame_get_buffer");
  for (int y = 0; y < image.height; ++y) {
    std::memcpy(frame->data[0] + std::ptrdiff_t(y) * frame->linesize[0], image.pixel(0, y), image.stride());
  }
  frame->pts = pts;
  return frame;
}

// Hands `frame` to a buffer source (nullptr: the end of its input).
void push(AVFilterContext* source, libav::FramePtr frame) {
  check(libav::ffmpeg().av_buffersrc_add_frame_flags(source, frame.get(), 0),
        frame ? "av_buffersrc_add_frame" : "av_buffersrc_close");
}

// Every frame the sink has ready, to `take`; stops when it needs more input or has ended.
template <class Take>
void drain(AVFilterContext* sink, AVFrame* scratch, Take&& take) {
  for (;;) {
    const int ret = libav::ffmpeg().av_buffersink_get_frame(sink, scratch);
    if (ret == AVERROR(EAGAIN) || ret == AVERROR_EOF) return;
    check(ret, "av_buffersink_get_frame");
    take(scratch);
    libav::ffmpeg().av_frame_unref(scratch);
  }
}

}  // namespace

// Pass 1 is the pipeline worker's (keep), pass 2 the calling thread's after the worker has stopped
// (encodeAll): never both at once.
struct GifWriter::Passes {
  int width = 0, height = 0, fps = 0;
  std::string url, name;
  libav::FilterGraphPtr paletteGraph;  // buffer → palettegen → buffersink
  AVFilterContext* paletteIn = nullptr;
  AVFilterContext* paletteOut = nullptr;
  libav::FramePtr scratch;
  std::vector<std::vector<std::uint8_t>> kept;  // the frames, deflated
  std::vector<Image> slots;                     // the pipeline's
  std::unique_ptr<VideoEncoder> gif;            // pass 2's; holds the file open while it writes

  // Pass 1, frame `index`: counted into the palette's histogram and kept.
  void keep(const Image& image, long index) {
    uLongf size = compressBound(uLong(image.rgba.size()));
    std::vector<std::uint8_t> deflated(size);
    // Level 1: the fastest; flat frames deflate well at any level.
    const int z = compress2(deflated.data(), &size, image.rgba.data(), uLong(image.rgba.size()), 1);
    if (z != Z_OK) {
      throw OutputError("compress2 (keeping a GIF frame for its second pass): zlib error " + std::to_string(z));
    }
    deflated.resize(size);
    deflated.shrink_to_fit();
    kept.push_back(std::move(deflated));
    push(paletteIn, rgbaFrame(image, index));
    drain(paletteOut, scratch.get(), [](AVFrame*) {});  // palettegen gives its palette only at the end
  }

  libav::FramePtr palette() {
    push(paletteIn, nullptr);
    libav::FramePtr result;
    drain(paletteOut, scratch.get(), [&](AVFrame* f) {
      result.reset(libav::ffmpeg().av_frame_clone(f));
      if (!result) throw OutputError("av_frame_clone: out of memory");
    });
    if (!result) throw OutputError("palettegen gave no palette");
    return result;
  }

  // Pass 2: the palette, then every kept frame through paletteuse into the encoder and the file.
  void encodeAll() {
    if (kept.empty()) throw OutputError("a GIF needs at least one frame; none was written to " + name);
    const libav::FramePtr colours = palette();
    paletteGraph.reset();

    gif = std::make_unique<VideoEncoder>("gif", "gif", url, name);
    AVCodecContext* c = gif->codec();
    c->width = width;
    c->height = height;
    c->pix_fmt = AV_PIX_FMT_PAL8;
    c->time_base = kCentiseconds;
    c->framerate = AVRational{fps, 1};
    const long frames = long(kept.size());
    const long lastDelay = startCs(frames, fps) - startCs(frames - 1, fps);
    gif->open({{"final_delay", std::to_string(lastDelay)}, {"loop", "0"}});

    libav::FilterGraphPtr graph(libav::ffmpeg().avfilter_graph_alloc());
    if (!graph) throw OutputError("avfilter_graph_alloc: out of memory");
    AVFilterContext* in = addFilter(graph.get(), "buffer", sourceArgs(width, height, AV_PIX_FMT_RGBA, fps), "frames");
    AVFilterContext* paletteIn =
        addFilter(graph.get(), "buffer", sourceArgs(colours->width, colours->height, colours->format, fps), "palette");
    AVFilterContext* use = addFilter(graph.get(), "paletteuse", kPaletteUse, "paletteuse");
    AVFilterContext* out = addFilter(graph.get(), "buffersink", "", "out");
    link(in, use, 0);
    link(paletteIn, use, 1);
    link(use, out);
    check(libav::ffmpeg().avfilter_graph_config(graph.get(), nullptr), "avfilter_graph_config(paletteuse)");

    libav::FramePtr paletteFrame(libav::ffmpeg().av_frame_clone(colours.get()));
    if (!paletteFrame) throw OutputError("av_frame_clone: out of memory");
    paletteFrame->pts = 0;
    push(paletteIn, std::move(paletteFrame));
    push(paletteIn, nullptr);  // paletteuse keeps the last palette for every later frame

    const AVRational frameTime = libav::ffmpeg().av_buffersink_get_time_base(out);
    auto encode = [&](AVFrame* f) {
      f->pts = libav::ffmpeg().av_rescale_q_rnd(f->pts, frameTime, kCentiseconds, AV_ROUND_NEAR_INF);
      gif->send(f);
    };
    Image image(width, height);
    for (long i = 0; i < frames; ++i) {
      std::vector<std::uint8_t>& deflated = kept[size_t(i)];
      uLongf size = uLongf(image.rgba.size());
      const int z = uncompress(image.rgba.data(), &size, deflated.data(), uLong(deflated.size()));
      if (z != Z_OK || size != image.rgba.size()) {
        throw OutputError("uncompress (a kept GIF frame): zlib error " + std::to_string(z));
      }
      std::vector<std::uint8_t>().swap(deflated);  // its memory is not needed again
      push(in, rgbaFrame(image, i));
      drain(out, scratch.get(), encode);
    }
    push(in, nullptr);
    drain(out, scratch.get(), encode);
    gif->finish();
  }
};

namespace {

void validateGifOptions(const FrameWriterOptions& o) {
  if (o.video.fps < 1)
    throw std::invalid_argument("GIF frame rate " + std::to_string(o.video.fps) + " is not positive");
  checkFps(outputFormat(OutputKind::gif), o.video.fps);
  checkFrameSize(outputFormat(OutputKind::gif), o.width, o.height, o.alpha);
  if (o.width < 1 || o.height < 1 || o.width > 65535 || o.height > 65535) {
    throw std::invalid_argument("GIF size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                                " is out of range");
  }
}

const std::filesystem::path& validatedGifPath(const std::filesystem::path& path, const FrameWriterOptions& options) {
  validateGifOptions(options);  // before the output is opened, as Mp4Writer does
  return path;
}

}  // namespace

GifWriter::GifWriter(const std::filesystem::path& path, const FrameWriterOptions& options)
    : SingleFileWriter(validatedGifPath(path, options), options.width, options.height, "the GIF") {
  auto p = std::make_unique<Passes>();
  p->width = options.width;
  p->height = options.height;
  p->fps = options.video.fps;
  // "file:": a colon in a named temporary is not a protocol (render/video/yuv_video_writer.cpp).
  p->url = "file:" + out_.reopenablePath().string();
  p->name = path.string();
  p->scratch.reset(libav::ffmpeg().av_frame_alloc());
  if (!p->scratch) throw OutputError("av_frame_alloc: out of memory");

  p->paletteGraph.reset(libav::ffmpeg().avfilter_graph_alloc());
  if (!p->paletteGraph) throw OutputError("avfilter_graph_alloc: out of memory");
  AVFilterGraph* graph = p->paletteGraph.get();
  p->paletteIn = addFilter(graph, "buffer", sourceArgs(p->width, p->height, AV_PIX_FMT_RGBA, p->fps), "frames");
  AVFilterContext* gen = addFilter(graph, "palettegen", kPaletteGen, "palettegen");
  p->paletteOut = addFilter(graph, "buffersink", "", "palette");
  link(p->paletteIn, gen);
  link(gen, p->paletteOut);
  check(libav::ffmpeg().avfilter_graph_config(graph, nullptr), "avfilter_graph_config(palettegen)");

  p->slots.resize(FramePipeline::slotCount(options.queueFrames));
  passes_ = std::move(p);
  Passes* passes = passes_.get();
  pipeline_ = std::make_unique<FramePipeline>(
      options.queueFrames, [passes](const Image& image, size_t slot) { passes->slots[slot] = image; },
      [passes](size_t slot, long index) { passes->keep(passes->slots[slot], index); });
}

GifWriter::~GifWriter() {
  if (!finished_) abort();
}

void GifWriter::complete() {
  passes_->encodeAll();
}

void GifWriter::release() noexcept {
  passes_.reset();  // closes the file
}

}  // namespace particles::render
