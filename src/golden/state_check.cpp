// The state check of one entry: see state_check.hpp.
#include "golden/state_check.hpp"

#include <fmt/format.h>

#include <chrono>
#include <iterator>
#include <new>

#include "golden/check_settings.hpp"
#include "golden/reproduce_commands.hpp"
#include "golden/state_table.hpp"

namespace particles::golden {

namespace fs = std::filesystem;
using scenario::GoldenEntry;

namespace {

// The state rows at every time of `e`. Throws what loading and stepping throw: the check's error.
std::vector<StateRow> simulateStates(const CheckContext& run, const GoldenEntry& e) {
  EntrySimulation simulation(run.manifest(), e, run.options().maxInputMiB);
  std::vector<StateRow> rows;
  for (const scenario::GoldenTime& t : e.times) {
    simulation.advanceTo(t);
    std::vector<StateRow> at = stateRows(simulation.scenario().system, t.text);
    rows.insert(rows.end(), std::make_move_iterator(at.begin()), std::make_move_iterator(at.end()));
  }
  return rows;
}

}  // namespace

StateResult checkState(CheckContext& run, const scenario::GoldenCheck& check) {
  const scenario::GoldenManifest& m = run.manifest();
  const CheckOptions& o = run.options();
  const GoldenEntry& e = m.states[check.entry];
  const auto start = std::chrono::steady_clock::now();
  StateResult r;
  r.name = check.name;
  r.scenario = e.scenarioGiven;
  for (const scenario::GoldenTime& t : e.times) r.times.push_back(t.text);
  const fs::path reference = stateReference(m, r.name);
  r.reference = shownPath(reference);
  r.reproduce.push_back(checkCommand(o, r.name));
  auto finish = [&] {
    r.seconds = secondsSince(start);
    run.done(r.name);
    return r;
  };
  std::vector<StateRow> actual;
  try {
    actual = simulateStates(run, e);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& ex) {
    r.outcome = Outcome::error;
    r.message = ex.what();
    return finish();
  }
  const std::string actualText = stateText(actual);
  const std::string actualFile = "states/" + r.name + ".actual.csv";
  const std::string expectedFile = "states/" + r.name + ".expected.csv";
  auto keepActual = [&] {
    writeText(run.folder() / actualFile, actualText);
    r.files.actual = actualFile;
  };
  if (o.keepAll) keepActual();
  if (referenceAbsent(reference)) {
    r.outcome = Outcome::missing;
    r.message = noReferenceYet(o, r.reference);
    if (!o.keepAll) keepActual();
    return finish();
  }
  std::string expectedText;
  std::vector<StateRow> expected;
  try {
    expectedText = readReference(reference, o.maxInputMiB);
    expected = parseStateText(expectedText, r.reference);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& ex) {
    run.unusableReference(r, ex);
    return finish();
  }
  const StateComparison c = compareStates(expected, actual, stateCompareToleranceOf(m, e));
  r.values = c.values;
  r.firstBeyond = c.firstBeyond;
  r.largest = c.largest;
  r.outcome = c.passed ? Outcome::passed : Outcome::failed;
  if (!c.mismatch.empty()) {
    r.message = c.mismatch;
  } else if (c.firstBeyond) {
    const StateDeviation& d = *c.firstBeyond;
    r.message = fmt::format("at t = {}, {} {} is {} where the reference has {}: {:.3g} apart, beyond {:.3g}", d.time,
                            d.point, d.quantity, d.actual, d.expected, d.difference, d.tolerance);
  }
  if (!c.passed) {
    if (!o.keepAll) keepActual();
    writeText(run.folder() / expectedFile, expectedText);
    r.files.expected = expectedFile;
  }
  return finish();
}

}  // namespace particles::golden
