// A state golden's file and its comparison: see state_table.hpp.
#include "golden/state_table.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "input/printable_text.hpp"
#include "input/csv_reader.hpp"
#include "output/csv_writer.hpp"
#include "scenario/scenario.hpp"

namespace particles::golden {

namespace {

double numberOf(const std::string& text, const std::string& where) {
  double x = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    throw std::invalid_argument(fmt::format("{}: {} is not a number", where, input::quotedValue(text)));
  }
  return x;
}

}  // namespace

std::vector<StateRow> stateRows(const System& system, const std::string& timeText) {
  const StateView v = system.view();
  const int particles = system.layout().numParticles;
  const int points = particles + system.layout().numBodies;
  std::vector<StateRow> rows;
  rows.reserve(size_t(points));
  for (int p = 0; p < points; ++p) {
    StateRow row{timeText, scenario::pointName(system.model(), p)};
    const Vec2 x = v.pos(p), u = v.vel(p);
    row.values[0] = x.x();
    row.values[1] = x.y();
    row.values[2] = u.x();
    row.values[3] = u.y();
    row.values[4] = p < particles ? 0.0 : v.angle(p - particles);
    row.values[5] = p < particles ? 0.0 : v.omega(p - particles);
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string stateText(const std::vector<StateRow>& rows) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}\n", kStateHeader);
  for (const StateRow& r : rows) {
    fmt::format_to(std::back_inserter(out), "{},{},{},{},{},{},{},{}\n", output::csvField(r.time),
                   output::csvField(r.name), r.values[0], r.values[1], r.values[2], r.values[3], r.values[4],
                   r.values[5]);
  }
  return fmt::to_string(out);
}

std::vector<StateRow> parseStateText(std::string_view text, const std::string& file) {
  if (const size_t nul = text.find('\0'); nul != std::string_view::npos) {
    throw std::invalid_argument(fmt::format("{}: byte {} is a NUL byte, which no state file holds", file, nul + 1));
  }
  const size_t headerEnd = text.find('\n');
  std::string_view header = text.substr(0, headerEnd);
  if (!header.empty() && header.back() == '\r') header.remove_suffix(1);
  if (header != kStateHeader) {
    throw std::invalid_argument(
        fmt::format("{}:1: the first line is not a state file's header {}", file, input::quotedValue(kStateHeader)));
  }
  std::vector<int> lines;
  std::vector<std::vector<std::string>> records;
  try {
    records = input::parseCsv(text, &lines);
  } catch (const input::CsvError& e) {
    throw std::invalid_argument(fmt::format("{}:{}: {}", file, e.line(), e.what()));
  }
  std::vector<StateRow> rows;
  for (size_t r = 1; r < records.size(); ++r) {  // records[0] is the header, checked above
    std::vector<std::string>& fields = records[r];
    if (fields.size() == 1 && fields[0].empty()) continue;  // an empty line
    const std::string where = fmt::format("{}:{}", file, lines[r]);
    if (fields.size() != 8) {
      throw std::invalid_argument(
          fmt::format("{}: {} fields, where a state row has 8 ({})", where, fields.size(), kStateHeader));
    }
    StateRow row{std::move(fields[0]), std::move(fields[1])};
    for (size_t q = 0; q < 6; ++q) {
      row.values[q] = numberOf(fields[q + 2], fmt::format("{}: {}", where, kStateQuantities[q]));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

double StateTolerance::of(size_t quantity) const {
  switch (quantity) {
    case 0:
    case 1: return position;
    case 2:
    case 3: return velocity;
    case 4: return angle;
    default: return omega;
  }
}

StateComparison compareStates(const std::vector<StateRow>& expected, const std::vector<StateRow>& actual,
                              const StateTolerance& tolerance) {
  StateComparison c;
  const size_t n = std::min(expected.size(), actual.size());
  for (size_t i = 0; i < n; ++i) {
    if (expected[i].time != actual[i].time || expected[i].name != actual[i].name) {
      c.passed = false;
      c.mismatch = fmt::format("row {}: the reference has {} at t = {}, the simulation {} at t = {}", i + 1,
                               expected[i].name, expected[i].time, actual[i].name, actual[i].time);
      return c;
    }
  }
  if (expected.size() != actual.size()) {
    c.passed = false;
    const bool more = expected.size() > actual.size();
    const StateRow& extra = more ? expected[n] : actual[n];
    c.mismatch = fmt::format("the reference has {} rows, the simulation {}: {} at t = {} is only in the {}",
                             expected.size(), actual.size(), extra.name, extra.time, more ? "reference" : "simulation");
    return c;
  }
  double largestRatio = -1.0;
  for (size_t i = 0; i < n; ++i) {
    for (size_t q = 0; q < 6; ++q) {
      const double e = expected[i].values[q], a = actual[i].values[q], tol = tolerance.of(q);
      const double difference = std::abs(a - e);
      const bool nanMismatch = std::isnan(a) != std::isnan(e);
      const bool beyond = nanMismatch || difference > tol;  // NaN against NaN: the same
      ++c.values;
      const StateDeviation d{
          expected[i].time, expected[i].name, std::string(kStateQuantities[q]), e, a, difference, tol};
      if (beyond && !c.firstBeyond) c.firstBeyond = d;
      const double ratio = nanMismatch              ? INFINITY
                           : std::isnan(difference) ? 0.0
                           : tol > 0                ? difference / tol
                                                    : difference;
      if (ratio > largestRatio) {
        largestRatio = ratio;
        c.largest = d;
      }
    }
  }
  c.passed = !c.firstBeyond;
  return c;
}

}  // namespace particles::golden
