// Citations of bench/README.md stay resolvable, and the file holds results, not a diary.
//
// Comments and documents cite a measurement as the file's name, a comma and a title in double
// quotes (a backtick after the name, a blank instead of the comma, or an opening parenthesis before
// the quote are accepted too; the name in quotes itself, as in a list of paths, is no citation); a
// citation may run across a line break of a comment. The test finds every such
// citation in the checkout's tracked text files and checks that its title is, after dropping
// backticks and bold marks, either a heading of bench/README.md or a row's name there: the first
// cell of a table row. It also checks that bench/README.md names no machine's absolute path
// (/work/, /home/, /root/, /tmp/, /opt/, /mnt/, /Users/), and that no file under bench/ speaks in a
// tracker's words (an issue's number, the word for a sitting of work, "row N of").
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kBenchCiteCheckout = PARTICLES_SOURCE_DIR;
// Built from two parts so that this file does not cite the README itself.
const std::string kBenchCiteTarget = std::string("bench/README") + ".md";

std::string benchCiteRead(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string benchCiteTrim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

// A title as compared: no backticks or bold marks, runs of blanks as one space, trimmed.
std::string benchCiteNormalised(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '`') continue;
    if (s[i] == '*' && i + 1 < s.size() && s[i + 1] == '*') {
      ++i;
      continue;
    }
    const bool blank = s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r';
    if (blank) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += s[i];
    }
  }
  return benchCiteTrim(out);
}

// The headings of a Markdown text (outside fenced code) and the first cells of its table rows.
std::set<std::string> benchCiteTitles(const std::string& markdown) {
  std::set<std::string> titles;
  std::istringstream lines(markdown);
  std::string line;
  bool inFence = false;
  while (std::getline(lines, line)) {
    if (line.rfind("```", 0) == 0) {
      inFence = !inFence;
      continue;
    }
    if (inFence) continue;
    if (line.rfind('#', 0) == 0) {
      const auto text = line.find_first_not_of('#');
      if (text != std::string::npos) titles.insert(benchCiteNormalised(line.substr(text)));
    } else if (line.rfind('|', 0) == 0) {
      const std::string first = line.substr(1, line.find('|', 1) - 1);
      if (first.find_first_not_of(" -:") != std::string::npos) titles.insert(benchCiteNormalised(first));
    }
  }
  return titles;
}

// A text with each line break, and the comment marks and blanks that follow it, made one space,
// so that a citation broken over two comment lines reads as one.
std::string benchCiteJoined(const std::string& text) {
  static const std::regex lineBreak(R"(\s*\n[ \t]*(?:(?://+|#+|\*|--)[ \t]*)?)");
  return std::regex_replace(text, lineBreak, " ");
}

struct BenchCitation {
  std::string title;
  std::string where;
};

// Every citation of bench/README.md in a text: the title between the double quotes.
std::vector<BenchCitation> benchCiteFind(const std::string& text, const std::string& where) {
  static const std::regex citation(R"re(bench/README\.md`?(?:,\s*|\s+|\s*\()"([^"\n]{1,200})")re");
  std::vector<BenchCitation> found;
  const std::string joined = benchCiteJoined(text);
  for (auto it = std::sregex_iterator(joined.begin(), joined.end(), citation); it != std::sregex_iterator(); ++it) {
    found.push_back({benchCiteNormalised((*it)[1].str()), where});
  }
  return found;
}

// The citations whose title is not among the README's titles.
std::vector<BenchCitation> benchCiteUnresolved(const std::vector<BenchCitation>& citations,
                                               const std::set<std::string>& titles) {
  std::vector<BenchCitation> bad;
  for (const auto& c : citations)
    if (!titles.count(c.title)) bad.push_back(c);
  return bad;
}

// The checkout's tracked files (git ls-files), or, without git, every file outside hidden folders
// and build trees (a folder holding CMakeCache.txt).
std::vector<fs::path> benchCiteFiles() {
  std::vector<fs::path> files;
  const std::string command = "git -C '" + kBenchCiteCheckout.string() + "' ls-files -z 2>/dev/null";
  if (FILE* pipe = popen(command.c_str(), "r")) {
    std::string name;
    for (int c = std::fgetc(pipe); c != EOF; c = std::fgetc(pipe)) {
      if (c == '\0') {
        files.push_back(kBenchCiteCheckout / name);
        name.clear();
      } else {
        name += char(c);
      }
    }
    pclose(pipe);
  }
  if (!files.empty()) return files;
  for (auto it = fs::recursive_directory_iterator(kBenchCiteCheckout); it != fs::recursive_directory_iterator(); ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name.rfind('.', 0) == 0 || fs::exists(it->path() / "CMakeCache.txt"))) {
      it.disable_recursion_pending();
    } else if (it->is_regular_file()) {
      files.push_back(it->path());
    }
  }
  return files;
}

// A text file: at most 4 MB and no NUL byte.
bool benchCiteIsText(const fs::path& file, std::string& text) {
  std::error_code error;
  if (!fs::is_regular_file(file, error) || fs::file_size(file, error) > (4u << 20)) return false;
  text = benchCiteRead(file);
  return text.find('\0') == std::string::npos;
}

std::string benchCiteList(const std::vector<BenchCitation>& citations) {
  std::string out;
  for (const auto& c : citations) out += "  " + c.where + ": \"" + c.title + "\"\n";
  return out;
}

}  // namespace

TEST_CASE("bench citations: every citation of bench/README.md names one of its headings or rows") {
  const auto titles = benchCiteTitles(benchCiteRead(kBenchCiteCheckout / kBenchCiteTarget));
  REQUIRE(titles.count("Measurements behind choices in the source"));
  std::vector<BenchCitation> citations;
  std::string text;
  for (const auto& file : benchCiteFiles()) {
    if (!benchCiteIsText(file, text) || text.find(kBenchCiteTarget) == std::string::npos) continue;
    auto found = benchCiteFind(text, fs::relative(file, kBenchCiteCheckout).string());
    citations.insert(citations.end(), found.begin(), found.end());
  }
  CHECK(citations.size() >= 20);  // the tree cites it in many places; none found means a broken search
  const auto bad = benchCiteUnresolved(citations, titles);
  INFO("citations whose title is no heading or row name of " << kBenchCiteTarget << ":\n" << benchCiteList(bad));
  CHECK(bad.empty());
}

TEST_CASE("bench citations: the matcher finds a bad title, also across a comment's line break") {
  const std::set<std::string> titles = benchCiteTitles(
      "# Benchmarks\n\n## The crossover\n\n```sh\n# not a heading\n```\n\n| row | figure |\n| --- | --- |\n"
      "| **GIF dithering** | 64.1 dB |\n");
  CHECK(titles.count("The crossover"));
  CHECK(titles.count("GIF dithering"));
  CHECK_FALSE(titles.count("not a heading"));
  const std::string cite = kBenchCiteTarget + ", \"";
  const std::string text = "// measured (" + cite + "The crossover\"), and (" + cite + "The\n// crossover\") and # (" +
                           cite + "GIF dithering\"), but (" + cite + "No such\n   # section\").\n" + "paths = [\"" +
                           kBenchCiteTarget + "\", \"golden/README.md\"]  # a list, no citation\n";
  const auto found = benchCiteFind(text, "memory");
  REQUIRE(found.size() == 4);
  CHECK(found[1].title == "The crossover");
  const auto bad = benchCiteUnresolved(found, titles);
  REQUIRE(bad.size() == 1);
  CHECK(bad[0].title == "No such section");
}

TEST_CASE("bench citations: bench/ names no machine's absolute path and speaks in no tracker's words") {
  const std::string readme = benchCiteRead(kBenchCiteCheckout / kBenchCiteTarget);
  static const std::regex machinePath(R"((^|[\s`'"(=:])/(work|home|root|tmp|opt|mnt|Users)/)");
  std::smatch m;
  CHECK_MESSAGE(!std::regex_search(readme, m, machinePath), "a machine's path in bench/README.md: " << m.str());
  // An issue's number, the word for a sitting of work (spelt in two parts here; a file name holding it
  // after '_' is one word and passes, `_` being a word character), or a row of some tracker's table.
  static const std::regex tracker(std::string(R"(\b(issues?\s+#?[0-9]+|)") + "sess" + R"(ions?\b|row\s+[0-9]+\s+of\b))",
                                  std::regex::icase);
  std::string text;
  for (auto it = fs::recursive_directory_iterator(kBenchCiteCheckout / "bench");
       it != fs::recursive_directory_iterator(); ++it) {
    if (!benchCiteIsText(it->path(), text)) continue;
    const bool found = std::regex_search(text, m, tracker);
    CHECK_MESSAGE(!found, it->path().lexically_relative(kBenchCiteCheckout).string() << ": \"" << m.str() << "\"");
  }
  // The pattern does catch a diary's words.
  const std::string diary = "measured after issue " + std::string("40's fourth sess") + "ion";
  CHECK(std::regex_search(diary, tracker));
}
