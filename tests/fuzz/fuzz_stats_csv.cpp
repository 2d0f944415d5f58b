// libFuzzer harness for the stats CSV that `particles plot` reads: text in, a table or a CsvError
// out, and from a table the figure as SVG bytes in memory, as `particles plot -o x.svg` draws it
// (FigureError is a normal outcome too). Any other exception escapes and any crash aborts: both
// are findings. How to run it: tests/fuzz/README.md.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "plot/errors.hpp"
#include "plot/figure.hpp"
#include "plot/stats_figure.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace particles::plot;
  try {
    const StatsTable table = parseStatsCsv(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.csv");
    (void)renderFigure(statsFigure(table), ImageFormat::Svg);
  } catch (const CsvError&) {
    // Malformed CSV, reported with its line and column.
  } catch (const FigureError&) {
    // A figure cairo could not draw, with cairo's message.
  }
  return 0;
}
