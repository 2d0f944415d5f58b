#pragma once
// What `particles render -o OUT` can write, one row per format (output_formats.cpp): the name -o
// gives, what the format can hold (alpha, a quality setting, a frame rate) and how its writer
// opens. Every rule about formats reads the rows: the command line's checks and renderSimulation
// (checkFormatOptions), openFrameWriter (frame_writer.hpp), the writers (crfOf, checkFps), and the
// help texts and docs/cli.md's table of formats, which are made from them.
//
// A new format: its writer's file pair, a value of OutputKind, and one row in output_formats.cpp
// (docs/architecture.md, "Adding an output format").

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace particles::render {

class FrameWriter;
struct FrameWriterOptions;

enum class OutputKind { mp4, webm, gif, png, pngSequence };

// An encoder's constant rate factor (quality): lower is better and larger.
struct CrfRange {
  int lowest = 0;
  int highest = 0;
  int byDefault = 0;
};

// A format that cannot show every frame rate: the most frames per second it takes, and the most
// it takes from the scenario's render.fps when the rate is not asked for.
struct FpsCap {
  int most = 0;
  int byDefault = 0;
  std::string_view why;  // why no more, for the refusal
};

// Opens a writer of frames to the path (a file or a directory), checking the options first.
using OpenFrameWriter = std::unique_ptr<FrameWriter> (*)(const std::filesystem::path& path,
                                                         const FrameWriterOptions& options);

struct OutputFormat {
  OutputKind kind;
  std::string_view extension;  // ".mp4" (matched in any case); "/" for a directory
  std::string_view example;    // how -o spells it: "file.mp4", "dir/"
  std::string_view name;       // "MP4": for messages and help
  std::string_view codec;      // "H.264"
  std::string_view contents;   // "H.264 video": for help
  // The frames' alpha (a transparent background) is kept; `alphaNote` says how, or why not.
  bool keepsAlpha = false;
  std::string_view alphaNote;
  std::optional<CrfRange> crf = std::nullopt;  // nothing: no quality setting (--crf refused)
  // A range of the frames can be rendered alone (--frames, a split render) and joined again.
  bool splits = false;
  // Its segments are joined by `particles concat` (render/video/mp4_concat.hpp), without re-encoding.
  bool joinedByConcat = false;
  // Its pixels keep chroma at half the width and height, so a frame's sides must be even: the pixel
  // format, and the one with alpha where alpha is kept, for the refusal. Empty: any size.
  std::string_view halvedChroma = {};
  std::string_view halvedChromaAlpha = {};
  std::optional<FpsCap> fpsCap = std::nullopt;  // nothing: any rate the command line takes
  // The widest and tallest frame its encoder takes, px (x264 and libvpx's VP9: 16384, found by
  // trying; GIF's screen is 16 bits); checkFrameSize refuses more before the encoder is opened,
  // where the encoder said only "Invalid data found when processing input".
  int maxSide = 0;
  // One frame at a time given by --at (which is then required); every other format is a run of
  // frames, and refuses --at.
  bool oneFrameAt = false;
  // Nothing for the one frame at --at: renderSimulation draws it and writes it with writePng.
  OpenFrameWriter open = nullptr;
};

// The rows, in the order help and docs list them.
std::span<const OutputFormat> outputFormats();
const OutputFormat& outputFormat(OutputKind kind);
// The row a path names: a trailing '/' or an existing directory is a directory's format, otherwise
// the extension decides (case-insensitive). Throws std::invalid_argument listing every row.
const OutputFormat& outputFormatOf(const std::filesystem::path& path);

// The options whose meaning depends on the format, as `particles render` takes them (a RenderJob's
// fields of the same names).
struct FormatOptions {
  bool transparentBackground = false;       // --background transparent
  bool hud = false;                         // --hud
  std::optional<int> crf = std::nullopt;    // --crf
  std::optional<int> fps = std::nullopt;    // the frame rate the output gets (--fps, or defaultFps)
  std::optional<double> at = std::nullopt;  // --at T
  bool frames = false;                      // --frames A:B
};

// Refuses the options `format` does not take, naming the option and the output `path` and saying
// which formats do, and --hud's opaque panel over a transparent background: std::invalid_argument.
void checkFormatOptions(const OutputFormat& format, const std::filesystem::path& path, const FormatOptions& options);
// The frames' alpha: refused where the format cannot keep it (std::invalid_argument).
void checkAlpha(const OutputFormat& format, const std::filesystem::path& path, bool alpha);
// The frame rate against the format's cap (std::invalid_argument).
void checkFps(const OutputFormat& format, int fps);
// A frame size the format can store: even sides where its chroma is halved (std::invalid_argument,
// suggesting the next even size), neither side past maxSide.
void checkFrameSize(const OutputFormat& format, int width, int height, bool alpha);
// The joined video of `particles concat`: a path of a format joinedByConcat (std::invalid_argument).
void checkConcatOutput(const std::filesystem::path& path);
// A crf asked for, against the format's range; std::invalid_argument for one out of range or
// given to a format without one.
void checkCrf(const OutputFormat& format, std::optional<int> crf);
// The crf the encoder of a format with one gets: `crf` once checked, else the format's default.
int crfOf(const OutputFormat& format, std::optional<int> crf);
// The frame rate when none is asked for: the scenario's, capped where the format caps it.
double defaultFps(const OutputFormat& format, double scenarioFps);

// Help texts of `particles render`'s options, from the rows.
std::string outputHelp();
std::string atHelp();
std::string framesHelp();
std::string fpsHelp();
std::string backgroundHelp();
std::string crfHelp();
// render's help on frame sizes: which formats refuse odd sides, and why.
std::string frameSizeHelp();
// concat's help on -o: "The joined video (.mp4)".
std::string concatOutputHelp();
// README.md's table of formats ("Videos for the web"), one line per row.
std::string outputFormatsMarkdown();

}  // namespace particles::render
