#include "render/video/output_formats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "render/video/gif_writer.hpp"
#include "render/video/mp4_writer.hpp"
#include "render/video/png_sequence_writer.hpp"
#include "render/video/webm_writer.hpp"

namespace particles::render {

namespace {

template <class Writer>
std::unique_ptr<FrameWriter> openWriter(const std::filesystem::path& path, const FrameWriterOptions& options) {
  return std::make_unique<Writer>(path, options);
}

const std::array<OutputFormat, 5> kOutputFormats{{
    {.kind = OutputKind::mp4,
     .extension = ".mp4",
     .example = "file.mp4",
     .name = "MP4",
     .codec = "H.264",
     .contents = "H.264 video",
     .keepsAlpha = false,
     .alphaNote = "H.264 in MP4 has no alpha channel",
     // x264's crf. Line art on a flat background is cheap to encode; 18 keeps thin coloured lines
     // free of visible ringing and chroma smear.
     .crf = CrfRange{0, 51, 18},
     // Segments join without re-encoding (particles concat).
     .splits = true,
     .joinedByConcat = true,
     .halvedChroma = "yuv420p",
     .maxSide = 16384,
     .open = &openWriter<Mp4Writer>},
    {.kind = OutputKind::webm,
     .extension = ".webm",
     .example = "file.webm",
     .name = "WebM",
     .codec = "VP9",
     .contents = "VP9 video",
     .keepsAlpha = true,
     .alphaNote = "VP9 with an alpha channel",
     // libvpx-vp9's constant quality (crf with a bit rate of 0). 31 gives about x264's 18 in PSNR on
     // the cloth (42.7 against 42.0 dB; docs/cli.md, "Videos for the web").
     .crf = CrfRange{0, 63, 31},
     // Its keyframes and alpha stream would not join.
     .splits = false,
     .halvedChroma = "yuv420p",
     .halvedChromaAlpha = "yuva420p",
     .maxSide = 16384,
     .open = &openWriter<WebmWriter>},
    {.kind = OutputKind::gif,
     .extension = ".gif",
     .example = "file.gif",
     .name = "GIF",
     .codec = "GIF",
     .contents = "animated GIF",
     .keepsAlpha = false,
     .alphaNote = "GIF has one transparent colour, no smooth edges over it",
     // Its one palette is made for the whole video.
     .splits = false,
     // A 60 fps GIF would play at 10 fps in browsers; without --fps the demos' 60 become 30, every
     // other frame of the MP4 (render/video/gif_writer.hpp).
     .fpsCap = FpsCap{50, 30, "its delays are whole centiseconds, and browsers slow delays under 2 cs down to 10 cs"},
     .maxSide = 65535,
     .open = &openWriter<GifWriter>},
    {.kind = OutputKind::pngSequence,
     .extension = "/",
     .example = "dir/",
     .name = "PNG sequence",
     .codec = "PNG",
     .contents = "numbered PNG frames, frame_000000.png …",
     .keepsAlpha = true,
     .alphaNote = "RGBA frames",
     .splits = true,
     .open = &openWriter<PngSequenceWriter>},
    {.kind = OutputKind::png,
     .extension = ".png",
     .example = "file.png",
     .name = "PNG",
     .codec = "PNG",
     .contents = "one frame",
     .keepsAlpha = true,
     .alphaNote = "RGBA",
     .splits = false,
     .oneFrameAt = true},
}};

// "a", "a or b", "a, b or c".
std::string listed(const std::vector<std::string>& items, std::string_view last) {
  if (items.size() < 2) return items.empty() ? std::string() : items.front();
  return fmt::format("{} {} {}", fmt::join(items.begin(), items.end() - 1, ", "), last, items.back());
}

bool everyRow(const OutputFormat&) {
  return true;
}
bool hasCrf(const OutputFormat& format) {
  return format.crf.has_value();
}

// What `field` says of the rows `keep` keeps (a flag of the row, or a function of it), listed:
// rowsWhere(&OutputFormat::splits, &OutputFormat::name, "and") is "MP4 and PNG sequence".
template <class Keep, class Field>
std::string rowsWhere(Keep keep, Field field, std::string_view last) {
  std::vector<std::string> items;
  for (const OutputFormat& format : kOutputFormats) {
    if (std::invoke(keep, format)) items.push_back(fmt::format("{}", std::invoke(field, format)));
  }
  return listed(items, last);
}

}  // namespace

std::span<const OutputFormat> outputFormats() {
  return kOutputFormats;
}

const OutputFormat& outputFormat(OutputKind kind) {
  const auto row = std::find_if(kOutputFormats.begin(), kOutputFormats.end(),
                                [&](const OutputFormat& format) { return format.kind == kind; });
  if (row == kOutputFormats.end()) throw std::logic_error("an output kind without a row in kOutputFormats");
  return *row;
}

const OutputFormat& outputFormatOf(const std::filesystem::path& path) {
  const std::string text = path.string();
  std::error_code ec;
  const bool directory = (!text.empty() && text.back() == '/') || std::filesystem::is_directory(path, ec);
  std::string extension = directory ? "/" : path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  for (const OutputFormat& format : kOutputFormats) {
    if (format.extension == extension) return format;
  }
  throw std::invalid_argument(fmt::format("cannot tell what to write to '{}': use {}", text, outputHelp()));
}

void checkAlpha(const OutputFormat& format, const std::filesystem::path& path, bool alpha) {
  if (!alpha || format.keepsAlpha) return;
  throw std::invalid_argument(fmt::format("--background transparent: {} output ({}) cannot keep it ({}); write {}",
                                          format.name, path.string(), format.alphaNote,
                                          rowsWhere(&OutputFormat::keepsAlpha, &OutputFormat::example, "or")));
}

void checkFps(const OutputFormat& format, int fps) {
  if (!format.fpsCap || fps <= format.fpsCap->most) return;
  throw std::invalid_argument(fmt::format("--fps {}: {} output has at most {} frames per second ({})", fps, format.name,
                                          format.fpsCap->most, format.fpsCap->why));
}

void checkCrf(const OutputFormat& format, std::optional<int> crf) {
  if (!crf) return;
  if (!format.crf) {
    throw std::invalid_argument(
        fmt::format("--crf is for {} output, not {}", rowsWhere(hasCrf, &OutputFormat::name, "and"), format.name));
  }
  if (*crf < format.crf->lowest || *crf > format.crf->highest) {
    throw std::invalid_argument(fmt::format("--crf {}: {} ({}) takes {} … {}", *crf, format.name, format.codec,
                                            format.crf->lowest, format.crf->highest));
  }
}

int crfOf(const OutputFormat& format, std::optional<int> crf) {
  checkCrf(format, crf);
  if (!format.crf) throw std::logic_error(fmt::format("crfOf: {} output has no crf", format.name));
  return crf.value_or(format.crf->byDefault);
}

double defaultFps(const OutputFormat& format, double scenarioFps) {
  return format.fpsCap ? std::min<double>(scenarioFps, format.fpsCap->byDefault) : scenarioFps;
}

void checkFormatOptions(const OutputFormat& format, const std::filesystem::path& path, const FormatOptions& options) {
  checkAlpha(format, path, options.transparentBackground);
  checkCrf(format, options.crf);
  if (options.fps) checkFps(format, *options.fps);
  if (format.oneFrameAt && !options.at) {
    throw std::invalid_argument(fmt::format(
        "-o {}: {} output is one frame and needs --at T, the simulated time to draw", path.string(), format.name));
  }
  if (!format.oneFrameAt && options.at) {
    throw std::invalid_argument(fmt::format("--at draws one frame: give -o {}, not {} output ({})",
                                            rowsWhere(&OutputFormat::oneFrameAt, &OutputFormat::example, "or"),
                                            format.name, path.string()));
  }
  if (!format.splits && options.frames) {
    throw std::invalid_argument(fmt::format(
        "--frames (a split render, its parts joined afterwards) is for {} output: give -o {}, not {} output ({})",
        rowsWhere(&OutputFormat::splits, &OutputFormat::name, "and"),
        rowsWhere(&OutputFormat::splits, &OutputFormat::example, "or"), format.name, path.string()));
  }
  if (options.hud && options.transparentBackground) {
    throw std::invalid_argument("--hud draws an opaque panel over the frame: not with --background transparent");
  }
}

void checkFrameSize(const OutputFormat& format, int width, int height, bool alpha) {
  if (format.maxSide > 0 && (width > format.maxSide || height > format.maxSide)) {
    throw std::invalid_argument(
        fmt::format("{} ({}) frames are at most {} px a side; {}x{} is larger (write PNG frames)", format.name,
                    format.codec, format.maxSide, width, height));
  }
  if (format.halvedChroma.empty() || (width >= 2 && height >= 2 && width % 2 == 0 && height % 2 == 0)) return;
  const std::string_view pixels = alpha && format.keepsAlpha ? format.halvedChromaAlpha : format.halvedChroma;
  throw std::invalid_argument(fmt::format(
      "{} ({}, {}) needs an even width and height; {}x{} is not (try {}x{}, or write PNG frames)", format.name,
      format.codec, pixels, width, height, width + (width & 1), height + (height & 1)));
}

void checkConcatOutput(const std::filesystem::path& path) {
  bool joined = false;
  try {
    joined = outputFormatOf(path).joinedByConcat;
  } catch (const std::invalid_argument&) {
    // No format at all: refused below like any other that concat does not write.
  }
  if (joined) return;
  throw std::invalid_argument(fmt::format("-o {}: the joined video must be a {} file", path.string(),
                                          rowsWhere(&OutputFormat::joinedByConcat, &OutputFormat::extension, "or")));
}

std::string outputHelp() {
  const auto described = [](const OutputFormat& f) {
    return fmt::format("{} ({}{})", f.example, f.contents, f.oneFrameAt ? ", with --at T" : "");
  };
  return rowsWhere(everyRow, described, "or");
}

std::string atHelp() {
  return fmt::format("Draw the one frame at this simulated time, s (with -o {})",
                     rowsWhere(&OutputFormat::oneFrameAt, &OutputFormat::example, "or"));
}

std::string framesHelp() {
  return fmt::format(
      "Render frames A … B−1 only (A:B; A: to the end), each the same as in the whole render, for {} output "
      "(join {} segments with concat)",
      rowsWhere(&OutputFormat::splits, &OutputFormat::name, "and"),
      rowsWhere(&OutputFormat::joinedByConcat, &OutputFormat::name, "and"));
}

std::string fpsHelp() {
  std::string help = "Frames per simulated second (default: the scenario's render.fps)";
  for (const OutputFormat& format : kOutputFormats) {
    if (format.fpsCap) {
      help += fmt::format("; {} at most {} unless given, at most {}", format.name, format.fpsCap->byDefault,
                          format.fpsCap->most);
    }
  }
  return help;
}

std::string backgroundHelp() {
  return fmt::format("theme (the theme's colour) or transparent (alpha 0 behind the shapes: {} only)",
                     rowsWhere(&OutputFormat::keepsAlpha, &OutputFormat::name, "and"));
}

std::string crfHelp() {
  std::string help = "Constant quality, lower is better and larger";
  for (const OutputFormat& f : kOutputFormats) {
    if (f.crf) {
      help += fmt::format("; {} ({}) {} … {}, default {}", f.name, f.codec, f.crf->lowest, f.crf->highest,
                          f.crf->byDefault);
    }
  }
  return help;
}

std::string frameSizeHelp() {
  const auto halvesChroma = [](const OutputFormat& f) { return !f.halvedChroma.empty(); };
  const auto anySize = [&](const OutputFormat& f) { return !halvesChroma(f); };
  const auto first = std::find_if(kOutputFormats.begin(), kOutputFormats.end(), halvesChroma);
  if (first == kOutputFormats.end()) return "Every format takes any size.";
  return fmt::format("Odd sizes are refused for {} ({} needs even sizes); {} take any size.",
                     rowsWhere(halvesChroma, &OutputFormat::name, "and"), first->halvedChroma,
                     rowsWhere(anySize, &OutputFormat::name, "and"));
}

std::string concatOutputHelp() {
  return fmt::format("The joined video ({})", rowsWhere(&OutputFormat::joinedByConcat, &OutputFormat::extension, "or"));
}

std::string outputFormatsMarkdown() {
  std::string table =
      "| `-o` | what | `--background transparent` | `--crf` (default) | `--frames` | fps cap | `--at T` | "
      "odd sizes |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  const auto yesNo = [](bool yes) { return yes ? "yes" : "no"; };
  for (const OutputFormat& f : kOutputFormats) {
    table += fmt::format(
        "| `{}` | {} | {}: {} | {} | {} | {} | {} | {} |\n", f.example, f.contents, yesNo(f.keepsAlpha), f.alphaNote,
        f.crf ? fmt::format("{} … {} ({})", f.crf->lowest, f.crf->highest, f.crf->byDefault) : "no", yesNo(f.splits),
        f.fpsCap ? fmt::format("at most {} ({} unless `--fps` says)", f.fpsCap->most, f.fpsCap->byDefault) : "no cap",
        f.oneFrameAt ? "required" : "no",
        f.halvedChroma.empty() ? std::string("yes") : fmt::format("no ({})", f.halvedChroma));
  }
  return table;
}

}  // namespace particles::render
