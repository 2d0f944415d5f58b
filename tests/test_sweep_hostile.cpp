// Sweeps, jobs and gather under hostile input: a sweep file may come from someone else
// and a sweep's folder may be touched by anyone, yet no value, path or name is ever executed, a
// job list is one line per job whatever the values hold, a reserved column cannot be a parameter,
// counts are checked before anything is built, and every file read is bounded and refused without
// blocking when it is not a regular file. The emitted lists run under real GNU parallel and under
// bash as Slurm's array tasks would, one index past the end included.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "app/job_record.hpp"
#include "app/job_table.hpp"
#include "cli_support.hpp"
#include "source_tree.hpp"

using particles::test::kSource;

namespace {

using particles::test::lines;
using particles::test::Scratch;
using particles::test::slurp;
namespace fs = std::filesystem;
using Usage = Scratch::Usage;


// Every file under `dir` whose name contains PWNED: what an executed value would have made.
std::vector<std::string> pwned(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().filename().string().find("PWNED") != std::string::npos &&
        e.path().filename().string().find("$(") == std::string::npos) {
      found.push_back(e.path().string());
    }
  }
  return found;
}

// `sh -c 'printf %s WORD'`'s output through bash, for a word shellQuote wrote.
std::string bashPrints(const std::string& quoted) {
  Scratch s;
  s.write("word.sh", "printf %s " + quoted);
  bool ok = false;
  std::string out = particles::test::commandOutput("bash '" + (s.dir / "word.sh").string() + "'", ok);
  REQUIRE(ok);
  return out;
}

// Values that once ran as commands or split a job's line, in YAML double quotes.
const std::vector<std::string> kHostileYaml = {R"y("x\ntouch PWNED1\n")y",
                                               R"y("$(touch PWNED2)")y",
                                               R"y("'`touch PWNED3`'")y",
                                               R"y("a'; touch PWNED4; echo '")y",
                                               R"y("\"; touch PWNED5; \"")y",
                                               R"y("a\rb\tc\\d")y",
                                               "y"};

std::string hostileSweep(const std::string& extra = "") {
  std::string values;
  for (const std::string& v : kHostileYaml) values += (values.empty() ? "" : ", ") + v;
  return "scenarios: [" + kSource +
         "/scenarios/springs.yaml]\ncommand: run\n"
         "options: {duration: 0.05, set: {simulation.dt: 0.01, description: \"s\\n$(touch PWNED6)'\"}}\n"
         "parameters:\n  - {key: name, values: [" +
         values + "]}\n" + extra;
}

}  // namespace

TEST_CASE("shellQuote: bash reads every word back byte for byte, on one line, and splitCommandText inverts it") {
  std::vector<std::string> words = {"plain",     "",     "with space", "it's",  "a\nb",         "$(touch PWNED)",
                                    "`x`",       "\\",   "'",          "\\'",   "\t\r\x01\x7f", "ü — ok",
                                    "--set=a b", "$'x'", "\"q\"",      "a'\n'b"};
  std::mt19937 random(26);  // fixed seed: the same words every run
  for (int i = 0; i < 200; ++i) {
    std::string w(size_t(random() % 12), ' ');
    for (char& c : w) c = char(1 + random() % 255);  // any byte but NUL, which argv cannot hold
    words.push_back(w);
  }
  const std::string text = particles::app::commandText(words);
  CHECK(text.find('\n') == std::string::npos);
  CHECK(text.find('\r') == std::string::npos);
  const auto back = particles::app::splitCommandText(text);
  REQUIRE(back.has_value());
  CHECK(*back == words);
  // bash itself: the hand-picked words and a sample of the random ones.
  for (size_t i = 0; i < 24; ++i) {
    CAPTURE(words[i]);
    CHECK(bashPrints(particles::app::shellQuote(words[i])) == words[i]);
  }
  for (const char* bad : {"a'b", "$'\\q'", "a b'", "a;b", "a|b", "$'\\x4'"}) {
    CAPTURE(bad);
    CHECK_FALSE(particles::app::splitCommandText(bad).has_value());
  }
}

TEST_CASE("sweep: hostile values run as data under GNU parallel and as Slurm array tasks, never as commands") {
  Scratch s;
  // The program under a name a shell would expand, and an output folder too.
  const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
  const fs::path program = s.dir / "p $(touch PWNED7)";
  fs::create_symlink(exe, program);
  s.write("hostile.yaml", hostileSweep());
  const std::string out = "o $(touch PWNED8) ';x";
  using particles::app::shellQuote;
  const auto r =
      s.run("sweep hostile.yaml -o " + shellQuote(out) + " --emit parallel --program " + shellQuote(program.string()));
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const fs::path outDir = s.dir / out;
  const auto list = lines(slurp(outDir / "jobs.txt"));
  REQUIRE(list.size() == kHostileYaml.size());  // one line per job
  for (size_t i = 0; i < list.size(); ++i) {
    CHECK(list[i] == particles::app::commandText({program.string(), "job", outDir.string(), std::to_string(i)}));
  }

  bool ok = false;
  const std::string log = particles::test::commandOutput("cd " + shellQuote(s.dir.string()) +
                                                             " && parallel --will-cite --joblog joblog.txt < " +
                                                             shellQuote((outDir / "jobs.txt").string()) + " 2>&1",
                                                         ok);
  CHECK_MESSAGE(ok, log);
  CHECK(pwned(s.dir).empty());
  CHECK(lines(slurp(s.dir / "joblog.txt")).size() == kHostileYaml.size() + 1);  // header + one per job
  const auto gathered = s.run("gather " + shellQuote(out));
  CHECK_MESSAGE(gathered.out.find(std::to_string(kHostileYaml.size()) +
                                  " jobs: " + std::to_string(kHostileYaml.size()) + " ok") != std::string::npos,
                gathered.out << gathered.err);
  // Each job's record holds its value, as data: the first job's name has its newline.
  const std::string record = slurp(outDir / "jobs/000000/record.txt");
  CHECK(record.find("--set $'name=x\\ntouch PWNED1\\n'") != std::string::npos);

  // The same folder as a Slurm array: every index runs (done before: skipped), one past the end is
  // refused, and nothing is executed on any of them.
  const auto slurm =
      s.run("sweep hostile.yaml -o " + shellQuote(out) + " --emit slurm --program " + shellQuote(program.string()));
  REQUIRE_MESSAGE(slurm.code == 0, slurm.err);
  for (size_t i = 0; i <= kHostileYaml.size(); ++i) {
    CAPTURE(i);
    const std::string task = particles::test::commandOutput(
        "cd " + shellQuote(s.dir.string()) + " && SLURM_ARRAY_TASK_ID=" + std::to_string(i) + " bash " +
            shellQuote((outDir / "sweep.sbatch").string()) + " 2>&1",
        ok);
    if (i < kHostileYaml.size()) {
      CHECK_MESSAGE(ok, task);
      CHECK_MESSAGE(task.find("skipped") != std::string::npos, task);
    } else {
      CHECK_FALSE(ok);
      CHECK_MESSAGE(task.find("no job " + std::to_string(i)) != std::string::npos, task);
    }
  }
  CHECK(pwned(s.dir).empty());
  CHECK_MESSAGE(slurp(outDir / "sweep.sbatch").find("eval") == std::string::npos, slurp(outDir / "sweep.sbatch"));
}

TEST_CASE("sweep: a split render's segments and joins run as jobs by index, the joins under concat.sbatch") {
  Scratch s;
  s.write("swing.yaml", particles::test::kSwingScenario);
  // options.duration shortens the video: the segments are counted from it.
  s.write("split.yaml",
          "scenarios: [swing.yaml]\ncommand: render\nsplit: 2\n"
          "options: {duration: 0.4, msaa: 1}\n"
          "parameters:\n  - {key: name, values: [\"a\\n$(touch PWNED)\"]}\n");
  const auto r = s.run("sweep split.yaml -o out --jobs 2");
  REQUIRE_MESSAGE(r.code == 0, r.err << r.out);
  const auto csv = particles::app::readJobTable(s.dir / "out", 64);
  REQUIRE(csv.rows.size() == 3);
  CHECK(csv.rows[0][csv.commandColumn()].find("--frames 0:2") != std::string::npos);
  CHECK(csv.rows[1][csv.commandColumn()].find("--frames 2:4") != std::string::npos);
  CHECK(slurp(s.dir / "out/jobs/000002/record.txt").find("value.frames: 4") != std::string::npos);

  const auto slurm = s.run("sweep split.yaml -o out --emit slurm");
  REQUIRE_MESSAGE(slurm.code == 0, slurm.err);
  const std::string concat = slurp(s.dir / "out/concat.sbatch");
  CHECK(concat.find("#SBATCH --array=0-0\n") != std::string::npos);
  CHECK(concat.find("job " + (s.dir / "out").string() + " \"$((2 + SLURM_ARRAY_TASK_ID))\"") != std::string::npos);
  bool ok = false;
  const std::string task = particles::test::commandOutput(
      "SLURM_ARRAY_TASK_ID=1 bash '" + (s.dir / "out/concat.sbatch").string() + "' 2>&1", ok);
  CHECK_FALSE(ok);
  CHECK_MESSAGE(task.find("no job 3") != std::string::npos, task);
  CHECK(pwned(s.dir).empty());
}

TEST_CASE("sweep: a path with a line break cannot go into a job list, values with one can") {
  Scratch s;
  s.write("hostile.yaml", hostileSweep());
  const auto r = s.run("sweep hostile.yaml -o 'o\ntouch PWNED' --emit parallel");
  CHECK(r.code == 2);
  CHECK_MESSAGE(r.err.find("control character") != std::string::npos, r.err);
  CHECK(pwned(s.dir).empty());
  CHECK(s.files().size() == 1);  // refused before anything was written: only the sweep file
}

TEST_CASE("sweep: the columns the sweep writes itself cannot be parameters' names") {
  const std::string head = "scenarios: [" + kSource + "/scenarios/springs.yaml]\ncommand: run\nparameters:\n";
  for (const char* name :
       {"index", "stage", "scenario", "segment", "dir", "command", "status", "exit", "seconds", "message"}) {
    CAPTURE(name);
    Scratch s;
    s.write("bad.yaml", head + "  - {key: dt, values: [0.01], name: " + name + "}\n");
    const auto r = s.run("sweep bad.yaml -o out");
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("bad.yaml:4:37: error: ") != std::string::npos, r.err);
    CHECK_MESSAGE(r.err.find("names a column the sweep writes itself") != std::string::npos, r.err);
    CHECK_FALSE(fs::exists(s.dir / "out"));
  }
}

TEST_CASE("sweep: bad numbers and oversized files are refused early, with the file and line, in bounded time") {
  const std::string head = "scenarios: [" + kSource + "/scenarios/springs.yaml]\ncommand: run\nparameters:\n";
  SUBCASE("a range of subnormal numbers") {
    Scratch s;
    s.write("bad.yaml", head + "  - {key: dt, range: {from: 1e-310, to: 1e-300, count: 2}}\n");
    const auto r = s.run("sweep bad.yaml -o out");
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find("bad.yaml:4:") != std::string::npos, r.err);
    CHECK(r.err.find("internal error") == std::string::npos);
  }
  SUBCASE("an fps option past what a number holds") {
    Scratch s;
    s.write("bad.yaml", "scenarios: [" + kSource +
                            "/scenarios/springs.yaml]\ncommand: render\nsplit: 2\n"
                            "options: {fps: 1e-400}\n");
    const auto r = s.run("sweep bad.yaml -o out");
    CHECK(r.code == 2);
    CHECK(r.err.find("internal error") == std::string::npos);
  }
  // 10⁶ values on one line (2 MB: yaml-cpp alone took 380 MB for them), 3 × 10⁶ in block form
  // (6 MB), and two crossed lists of 10⁵ values (refused once the second is read). Under the
  // sanitizers, where no bound on time or memory is checked, 2 × 10⁵ in each form: past the limit
  // all the same, in a fifth of the case's time there.
  const int flowValues = particles::test::kSanitized ? 200'000 : 1'000'000;
  const int blockValues = particles::test::kSanitized ? 200'000 : 3'000'000;
  std::string flow, block, crossed;
  for (int i = 1; i <= flowValues; ++i) {
    if (i > 1) flow += ',';  // not (i > 1 ? "," : "") + …: GCC 12's -O3 -Wrestrict false positive (bug 105329)
    flow += std::to_string(i);
  }
  for (int i = 1; i <= blockValues; ++i) block += "      - " + std::to_string(i) + "\n";
  for (int k = 1; k <= 2; ++k) {
    crossed += "  - {key: 'forces[" + std::to_string(k) + "].ks', range: {from: 1, to: 2, count: 100000}}\n";
  }
  const std::vector<std::pair<std::string, std::string>> big = {
      {head + "  - {key: dt, values: [" + flow + "]}\n", "bad.yaml:4:23: error: a list of more than 100000 items"},
      {head + "  - key: dt\n    values:\n" + block, "bad.yaml:6:7: error: a list of more than 100000 items"},
      {head + crossed, "more than 100000 jobs"}};
  for (const auto& [text, message] : big) {
    Scratch s;
    s.write("bad.yaml", text);
    Usage used;
    const auto r = s.runBounded("sweep bad.yaml -o out", used);
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find(message) != std::string::npos, r.err);
    if (!particles::test::kSanitized) {
      CHECK(used.cpuSeconds < 2.0);
      CHECK(used.peakMiB < 300.0);
    }
  }
}

TEST_CASE("gather and job: a tampered folder is read within bounds and refused with the file and line") {
  Scratch s;
  s.write("ok.yaml", "scenarios: [" + kSource +
                         "/scenarios/springs.yaml]\ncommand: run\noptions: {duration: 0.05}\n"
                         "parameters:\n  - {key: dt, values: [0.01, 0.02, 0.025]}\n");
  REQUIRE(s.run("sweep ok.yaml -o out --jobs 1").code == 0);
  const fs::path out = s.dir / "out";
  const std::string table = slurp(out / "jobs.csv");

  SUBCASE("a FIFO, a huge file and a flood of keys as records") {
    fs::remove(out / "jobs/000000/record.txt");
    REQUIRE(::mkfifo((out / "jobs/000000/record.txt").c_str(), 0644) == 0);
    s.write("huge", "");
    fs::resize_file(s.dir / "huge", std::uintmax_t(1) << 30);  // sparse: 1 GiB on no disk
    fs::remove(out / "jobs/000001/record.txt");
    fs::create_symlink(s.dir / "huge", out / "jobs/000001/record.txt");
    std::string flood = slurp(out / "jobs/000002/record.txt");
    // 50,000 keys; 5,000 under the sanitizers, where the bounds below are not checked.
    const int keys = particles::test::kSanitized ? 5'000 : 50'000;
    for (int k = 0; k < keys; ++k) flood += "value.k" + std::to_string(k) + ": " + std::to_string(k) + "\n";
    s.write("out/jobs/000002/record.txt", flood);
    Usage used;
    const auto r = s.runBounded("gather out", used);
    CHECK_MESSAGE(r.code == 0, r.err);
    CHECK_MESSAGE(r.err.find("record.txt: cannot read: it is a FIFO") != std::string::npos, r.err);
    CHECK_MESSAGE(r.err.find("larger than the input limit of 64 MiB") != std::string::npos, r.err);
    CHECK_MESSAGE(r.out.find("1 ok, 0 failed, 0 not run, 2 with unreadable records") != std::string::npos, r.out);
    if (!particles::test::kSanitized) {
      CHECK(used.cpuSeconds < 2.0);
      CHECK(used.peakMiB < 300.0);
    }
    // The job itself refuses a FIFO as its record rather than waiting on it.
    const auto job = s.runBounded("job out 0", used);
    CHECK(job.code == 2);
    CHECK_MESSAGE(job.err.find("not a regular file") != std::string::npos, job.err);
  }
  SUBCASE("a FIFO as jobs.csv") {
    fs::remove(out / "jobs.csv");
    REQUIRE(::mkfifo((out / "jobs.csv").c_str(), 0644) == 0);
    Usage used;
    for (const char* command : {"gather out", "job out 0"}) {
      const auto r = s.runBounded(command, used);
      CHECK(r.code == 2);
      CHECK_MESSAGE(r.err.find("jobs.csv: cannot read: it is a FIFO") != std::string::npos, r.err);
    }
  }
  SUBCASE("rows that point elsewhere, a column twice, a command of another stage") {
    const auto replaced = [&](const std::string& from, const std::string& to) {
      std::string t = table;
      const size_t at = t.find(from);
      REQUIRE(at != std::string::npos);
      return t.replace(at, from.size(), to);
    };
    const std::vector<std::pair<std::string, std::string>> cases = {
        {replaced("jobs/000001", "../../etc"), "jobs.csv:3: job 1's folder is '../../etc', not jobs/000001"},
        {replaced("index,stage,scenario,dt", "index,stage,scenario,dir"), "the column 'dir' appears twice"},
        {replaced("1,run,", "7,run,"), "jobs.csv:3: index '7' where job 1 belongs"},
        {replaced(" run /", " sweep /"), "jobs.csv:2: job 0 is a run job, but its command runs 'sweep'"},
    };
    for (const auto& [text, message] : cases) {
      CAPTURE(message);
      s.write("out/jobs.csv", text);
      const auto job = s.run("job out 0");
      CHECK(job.code == 2);
      CHECK_MESSAGE(job.err.find(message) != std::string::npos, job.err);
      if (message.find("sweep") == std::string::npos) {
        const auto gather = s.run("gather out");
        CHECK(gather.code == 2);
        CHECK_MESSAGE(gather.err.find(message) != std::string::npos, gather.err);
      }
    }
  }
  SUBCASE("an index that is not a job's") {
    for (const char* index : {"3", "-1", "x", "1e2", "99999999999999999999999"}) {
      CAPTURE(index);
      const auto r = s.run(std::string("job out ") + index);
      CHECK(r.code == 2);
      CHECK(r.err.find("internal error") == std::string::npos);
    }
  }
}

TEST_CASE("job record: parsing is linear and takes a repeated key's last value") {
  std::string text = "version: v\ncommand: run x\nexit: 0\nseconds: 1.5\n";
  for (int k = 0; k < 200'000; ++k) text += "value.k" + std::to_string(k % 1000) + ": " + std::to_string(k) + "\n";
  const auto r = particles::app::parseJobRecord(text);
  REQUIRE(r.has_value());
  REQUIRE(r->headline.size() == 1000);
  CHECK(r->headline[7].first == "k7");
  CHECK(r->headline[7].second == 199'007);
  CHECK_FALSE(particles::app::parseJobRecord("version: v\nexit: 300\n").has_value());
  CHECK_FALSE(particles::app::parseJobRecord("version: v\nexit: 1e400\n").has_value());
  CHECK_FALSE(particles::app::parseJobRecord("command: x\nexit: 0\n").has_value());
}
