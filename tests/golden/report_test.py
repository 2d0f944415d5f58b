#!/usr/bin/python3
"""The golden report and accepting frames from it (golden/README.md, "The report"), end to end in a
scratch folder, never in golden/: a golden frame made wrong on purpose (the frame one time step
later) fails its check; report.html names the test and links its expected, actual and diff
pictures, which are in the folder; `scripts/update-golden --from` refuses a folder without results
and a frame whose variants disagree, then accepts the actual frame into the scratch golden folder;
and the check passes again.

usage: report_test.py PARTICLES SOURCE_DIR CMAKE
"""
import html.parser
import os
import shutil
import subprocess
import sys
import tempfile

FRAME = "cloth_t2.5"
WRONG_AT = "2.51"  # one cloth time step (0.01 s) later: 2459 px differ (golden/README.md, signal table)
FAILING_TEST = "golden:report-test:cloth_t2.5"
# A name with HTML's special characters, which the report must show as text.
DIFFER_TEST = "golden:report-test:<b>next-step</b>&'quoted'"

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
    return condition


class LinkedFiles(html.parser.HTMLParser):
    """The report's text, its tags, and the pictures and links of each section by its id."""

    def __init__(self):
        super().__init__()
        self.text, self.tags, self.links = [], [], {}
        self.section = None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        self.tags.append(tag)
        if tag == "section":
            self.section = attrs.get("id")
            self.links[self.section] = {"img": [], "a": []}
        elif self.section is not None and tag in ("img", "a"):
            self.links[self.section][tag].append(attrs.get("src" if tag == "img" else "href"))

    def handle_endtag(self, tag):
        if tag == "section":
            self.section = None

    def handle_data(self, data):
        self.text.append(data)


def frame_line(source):
    """(scenario, --at, options) of FRAME in golden/frames.txt."""
    options = []
    with open(os.path.join(source, "golden", "frames.txt"), encoding="utf-8") as f:
        for line in f:
            words = line.split()
            if words[:1] == ["options:"]:
                options = words[1:]
            elif words[:1] == [FRAME]:
                scenario, at = words[1], words[2]
    return scenario, at, options


def run(command, env=None):
    return subprocess.run(command, capture_output=True, text=True, env=env)


def main():
    particles, source, cmake = sys.argv[1], sys.argv[2], sys.argv[3]
    scenario, at, options = frame_line(source)
    scenario_file = os.path.join(source, "scenarios", scenario + ".yaml")

    def render(out, when):
        run_ok([particles, "render", scenario_file, "-o", out, "--at", when, *options, "--quiet"])

    def check_frame(out_dir, golden_dir, name, test, expect="match", golden_command="ON"):
        return run([cmake, f"-DPARTICLES={particles}", f"-DSCENARIO={scenario_file}", f"-DAT={at}",
                    f"-DGOLDEN={os.path.join(golden_dir, FRAME + '.png')}", f"-DOUT_DIR={out_dir}",
                    f"-DNAME={name}", f"-DEXPECT={expect}", f"-DRENDER_OPTIONS={'|'.join(options)}",
                    f"-DTEST_NAME={test}", f"-DGOLDEN_COMMAND={golden_command}",
                    "-P", os.path.join(source, "tests", "golden", "check_frame.cmake")])

    def write_report(out_dir):
        return run_ok([sys.executable, os.path.join(source, "tests", "golden", "write_report.py"), out_dir])

    def update_golden(golden_dir, *args):
        env = dict(os.environ, PARTICLES=particles, GOLDEN_DIR=golden_dir)
        return run([os.path.join(source, "scripts", "update-golden"), *args], env=env)

    work = tempfile.mkdtemp(prefix="particles_golden_report_")
    try:
        wrong, right = os.path.join(work, "golden"), os.path.join(work, "golden-right")
        os.mkdir(wrong)
        os.mkdir(right)
        render(os.path.join(wrong, FRAME + ".png"), WRONG_AT)
        render(os.path.join(right, FRAME + ".png"), at)
        wrong_bytes = read_bytes(os.path.join(wrong, FRAME + ".png"))

        # A run against the wrong golden: the frame fails, the perturbation test passes (it differs).
        out = os.path.join(work, "run")
        check(check_frame(out, wrong, FRAME + ".default", FAILING_TEST).returncode != 0,
              "check_frame passed against a wrong golden frame")
        check(check_frame(out, wrong, FRAME + ".differ", DIFFER_TEST, "differ", "OFF").returncode == 0,
              "check_frame EXPECT=differ failed although the frames differ")
        printed = write_report(out)
        report = os.path.join(out, "report.html")
        check(report in printed, f"write_report.py does not print the report's path: {printed!r}")
        check_report(out, report)

        # update-golden --from: a folder without results, then a frame whose variants disagree.
        empty = os.path.join(work, "empty")
        os.mkdir(empty)
        r = update_golden(wrong, "--from", empty)
        check(r.returncode != 0 and "results" in r.stderr,
              f"update-golden --from a folder without results: exit {r.returncode}, {r.stderr!r}")
        disagree = os.path.join(work, "disagree")
        check_frame(disagree, wrong, FRAME + ".a", "golden:report-test:a")
        check_frame(disagree, right, FRAME + ".b", "golden:report-test:b")
        r = update_golden(wrong, "--from", disagree)
        check(r.returncode != 0 and "refused" in r.stderr and "disagree" in r.stderr,
              f"update-golden accepted a frame one variant fails and another passes: exit {r.returncode}, "
              f"{r.stdout!r} {r.stderr!r}")
        check(read_bytes(os.path.join(wrong, FRAME + ".png")) == wrong_bytes,
              "a refused update-golden changed the golden frame")

        # Accepting the run's frame, then the check passes.
        r = update_golden(wrong, "--from", out)
        check(r.returncode == 0 and f"accepted   {wrong}/{FRAME}.png" in r.stdout and "checked" in r.stdout,
              f"update-golden --from {out}: exit {r.returncode}, {r.stdout!r} {r.stderr!r}")
        check(read_bytes(os.path.join(wrong, FRAME + ".png")) == read_bytes(os.path.join(out, FRAME + ".default.png")),
              "the golden frame is not the accepted actual frame")
        again = os.path.join(work, "again")
        r = check_frame(again, wrong, FRAME + ".default", FAILING_TEST)
        check(r.returncode == 0, f"the check still fails after update-golden --from: {r.stdout} {r.stderr}")
        write_report(again)
        with open(os.path.join(again, "report.html"), encoding="utf-8") as f:
            check("1 test, all pass" in f.read(), "the report after accepting does not say that all pass")
    finally:
        shutil.rmtree(work)

    for failure in failures:
        print("FAILED:", failure, file=sys.stderr)
    if failures:
        sys.exit(1)
    print("report names the failing frame with its three pictures; update-golden --from accepts it, refuses "
          "a folder without results and disagreeing variants; the check passes again")


def check_report(out, report):
    parsed = LinkedFiles()
    with open(report, encoding="utf-8") as f:
        parsed.feed(f.read())
    text = "".join(parsed.text)
    check("1 of 2 tests failing" in text, "the report's headline does not count 1 failing test of 2")
    links = parsed.links.get(FAILING_TEST)
    if not check(links is not None, f"no section for {FAILING_TEST} in the report"):
        return
    check(len(links["img"]) == 3, f"{FAILING_TEST}: {len(links['img'])} pictures, not expected, actual and diff")
    for src in links["img"] + links["a"]:
        path = os.path.join(out, src)
        check("/" not in src and os.path.isfile(path), f"{FAILING_TEST} links {src!r}, not a file beside the report")
    check(f"{FRAME}.default.expected.png" in links["img"], "the golden frame is not copied beside the report")
    # The numbers of the result file, as the report shows them.
    with open(os.path.join(out, "results", FRAME + ".default.txt"), encoding="utf-8") as f:
        result = dict(line.split("=", 1) for line in f.read().splitlines())
    for shown in (f"{result['differing']} of {result['pixels']} px ({result['share_percent']} %)",
                  f"{result['largest']} of 255", result["box"],
                  f"threshold {result['threshold']}, bound {result['bound_percent']} %",
                  result["render_command"]):
        check(shown in text, f"the report does not show {shown!r}")
    check(DIFFER_TEST in text and "b" not in parsed.tags, "the test name with <, & and ' is not shown as text")
    check(f"{DIFFER_TEST}differ" in text, "the perturbation test is not listed as passing, expected to differ")


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def run_ok(command):
    r = run(command)
    if r.returncode != 0:
        sys.exit(f"{' '.join(command)}: exit {r.returncode}\n{r.stdout}{r.stderr}")
    return r.stdout


if __name__ == "__main__":
    main()
