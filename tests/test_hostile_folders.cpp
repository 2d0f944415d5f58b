// `golden` and `job` under hostile folders, end to end as a user runs them: references
// that are links out of their folder, job rows and records that point elsewhere, report folders
// that are not reports, references that are the run's own inputs, shards whose kept files collide,
// and names with control bytes on the terminal. In every case the decoy outside is checked
// untouched and nothing is created outside the command's folders.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <set>
#include <string>

#include "cli_support.hpp"
#include "output/write_sandbox.hpp"
#include "skip.hpp"
#include "source_tree.hpp"

using particles::test::kSource;

namespace {

using particles::test::Scratch;
using particles::test::slurp;
namespace fs = std::filesystem;


// A scratch folder with a copy of scenarios/springs.yaml and a decoy folder with two files in it.
struct Hostile : Scratch {
  fs::path decoy = dir / "decoy";
  Hostile() {
    fs::copy_file(kSource + "/scenarios/springs.yaml", dir / "springs.yaml");
    fs::create_directories(decoy);
    write("decoy/notes.txt", "PRECIOUS");
    fs::copy_file(kSource + "/golden/cloth_t0.5.png", decoy / "figure.png");
  }
  void decoyUntouched() const {
    CHECK(slurp(decoy / "notes.txt") == "PRECIOUS");
    CHECK(slurp(decoy / "figure.png") == slurp(kSource + "/golden/cloth_t0.5.png"));
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(decoy)) names.insert(e.path().filename().string());
    CHECK(names == std::set<std::string>{"notes.txt", "figure.png"});
  }
  // A states-only manifest (no GL needed) over springs.yaml, its references in refs/.
  void statesManifest() const {
    write("m.yaml", "references: refs\nstates:\n  - {scenario: springs.yaml, times: [0.1]}\n");
    fs::create_directories(dir / "refs");
  }
  // A report of a failing state check in `folder`: the reference changed after it was made, so the
  // check keeps its actual and expected files.
  void failingReport(const std::string& folder) const {
    statesManifest();
    REQUIRE(run("golden update m.yaml -q").code == 0);
    write("refs/springs.csv", slurp(dir / "refs/springs.csv") + "0.1,extra,1,1,1,1,0,0\n");
    REQUIRE(run("golden check m.yaml -o " + folder + " -q").code != 0);
  }
  static bool says(const particles::test::Result& r, const std::string& what) {
    return r.err.find(what) != std::string::npos || r.out.find(what) != std::string::npos;
  }
};

}  // namespace

TEST_CASE("golden update and check: a reference that is a link out of its folder is refused, exit 2") {
  Hostile s;
  s.statesManifest();
  REQUIRE(s.run("golden update m.yaml -q").code == 0);
  REQUIRE(s.run("golden check m.yaml -o rep -q").code == 0);
  fs::remove(s.dir / "refs/springs.csv");
  SUBCASE("a link to a file elsewhere") {
    fs::create_symlink(s.decoy / "notes.txt", s.dir / "refs/springs.csv");
  }
  SUBCASE("a relative link up and out") {
    fs::create_symlink("../decoy/notes.txt", s.dir / "refs/springs.csv");
  }
  SUBCASE("a dangling link that would create a file elsewhere") {
    fs::create_symlink("../decoy/new.csv", s.dir / "refs/springs.csv");
  }
  SUBCASE("a link into the report folder that check -o would replace") {
    fs::create_symlink("../rep/results.json", s.dir / "refs/springs.csv");
  }
  const std::string report = slurp(s.dir / "rep/results.json");
  for (const char* command : {"golden update m.yaml", "golden update m.yaml --from rep", "golden check m.yaml -o rep2",
                              "golden check m.yaml -o rep"}) {
    CAPTURE(command);
    const auto r = s.run(command);
    CHECK(r.code == 2);
    CHECK_MESSAGE(Hostile::says(r, "leads outside"), r.err);
    s.decoyUntouched();
  }
  CHECK_FALSE(fs::exists(s.dir / "rep2"));
  CHECK(slurp(s.dir / "rep/results.json") == report);
}

TEST_CASE("golden update: a frame reference that links to a picture elsewhere is refused, the picture kept") {
  Hostile s;
  s.write("m.yaml", "references: refs\nframes:\n  - {scenario: springs.yaml, times: [0.5], render: {size: 64x48}}\n");
  const auto first = s.run("golden update m.yaml -q");
  if (first.code != 0) {
    particles::test::skipTest("no GL here: " + first.err);
    return;
  }
  fs::remove(s.dir / "refs/springs_t0.5.png");
  fs::create_symlink(s.decoy / "figure.png", s.dir / "refs/springs_t0.5.png");
  const auto r = s.run("golden update m.yaml");
  CHECK(r.code == 2);
  CHECK_MESSAGE(Hostile::says(r, "leads outside"), r.err);
  s.decoyUntouched();
}

TEST_CASE("golden update: a reference that is the manifest or a scenario is refused, the input kept") {
  Hostile s;
  // A scenario named like the state's reference: `springs.csv` in the references folder ".".
  fs::copy_file(s.dir / "springs.yaml", s.dir / "scen.csv");
  const std::string scenario = slurp(s.dir / "scen.csv");
  s.write("m.yaml", "states:\n  - {scenario: scen.csv, times: [0.1]}\n");
  for (const char* command : {"golden update m.yaml", "golden update m.yaml --missing"}) {
    const auto r = s.run(command);
    CHECK(r.code == 2);
    CHECK_MESSAGE(Hostile::says(r, "scen.csv"), r.err);
    CHECK(slurp(s.dir / "scen.csv") == scenario);
  }
}

TEST_CASE("golden -o: only a folder that is entirely an earlier report is replaced") {
  Hostile s;
  s.statesManifest();
  REQUIRE(s.run("golden update m.yaml -q").code == 0);
  REQUIRE(s.run("golden check m.yaml -o rep -q").code == 0);
  SUBCASE("a folder whose results.json is no report, with a thesis and a subfolder") {
    fs::create_directories(s.dir / "thesis/sub");
    s.write("thesis/results.json", R"({"not":"a golden report"})");
    s.write("thesis/thesis.tex", "\\documentclass{article}");
    for (const char* command : {"golden check m.yaml -o thesis", "golden report rep -o thesis"}) {
      CAPTURE(command);
      const auto r = s.run(command);
      CHECK(r.code == 2);
      CHECK(slurp(s.dir / "thesis/thesis.tex") == "\\documentclass{article}");
      CHECK(fs::is_directory(s.dir / "thesis/sub"));
    }
  }
  SUBCASE("an earlier report with a file of someone else's added") {
    fs::copy(s.dir / "rep", s.dir / "old", fs::copy_options::recursive);
    s.write("old/notes.txt", "mine");
    const auto r = s.run("golden check m.yaml -o old");
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("notes.txt") != std::string::npos, r.err);
    CHECK(slurp(s.dir / "old/notes.txt") == "mine");
  }
  SUBCASE("an earlier report is replaced, and nothing is left beside it") {
    CHECK(s.run("golden check m.yaml -o rep -q").code == 0);
    CHECK(fs::exists(s.dir / "rep/results.json"));
    for (const auto& e : fs::directory_iterator(s.dir)) {
      CHECK_MESSAGE(e.path().filename().string().find("rep.") != 0, e.path());
    }
  }
}

TEST_CASE("golden report: kept files that collide or are claimed twice are refused, exit 2") {
  Hostile s;
  s.failingReport("a");  // two copies of it, one renamed
  const std::string json = slurp(s.dir / "a/results.json");
  REQUIRE(json.find("\"springs\"") != std::string::npos);
  fs::copy(s.dir / "a", s.dir / "b", fs::copy_options::recursive);
  auto rename = [&](const std::string& folder, const std::string& from, const std::string& to) {
    std::string text = slurp(s.dir / folder / "results.json");
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
      text.replace(at, from.size(), to);
    }
    s.write(folder + "/results.json", text);
  };
  rename("b", "\"springs\"", "\"other\"");  // another check's name, the same kept files: claimed twice
  const auto twice = s.run("golden report a b -o merged");
  CHECK(twice.code == 2);
  CHECK_MESSAGE(twice.err.find("both keep") != std::string::npos, twice.err);
  // One kept file's path the folder of the other's.
  fs::remove(s.dir / "b/states/springs.actual.csv");
  fs::create_directories(s.dir / "b/states/springs.actual.csv");
  fs::rename(s.dir / "b/states/springs.expected.csv", s.dir / "b/states/springs.actual.csv/inner.csv");
  rename("b", "states/springs.expected.csv", "states/springs.actual.csv/inner.csv");
  rename("b", "\"states/springs.actual.csv\"", "\"states/b.csv\"");
  fs::copy_file(s.dir / "a/states/springs.actual.csv", s.dir / "b/states/b.csv");
  const auto nested = s.run("golden report a b -o merged");
  CHECK(nested.code == 2);
  CHECK_MESSAGE(nested.err.find("the other's folder") != std::string::npos, nested.err);
  CHECK_FALSE(fs::exists(s.dir / "merged"));
  for (const auto& e : fs::directory_iterator(s.dir)) {
    CHECK_MESSAGE(e.path().filename().string().find("merged.partial") != 0, e.path());
  }
}

TEST_CASE("golden: names with control bytes reach the terminal escaped") {
  Hostile s;
  s.failingReport("a");
  std::string text = slurp(s.dir / "a/results.json");
  const std::string from = "\"name\": \"springs\"";
  REQUIRE(text.find(from) != std::string::npos);
  text.replace(text.find(from), from.size(), "\"name\": \"spr\\u001b]0;owned\\u0007ings\\u001b[2J\"");
  s.write("a/results.json", text);
  const auto r = s.run("golden report a -o merged");
  CHECK(r.code == 1);
  CHECK(r.out.find('\x1b') == std::string::npos);
  CHECK(r.out.find('\a') == std::string::npos);
  CHECK_MESSAGE(r.out.find("spr\\x1b]0;owned\\x07ings\\x1b[2J") != std::string::npos, r.out);
}

TEST_CASE("job: a row, a record or a job folder that points outside the sweep's folder is refused, exit 2") {
  Hostile s;
  s.write("sw.yaml",
          "scenarios: [springs.yaml]\ncommand: run\noptions: {duration: 0.1}\n"
          "parameters:\n  - {key: \"forces[1].ks\", values: [50, 60]}\n");
  REQUIRE(s.run("sweep sw.yaml -o out --emit parallel").code == 0);
  const fs::path out = s.dir / "out";
  const std::string table = slurp(out / "jobs.csv");
  auto edited = [&](const std::string& from, const std::string& to) {
    std::string t = table;
    const size_t at = t.find(from);
    REQUIRE(at != std::string::npos);
    return t.replace(at, from.size(), to);
  };
  SUBCASE("--stats and --record edited to files elsewhere") {
    const std::string stats = (out / "jobs/000000/stats.csv").string();
    const std::string record = (out / "jobs/000000/record.txt").string();
    REQUIRE(table.find(stats) != std::string::npos);
    s.write("out/jobs.csv", edited(record, (s.decoy / "new.txt").string()));
    auto r = s.run("job out 0");
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("outside the sweep's folder") != std::string::npos, r.err);
    s.write("out/jobs.csv", edited(stats, (s.decoy / "notes.txt").string()));
    r = s.run("job out 0");
    CHECK(r.code == 2);
    s.write("out/jobs.csv", edited(stats, (out / "jobs/000000/../../../decoy/notes.txt").string()));
    r = s.run("job out 0");
    CHECK(r.code == 2);
    // Inside the sweep's folder but over what the job reads, or into another job's folder.
    for (const fs::path& inside : {out / "jobs.csv", out / "jobs/000001/stats.csv"}) {
      CAPTURE(inside);
      s.write("out/jobs.csv", edited(stats, inside.string()));
      r = s.run("job out 0");
      CHECK(r.code == 2);
      CHECK_MESSAGE(r.err.find("outside the job's own folder jobs/000000") != std::string::npos, r.err);
    }
    CHECK_FALSE(fs::exists(out / "jobs/000001/stats.csv"));
  }
  SUBCASE("the record a link to a file elsewhere") {
    fs::create_symlink(s.decoy / "notes.txt", out / "jobs/000000/record.txt");
    const auto r = s.run("job out 0");
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("a symbolic link") != std::string::npos, r.err);
  }
  SUBCASE("an output a link to a file elsewhere") {
    fs::create_symlink(s.decoy / "notes.txt", out / "jobs/000000/stats.csv");
    const auto r = s.run("job out 0");
    CHECK(r.code == 2);
  }
  SUBCASE("the job's folder a link to a folder elsewhere") {
    fs::remove_all(out / "jobs/000000");
    fs::create_symlink(s.decoy, out / "jobs/000000");
    const auto r = s.run("job out 0");
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("a symbolic link") != std::string::npos, r.err);
  }
  SUBCASE("a regular file that is not a record") {
    s.write("out/jobs/000000/record.txt", "my notes, not a record\n");
    const auto r = s.run("job out 0");
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("not a job record") != std::string::npos, r.err);
    CHECK(slurp(out / "jobs/000000/record.txt") == "my notes, not a record\n");
  }
  s.decoyUntouched();
  // And the untouched row still runs.
  s.write("out/jobs.csv", table);
  fs::remove_all(out / "jobs/000001");
  fs::create_directories(out / "jobs/000001");
  const auto ok = s.run("job out 1");
  CHECK_MESSAGE(ok.code == 0, ok.err);
  CHECK(fs::exists(out / "jobs/000001/record.txt"));
}

TEST_CASE("sweep: an output folder whose jobs/, jobs.csv or job list leads elsewhere is refused, exit 2") {
  Hostile s;
  s.write("sw.yaml",
          "scenarios: [springs.yaml]\ncommand: run\noptions: {duration: 0.1}\n"
          "parameters:\n  - {key: \"forces[1].ks\", values: [50, 60]}\n");
  fs::create_directories(s.dir / "out");
  SUBCASE("jobs/ a link to a folder elsewhere") {
    fs::create_symlink(s.decoy, s.dir / "out/jobs");
  }
  SUBCASE("jobs.csv a link to a file elsewhere") {
    fs::create_symlink(s.decoy / "notes.txt", s.dir / "out/jobs.csv");
  }
  SUBCASE("jobs.txt a dangling link out") {
    fs::create_symlink("../decoy/new.txt", s.dir / "out/jobs.txt");
  }
  SUBCASE("sweep.sbatch a link out") {
    fs::create_symlink("../decoy/figure.png", s.dir / "out/sweep.sbatch");
  }
  const auto parallel = s.run("sweep sw.yaml -o out --emit parallel");
  const auto slurm = s.run("sweep sw.yaml -o out --emit slurm");
  CHECK(parallel.code + slurm.code >= 2);
  CHECK((parallel.code == 0 || parallel.code == 2));
  CHECK((slurm.code == 0 || slurm.code == 2));
  const std::string errors = parallel.err + slurm.err;
  CHECK_MESSAGE(Hostile::says(parallel.code ? parallel : slurm, "leads outside"), errors);
  s.decoyUntouched();
}

TEST_CASE("write sandbox: after restrictWritesBeneath the kernel refuses writes elsewhere") {
  Scratch s;
  fs::create_directories(s.dir / "inside");
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // 0: enforced and obeyed; 3: no Landlock here; 1, 2: a write went where it should not or not where it should.
    try {
      if (!particles::output::restrictWritesBeneath(s.dir / "inside")) ::_exit(3);
    } catch (...) {
      ::_exit(4);
    }
    if (!std::ofstream(s.dir / "inside" / "ok.txt").put('x')) ::_exit(1);
    if (std::ofstream(s.dir / "outside.txt").put('x')) ::_exit(2);
    ::_exit(0);
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 3) {
    particles::test::skipTest("this kernel has no Landlock: the job's checks before it runs stand alone");
    return;
  }
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(fs::exists(s.dir / "inside" / "ok.txt"));
  CHECK_FALSE(fs::exists(s.dir / "outside.txt"));
}
