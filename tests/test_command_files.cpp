// The files a command names (src/app/command.hpp, CommandFiles) and the rule they are checked by
// (src/output/distinct_files.hpp): golden, sweep and gather name theirs through their rows of the
// command table, as the other commands do, and an output folder replaced whole (a golden report)
// holds no input. The refusals end to end are tests/test_cli_outputs.cpp's.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "app/cli.hpp"
#include "cli_support.hpp"
#include "output/distinct_files.hpp"

namespace {

using particles::output::NamedFile;
using particles::output::requireDistinctFiles;
using particles::output::SameFileError;
using particles::test::Scratch;
namespace fs = std::filesystem;

// The message requireDistinctFiles refuses with, or "accepted".
std::string verdict(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  try {
    requireDistinctFiles(outputs, inputs);
  } catch (const SameFileError& e) {
    return e.what();
  }
  return "accepted";
}

// A file as the table lists it: its role, path and whether it is a folder replaced whole.
std::string describe(const NamedFile& f) {
  return f.role + " " + f.path.string() + (f.wholeFolder ? " (whole)" : "");
}

// The parsed command line's files, outputs then inputs, one line each.
std::vector<std::string> filesOf(const std::vector<std::string>& args) {
  particles::app::Cli cli;
  cli.parse(args);
  const particles::app::CommandFiles files = cli.commandFiles();
  std::vector<std::string> out;
  for (const NamedFile& f : files.outputs) out.push_back("out: " + describe(f));
  for (const NamedFile& f : files.inputs) out.push_back("in: " + describe(f));
  return out;
}

}  // namespace

TEST_CASE("distinct files: an output folder replaced whole holds no input, by name or through a link") {
  Scratch s;
  fs::create_directories(s.dir / "rep/sub");
  s.write("rep/sub/m.yaml", "");
  s.write("report.yaml", "");
  fs::create_symlink("rep", s.dir / "link");
  const NamedFile folder{"-o", s.dir / "rep", true};
  const std::string rep = (s.dir / "rep").string();
  CHECK(verdict({folder}, {{"the manifest", s.dir / "rep/sub/m.yaml"}}) ==
        "-o '" + rep + "' is a folder replaced whole, and the manifest '" + rep +
            "/sub/m.yaml' is in it; an output never replaces an input");
  // Through a link into it, and a file not there yet.
  CHECK(verdict({folder}, {{"the scenario", s.dir / "link/sub/m.yaml"}}) != "accepted");
  CHECK(verdict({folder}, {{"the references", s.dir / "rep/refs"}}) != "accepted");
  CHECK(verdict({{"-o", s.dir / "new", true}}, {{"the references", s.dir / "new/refs"}}) != "accepted");
  // The folder itself is the same file.
  CHECK(verdict({folder}, {{"the report folder", s.dir / "link"}}) ==
        "-o '" + rep + "' and the report folder '" + (s.dir / "link").string() +
            "' name the same file; an output never replaces an input");
  // Beside it, even when its name starts with the folder's.
  CHECK(verdict({folder}, {{"the manifest", s.dir / "report.yaml"}}) == "accepted");
  // A folder that is not replaced whole (a sweep's) may hold inputs.
  CHECK(verdict({{"-o", s.dir / "rep"}}, {{"the manifest", s.dir / "rep/sub/m.yaml"}}) == "accepted");
}

TEST_CASE("command table: golden, sweep and gather name their files from their rows") {
  CHECK(filesOf({"golden", "check", "m.yaml", "-o", "rep"}) ==
        std::vector<std::string>{"out: -o rep (whole)", "in: the manifest m.yaml"});
  CHECK(filesOf({"golden", "report", "a", "b", "-o", "rep"}) ==
        std::vector<std::string>{"out: -o rep (whole)", "in: the report folder a", "in: the report folder b"});
  CHECK(filesOf({"golden", "update", "m.yaml", "--from", "a"}) ==
        std::vector<std::string>{"in: the manifest m.yaml", "in: --from a"});
  CHECK(filesOf({"sweep", "s.yaml", "-o", "out", "--emit", "slurm"}) ==
        std::vector<std::string>{"out: the output folder out", "out: the job table out/jobs.csv",
                                 "out: the results out/results.csv", "out: the figure out/results.svg",
                                 "out: the job list out/sweep.sbatch", "out: the job list out/concat.sbatch",
                                 "out: the job list out/submit.sh", "in: the sweep file s.yaml"});
  // Without -o the folder is named after the sweep, which the command checks once it has read it.
  CHECK(filesOf({"sweep", "s.yaml"}) == std::vector<std::string>{"in: the sweep file s.yaml"});
  CHECK(filesOf({"gather", "out"}) == std::vector<std::string>{"out: -o out/results.csv", "out: --plot out/results.svg",
                                                               "in: the job table out/jobs.csv"});
  CHECK(filesOf({"gather", "out", "-o", "r.csv", "--plot", "none"}) ==
        std::vector<std::string>{"out: -o r.csv", "out: --plot ", "in: the job table out/jobs.csv"});
}
