// A state golden's file and its comparison (src/golden/state_table.hpp): the text round-trips
// every double exactly, names that need quoting survive, and the comparison finds the first value
// beyond its tolerance in file order, refuses rows that do not pair up and treats NaN as a change.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "golden/state_table.hpp"

using namespace particles::golden;

namespace {

std::vector<StateRow> sampleRows() {
  return {{"0.5", "bob", {0.1, -0.2, 1e-300, 3.0, 0.0, 0.0}},
          {"0.5", "a, \"quoted\"\nname", {1.0 / 3.0, 2.0 / 3.0, -5e-17, 0.0, 0.0, 0.0}},
          {"2", "bob", {0.15, -0.25, 1.0, 2.0, 0.0, 0.0}},
          {"2", "plate", {1.6, 0.4, 0.0, 0.1, 0.3, -2.5}}};
}

}  // namespace

TEST_CASE("golden state file: every double and every name round-trips through the text") {
  const std::vector<StateRow> rows = sampleRows();
  const std::string text = stateText(rows);
  CHECK(text.rfind("t,name,x,y,vx,vy,angle,omega\n", 0) == 0);
  CHECK(text.find("\"a, \"\"quoted\"\"\nname\"") != std::string::npos);
  const std::vector<StateRow> back = parseStateText(text, "s.csv");
  REQUIRE(back.size() == rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    CAPTURE(i);
    CHECK(back[i].time == rows[i].time);
    CHECK(back[i].name == rows[i].name);
    for (size_t q = 0; q < 6; ++q) CHECK(back[i].values[q] == rows[i].values[q]);  // bit for bit
  }
  const StateComparison same = compareStates(rows, back, {});
  CHECK(same.passed);
  CHECK(same.values == 24);
  CHECK_FALSE(same.firstBeyond);
}

TEST_CASE("golden state file: a file that is not one is refused with its line") {
  auto message = [](const std::string& text) {
    try {
      parseStateText(text, "ref.csv");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK(message("t,name,x,y\n") ==
        "ref.csv:1: the first line is not a state file's header 't,name,x,y,vx,vy,angle,omega'");
  CHECK(message("t,name,x,y,vx,vy,angle,omega\n1,a,1,2,3\n").find("ref.csv:2: 5 fields") == 0);
  CHECK(message("t,name,x,y,vx,vy,angle,omega\n1,a,1,2,3,4,5,6\n1,b,1,2,x3,4,5,6\n") ==
        "ref.csv:3: vx: 'x3' is not a number");
  CHECK(message("t,name,x,y,vx,vy,angle,omega\n1,\"a,1,2,3,4,5,6\n") == "ref.csv:2: a quoted field is not closed");
  CHECK(message("t,name,x,y,vx,vy,angle,omega\r\n1,a,1,2,3,4,5,6\r\n") == "accepted");
  constexpr char withNul[] = "t,name,x,y,vx,vy,angle,omega\n1,a\0,1,2,3,4,5,6\n";
  CHECK(message(std::string(withNul, sizeof withNul - 1)) ==
        "ref.csv: byte 33 is a NUL byte, which no state file holds");
}

TEST_CASE("golden state comparison: the first value beyond its tolerance, in file order") {
  const std::vector<StateRow> expected = sampleRows();
  std::vector<StateRow> actual = expected;
  actual[2].values[3] += 2e-5;  // bob's vy at t = 2: beyond a velocity tolerance of 1e-5
  actual[3].values[4] += 0.5;   // plate's angle at t = 2: far beyond, but later in the file
  actual[0].values[0] += 5e-7;  // bob's x at 0.5: within 1e-6
  const StateTolerance tolerance{1e-6, 1e-5, 1e-6, 1e-5};
  const StateComparison c = compareStates(expected, actual, tolerance);
  CHECK_FALSE(c.passed);
  REQUIRE(c.firstBeyond);
  CHECK(c.firstBeyond->time == "2");
  CHECK(c.firstBeyond->point == "bob");
  CHECK(c.firstBeyond->quantity == "vy");
  CHECK(c.firstBeyond->difference == doctest::Approx(2e-5));
  CHECK(c.firstBeyond->tolerance == 1e-5);
  REQUIRE(c.largest);
  CHECK(c.largest->point == "plate");
  CHECK(c.largest->quantity == "angle");

  actual = expected;
  actual[1].values[1] = std::numeric_limits<double>::quiet_NaN();
  const StateComparison nan = compareStates(expected, actual, {1e9, 1e9, 1e9, 1e9});
  CHECK_FALSE(nan.passed);
  REQUIRE(nan.firstBeyond);
  CHECK(nan.firstBeyond->quantity == "y");
}

TEST_CASE("golden state comparison: rows that do not pair up are a failure named, not compared") {
  const std::vector<StateRow> expected = sampleRows();
  std::vector<StateRow> fewer(expected.begin(), expected.end() - 1);
  const StateComparison c = compareStates(expected, fewer, {});
  CHECK_FALSE(c.passed);
  CHECK(c.mismatch == "the reference has 4 rows, the simulation 3: plate at t = 2 is only in the reference");
  std::vector<StateRow> renamed = expected;
  renamed[2].name = "bob2";
  const StateComparison r = compareStates(expected, renamed, {});
  CHECK(r.mismatch == "row 3: the reference has bob at t = 2, the simulation bob2 at t = 2");
  CHECK(r.values == 0);
}
