#include "plot/stats_figure.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>

#include "input/text_file.hpp"
#include "plot/errors.hpp"

namespace particles::plot {

namespace {

constexpr std::array<std::string_view, 6> kColumns = {"t",     "kinetic",          "potential",
                                                      "total", "constraint_error", "penetration"};

// A field as messages quote it: whole up to 80 bytes, else its start and its length (a 10 MB field
// is not echoed back), cut before a UTF-8 continuation byte.
std::string quoted(std::string_view field) {
  constexpr std::size_t kMax = 80;
  if (field.size() <= kMax) return "'" + std::string(field) + "'";
  std::size_t cut = kMax - 8;
  while (cut > 0 && (static_cast<unsigned char>(field[cut]) & 0xC0) == 0x80) --cut;
  return fmt::format("'{}…' ({} bytes)", field.substr(0, cut), field.size());
}

// One field as a finite double, all of it: "1e-3" yes; " 1", "1x", "", "nan", "inf" no.
double parseNumber(std::string_view field, const std::filesystem::path& file, std::size_t line, std::size_t column,
                   std::string_view columnName) {
  double value = 0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (field.empty() || ec == std::errc::invalid_argument || end != field.data() + field.size()) {
    throw CsvError(file, line, column,
                   "column '" + std::string(columnName) + "': expected a number, found " + quoted(field));
  }
  if (ec == std::errc::result_out_of_range || !std::isfinite(value)) {
    throw CsvError(file, line, column,
                   "column '" + std::string(columnName) + "': " + quoted(field) + " is not a finite number");
  }
  return value;
}

}  // namespace

StatsTable parseStatsCsv(std::string_view text, const std::filesystem::path& file) {
  StatsTable table;
  std::array<std::vector<double>*, 6> columns = {&table.t,     &table.kinetic,         &table.potential,
                                                 &table.total, &table.constraintError, &table.penetration};
  std::size_t lineNumber = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);

    if (lineNumber == 1) {
      if (line != kStatsCsvHeader) {
        const std::string_view expected = kStatsCsvHeader;
        const auto mismatch = std::mismatch(line.begin(), line.end(), expected.begin(), expected.end());
        throw CsvError(file, 1, static_cast<std::size_t>(mismatch.first - line.begin()) + 1,
                       "the header must be exactly '" + std::string(expected) + "'");
      }
      continue;
    }
    if (line.empty()) throw CsvError(file, lineNumber, 1, "empty line");
    std::size_t fieldStart = 0;
    for (std::size_t c = 0; c < kColumns.size(); ++c) {
      if (fieldStart > line.size()) {
        throw CsvError(
            file, lineNumber, line.size() + 1,
            "expected 6 fields, found " + std::to_string(c) + " (missing '" + std::string(kColumns[c]) + "')");
      }
      std::size_t fieldEnd = line.find(',', fieldStart);
      if (fieldEnd == std::string_view::npos) fieldEnd = line.size();
      if (c + 1 == kColumns.size() && fieldEnd != line.size()) {
        throw CsvError(file, lineNumber, fieldEnd + 2, "expected 6 fields, found more");
      }
      columns[c]->push_back(
          parseNumber(line.substr(fieldStart, fieldEnd - fieldStart), file, lineNumber, fieldStart + 1, kColumns[c]));
      fieldStart = fieldEnd + 1;
    }
  }
  if (lineNumber == 0)
    throw CsvError(file, 1, 1, "empty file: expected the header '" + std::string(kStatsCsvHeader) + "'");
  return table;
}

namespace {

// Whether the positive values of the columns span at least two decades.
bool spansDecades(std::initializer_list<const std::vector<double>*> columns) {
  double lo = INFINITY, hi = 0;
  for (const auto* column : columns) {
    for (double v : *column) {
      if (v > 0 && std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
  }
  return hi > 0 && hi >= 100 * lo;
}

}  // namespace

StatsTable readStatsCsv(const std::filesystem::path& file, std::uintmax_t maxInputMiB) {
  std::string text;
  try {
    text = input::readTextFile(file, maxInputMiB);
  } catch (const input::ReadError& e) {
    throw CsvError(file, 0, 0, e.what());
  }
  return parseStatsCsv(text, file);
}

namespace {

bool allZero(const std::vector<double>& column) {
  return std::all_of(column.begin(), column.end(), [](double v) { return v == 0; });
}

std::string title(const StatsFigureContext& c) {
  std::vector<std::string> parts;
  if (!c.scenario.empty()) parts.push_back(c.scenario);
  if (!c.integrator.empty()) parts.push_back(c.integrator);
  if (c.dt > 0) parts.push_back(fmt::format("dt = {} s", c.dt));
  if (parts.empty() && !c.source.empty()) parts.push_back(c.source);
  if (parts.empty()) return "Energy and constraint error";
  return fmt::format("Energy and constraint error: {}", fmt::join(parts, ", "));
}

}  // namespace

Figure statsFigure(const StatsTable& table, const StatsFigureContext& context) {
  const std::size_t n = table.t.size();
  for (const auto* column :
       {&table.kinetic, &table.potential, &table.total, &table.constraintError, &table.penetration}) {
    if (column->size() != n) throw FigureError("stats table: columns of different lengths");
  }
  LineChart chart{"t [s]", {}};
  chart.panels.push_back({"energy [J]",
                          AxisScale::Linear,
                          {{"kinetic", table.t, table.kinetic},
                           {"potential", table.t, table.potential},
                           {"total", table.t, table.total}}});
  Figure figure;
  // An empty table has nothing to report as zero: its panels say "no data".
  if (n > 0 && allZero(table.constraintError)) {
    figure.caption.push_back("Constraint error: 0 throughout.");
  } else {
    chart.panels.push_back({"constraint error [m]", AxisScale::Log, {{"", table.t, table.constraintError}}});
  }
  if (n > 0 && allZero(table.penetration)) {
    figure.caption.push_back("Penetration: 0 throughout (no contact).");
  } else {
    chart.panels.push_back({"penetration [m]",
                            spansDecades({&table.penetration}) ? AxisScale::Log : AxisScale::Linear,
                            {{"", table.t, table.penetration}}});
  }
  if (!context.mouse.empty()) {
    chart.bands = context.mouse;
    figure.caption.insert(figure.caption.begin(),
                          "Shaded: a scripted mouse holds a point. Its spring's energy is part of the total, which "
                          "jumps where it grabs and lets go.");
  }
  figure.title = title(context);
  figure.chart = std::move(chart);
  return figure;
}

}  // namespace particles::plot
