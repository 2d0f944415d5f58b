// Names, docs and comments say what a case is or why a rule exists, not which tracker entry or
// sitting of work asked for it: "issue" and a number tells a reader of the source nothing they can
// look up, and the word made of "sess" and "ion" dates a text to the people who wrote it. This test
// walks the source tree as a tarball holds it (no .git needed: build folders, caches and binary
// files skipped) and names file:line for each such word. An upstream project's bug is cited by its
// address (https://github.com/jbeder/yaml-cpp/issues/1040), which the rule does not match.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

namespace fs = std::filesystem;

namespace {

bool houseWordsIsWordChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

std::string houseWordsLower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return out;
}

std::string houseWordsUpper(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return out;
}

// Whether a line holds a tracker's number ("issue" or "issues" as a word, then optional blanks and
// '#', then a digit) or the word "sess" "ion" / "sess" "ions" on its own: '_' joins words, so a
// file name that holds it after an underscore (bench/server_…sh) is one word and passes.
bool houseWordsTrackerWord(std::string_view line) {
  const std::string lower = houseWordsLower(line);
  const auto startsWord = [&](std::size_t at) { return at == 0 || !houseWordsIsWordChar(lower[at - 1]); };
  for (std::size_t at = lower.find("issue"); at != std::string::npos; at = lower.find("issue", at + 1)) {
    if (!startsWord(at)) continue;
    std::size_t i = at + 5;
    if (i < lower.size() && lower[i] == 's') ++i;
    while (i < lower.size() && (lower[i] == ' ' || lower[i] == '\t')) ++i;
    if (i < lower.size() && lower[i] == '#') ++i;
    while (i < lower.size() && (lower[i] == ' ' || lower[i] == '\t')) ++i;
    if (i < lower.size() && std::isdigit(static_cast<unsigned char>(lower[i]))) return true;
  }
  const std::string word = std::string("sess") + "ion";
  for (std::size_t at = lower.find(word); at != std::string::npos; at = lower.find(word, at + 1)) {
    if (!startsWord(at)) continue;
    std::size_t end = at + word.size();
    if (end < lower.size() && lower[end] == 's') ++end;
    if (end == lower.size() || !houseWordsIsWordChar(lower[end])) return true;
  }
  return false;
}

// Folders that are not the source: git's, build trees (build*/ at the top, .gitignore) and caches
// that tools write beside the sources.
bool houseWordsSkippedFolder(const fs::path& folder, bool atTop) {
  const std::string name = folder.filename().string();
  if (name == ".git" || name == ".cache" || name == "__pycache__" || name == ".pytest_cache" ||
      name == "node_modules" || name.ends_with(".egg-info"))
    return true;
  return atTop && (name.starts_with("build") || name == "out");
}

// Images, video and archives are not text; any other file with a NUL byte is taken as binary too.
bool houseWordsBinaryName(const fs::path& file) {
  static const std::array<std::string_view, 14> kBinary = {".png", ".gif", ".jpg", ".jpeg", ".mp4", ".webm", ".mkv",
                                                           ".avi", ".y4m", ".gz",  ".zip",  ".xz",  ".so",   ".o"};
  const std::string ext = houseWordsLower(file.extension().string());
  return std::find(kBinary.begin(), kBinary.end(), ext) != kBinary.end();
}

struct HouseWordsHit {
  std::string where;  // file:line
  std::string line;
};

std::vector<HouseWordsHit> houseWordsInTree(const fs::path& root, int& filesRead) {
  std::vector<HouseWordsHit> hits;
  filesRead = 0;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    const fs::directory_entry& entry = *it;
    if (entry.is_directory()) {
      if (houseWordsSkippedFolder(entry.path(), it.depth() == 0)) it.disable_recursion_pending();
      continue;
    }
    if (!entry.is_regular_file() || houseWordsBinaryName(entry.path())) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (text.find('\0') != std::string::npos) continue;
    ++filesRead;
    const std::string relative = entry.path().lexically_relative(root).generic_string();
    std::size_t start = 0;
    for (int number = 1; start < text.size(); ++number) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      const std::string_view line(text.data() + start, end - start);
      if (houseWordsTrackerWord(line)) {
        hits.push_back({relative + ":" + std::to_string(number), std::string(line.substr(0, 160))});
      }
      start = end + 1;
    }
  }
  std::sort(hits.begin(), hits.end(), [](const HouseWordsHit& a, const HouseWordsHit& b) { return a.where < b.where; });
  return hits;
}

}  // namespace

TEST_CASE("house words: the matcher finds tracker numbers and the word for a sitting, and nothing else") {
  // Built from pieces so that this file itself holds none of the words it looks for.
  const std::string issue = std::string("Iss") + "ue", sitting = std::string("sess") + "ion";
  const std::vector<std::string> matching = {
      "// " + issue + " 26, rows 10 and 11",
      "TEST_CASE(\"" + houseWordsLower(issue) + " 26 row 16: a render\")",
      "(" + houseWordsLower(issue) + " 39)",
      houseWordsLower(issue) + "s 13, 26, 39",
      houseWordsLower(issue) + " #42",
      houseWordsLower(issue) + "#7",
      houseWordsUpper(issue) + " 40's fourth",
      "in the same " + sitting + ", alternating",
      "other " + sitting + "s' builds",
      sitting + ":",
      "\"" + sitting + "\"",
  };
  const std::vector<std::string> passing = {
      "https://github.com/jbeder/yaml-cpp/" + houseWordsLower(issue) + "s/1040",
      "bench/server_" + sitting + ".sh",
      sitting + "_id",
      "a " + sitting + "Token",
      "tissue 3",
      "the " + houseWordsLower(issue) + " with the loop, and 3 more",
      houseWordsLower(issue) + "d 4 times",
      "obsessions 2",
      "",
  };
  for (const std::string& line : matching) {
    CAPTURE(line);
    CHECK(houseWordsTrackerWord(line));
  }
  for (const std::string& line : passing) {
    CAPTURE(line);
    CHECK_FALSE(houseWordsTrackerWord(line));
  }
}

TEST_CASE("house words: no file of the source tree names a tracker entry or a sitting of work") {
  int filesRead = 0;
  const std::vector<HouseWordsHit> hits = houseWordsInTree(PARTICLES_SOURCE_DIR, filesRead);
  // The tree holds several hundred text files; far fewer means the walk skipped what it should read.
  CHECK(filesRead > 300);
  std::string report = std::to_string(hits.size()) +
                       " lines say which tracker entry or sitting of work asked for them; say what the case is or "
                       "why the rule exists instead:\n";
  for (const HouseWordsHit& hit : hits) report += hit.where + ": " + hit.line + "\n";
  CHECK_MESSAGE(hits.empty(), report);
}
