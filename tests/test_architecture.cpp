// The rooms of docs/architecture.md, checked on the sources: every `#include "room/…"` points
// along an allowed arrow (program → scenario, video, render, plot → core; video → render, never
// back; render, video, plot, program → output; the tests' support → video, render, core, output,
// and no room → the tests' support), and the core includes no library for files, YAML, GL, images
// or video.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kCheckout = PARTICLES_SOURCE_DIR;

// Each room, its folder, and the rooms it may include besides itself. A room's files are those
// under its folder but not under a room nested in it (render/video inside render/).
struct Room {
  std::string name;
  fs::path folder;
  std::set<std::string> mayInclude;
};

// The rooms in a folder of another room, and the prefix their includes are written with.
const std::vector<std::pair<std::string, std::string>> kNestedRooms = {{"video", "render/video/"}};

const std::vector<Room>& rooms() {
  static const std::vector<Room> all = {
      {"core", kCheckout / "src/core", {}},
      {"output", kCheckout / "src/output", {}},
      {"input", kCheckout / "src/input", {}},
      {"style", kCheckout / "src/style", {"core"}},
      {"scenario", kCheckout / "src/scenario", {"core", "style", "input"}},
      {"render", kCheckout / "render", {"core", "style", "plot", "output"}},
      // The writers and encoders: frames from the renderer to files. The renderer never includes them.
      {"video", kCheckout / "render/video", {"render", "style", "plot", "core", "output"}},
      {"plot", kCheckout / "plot", {"output", "input"}},
      {"golden", kCheckout / "src/golden", {"core", "style", "scenario", "render", "output", "input"}},
      {"api", kCheckout / "src/api", {"core", "style", "scenario", "render", "video", "input", "output", "golden"}},
      {"app",
       kCheckout / "src/app",
       {"core", "style", "scenario", "render", "video", "plot", "output", "input", "golden"}},
      // What only the tests use (particles_test_support): no room above may include it.
      {"support", kCheckout / "tests/support", {"core", "style", "render", "video", "output"}},
  };
  return all;
}

struct Include {
  fs::path file;
  int line;
  std::string target;  // as written between the quotes or brackets
  bool angled;
};

// True for a folder holding a room of its own, below the folder searched.
bool isNestedRoom(const fs::path& folder, const fs::path& searched) {
  if (folder == searched) return false;
  for (const auto& [name, prefix] : kNestedRooms) {
    if (folder == kCheckout / prefix.substr(0, prefix.size() - 1)) return true;
  }
  return false;
}

std::vector<Include> includesUnder(const fs::path& folder) {
  static const std::regex include(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
  std::vector<Include> out;
  for (auto it = fs::recursive_directory_iterator(folder); it != fs::recursive_directory_iterator(); ++it) {
    const fs::directory_entry& entry = *it;
    if (entry.is_directory() && isNestedRoom(entry.path(), folder)) {
      it.disable_recursion_pending();
      continue;
    }
    const auto ext = entry.path().extension();
    if (ext != ".cpp" && ext != ".hpp") continue;
    std::ifstream in(entry.path());
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
      std::smatch m;
      if (std::regex_search(text, m, include)) out.push_back({entry.path(), line, m[2].str(), m[1].str() == "<"});
    }
  }
  return out;
}

// The room a quoted include names by its first folder ("core/system.hpp" → core), or by the
// folder of a nested room ("render/video/frame_writer.hpp" → video).
std::string roomOf(const std::string& target) {
  for (const auto& [name, prefix] : kNestedRooms) {
    if (target.starts_with(prefix)) return name;
  }
  const auto slash = target.find('/');
  return slash == std::string::npos ? std::string() : target.substr(0, slash);
}

}  // namespace

TEST_CASE("every include follows the rooms' arrows") {
  int checked = 0;
  for (const Room& room : rooms()) {
    REQUIRE(fs::is_directory(room.folder));
    for (const Include& inc : includesUnder(room.folder)) {
      if (inc.angled) continue;
      ++checked;
      const std::string target = roomOf(inc.target);
      CAPTURE(inc.file.string());
      CAPTURE(inc.line);
      CAPTURE(inc.target);
      // Includes name their room ("core/state.hpp"), so the arrow is visible where it is drawn.
      CHECK_MESSAGE(!target.empty(), "include without its room");
      CHECK_MESSAGE((target == room.name || room.mayInclude.count(target) == 1),
                    room.name << " may not include " << target);
    }
  }
  CHECK(checked > 100);
}

TEST_CASE("the core uses no files, YAML, GL, images or video") {
  const std::vector<std::string> forbidden = {"fstream", "cstdio", "filesystem", "yaml-cpp", "GL/", "EGL/", "png",
                                              "libav", "libsw", "cairo", "nlohmann", "unistd"};
  int checked = 0;
  for (const Include& inc : includesUnder(kCheckout / "src/core")) {
    if (!inc.angled) continue;
    ++checked;
    for (const std::string& word : forbidden) {
      CAPTURE(inc.file.string());
      CAPTURE(inc.target);
      CHECK(inc.target.find(word) == std::string::npos);
    }
  }
  CHECK(checked > 20);
}

// The public headers are all a user's program includes: they include each other and the
// standard library, never a room's header, Eigen, GL, libav or yaml-cpp, so that the installed
// package is all a consumer needs.
TEST_CASE("the public headers include only each other and the standard library") {
  const std::regex allowed(R"(^(particles/[a-z_]+\.hpp|[a-z_]+)$)");
  int checked = 0;
  for (const Include& inc : includesUnder(kCheckout / "include/particles")) {
    ++checked;
    CAPTURE(inc.file.string());
    CAPTURE(inc.target);
    CHECK(inc.angled);
    CHECK(std::regex_match(inc.target, allowed));
  }
  CHECK(checked >= 8);
}

// The Python module is built on the public API alone, as any user's program: its files
// include the public headers, pybind11, the standard library (with libstdc++'s cxxabi.h, for
// abi::__forced_unwind) and each other, never a room.
TEST_CASE("the Python module includes only the public headers, pybind11 and the standard library") {
  const std::regex allowedAngled(R"(^(particles/[a-z_]+\.hpp|pybind11/[a-z0-9_/]+\.h|[a-z_]+|cxxabi\.h)$)");
  const std::regex allowedQuoted(R"(^[a-z_]+\.hpp$)");  // python/src's own
  int checked = 0;
  for (const Include& inc : includesUnder(kCheckout / "python/src")) {
    ++checked;
    CAPTURE(inc.file.string());
    CAPTURE(inc.target);
    CHECK(std::regex_match(inc.target, inc.angled ? allowedAngled : allowedQuoted));
  }
  CHECK(checked >= 10);
}

// CTest takes a test's name from doctest_discover_tests as a list, so a ';' in a TEST_CASE name
// splits it: the pieces match no test case, run none and pass. Nine tests once passed that way.
TEST_CASE("every test case's name can be run by CTest: none holds a semicolon") {
  const std::regex testCase(R"re(TEST_CASE\("([^"]*)")re");
  for (const auto& entry : fs::directory_iterator(kCheckout / "tests")) {
    if (entry.path().extension() != ".cpp") continue;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (auto it = std::sregex_iterator(text.begin(), text.end(), testCase); it != std::sregex_iterator(); ++it) {
      CAPTURE(entry.path().filename().string());
      CHECK_MESSAGE((*it)[1].str().find(';') == std::string::npos, (*it)[1].str());
    }
  }
}
