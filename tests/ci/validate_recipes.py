#!/usr/bin/python3
"""Checks the CI recipes of docs/ci/ (docs/ci/README.md), so that a user copying them gets a
pipeline that CI accepts and that does what the README says.

  github SOURCE_DIR   docs/ci/github-actions.yml passes @action-validator/cli 0.6.0 (GitHub's
                      workflow schema; installed by scripts/npm-tools from npm's registry, and a
                      failure when it cannot be), and a copy with an unknown key in a step fails
                      it, naming the key: the validator is really checking. Then the structure
                      the README promises (below), which must also fail on broken copies.
  gitlab SOURCE_DIR   docs/ci/gitlab-ci.yml has the structure the README promises; GitLab has no
                      offline validator, so each promise is checked here on the parsed YAML, and
                      each check must fail on a copy broken on purpose.

Both: particles comes from the release archive named by PARTICLES_ARCHIVE_URL, and nothing is
built. Each job's set-up commands (those before its `particles golden` command) are also run, in
a scratch folder, on a stand-in archive served from a file:// URL, with `apt-get` replaced by a
stub that only records its arguments (and curl or xz by stand-ins where the machine has none):
they must put the stand-in's `particles` on the PATH and run its --version; with the variable
unset they must stop before anything else, naming it; with a wrong PARTICLES_ARCHIVE_SHA256
they must fail.

usage: validate_recipes.py github|gitlab SOURCE_DIR
"""
import copy
import functools
import hashlib
import io
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile

import yaml

# Under CTest's TIMEOUT (300 s, CMakeLists.txt), so that an unreachable registry ends with the
# message below rather than a killed test. scripts/npm-tools gives up after about 3 min on a
# registry that never answers, 15 s on a refused connection.
NPM_TOOLS_TIMEOUT = 270
VALIDATOR_TIMEOUT = 60
UNKNOWN_KEY = "frobnicate-particles"
ARCHIVE_VARIABLE = "PARTICLES_ARCHIVE_URL"
STAND_IN_VERSION = "particles 9.9.9 build stand-in"
# What building particles takes, which the recipes no longer do (docs/ci/README.md, "What they do").
BUILD_COMMANDS = re.compile(r"\b(cmake|ninja|make|g\+\+|gcc|clang|build-essential|git (clone|fetch|init))\b"
                            r"|scripts/deps|PARTICLES_REPO|PARTICLES_REF")
SETUP_TIMEOUT = 60


def fail(message):
    print(f"FAILED: {message}", file=sys.stderr)
    sys.exit(1)


def script_text(lines):
    """A job's commands as one string (GitLab: a list of strings; GitHub: one `run` string)."""
    if isinstance(lines, str):
        return lines
    return "\n".join(str(line) for line in lines or [])


def command_lines(text):
    """Shell lines with backslash continuations joined, so one command is one line."""
    return re.sub(r"\\\n\s*", " ", text).splitlines()


# --- Both: the set-up commands ------------------------------------------------------------------


def setup_problems(job, text):
    """What the README promises of job `job`'s set-up commands `text` and they lack, read."""
    problems = []
    lines = command_lines(text)
    if not re.search(r'-z\s+"\$\{?' + ARCHIVE_VARIABLE + r'(:-)?\}?"', text):
        problems.append(f"job `{job}` does not stop when {ARCHIVE_VARIABLE} is empty")
    if not any(re.search(r"\bcurl\b", line) and "-fsSL" in line and "--retry" in line and ARCHIVE_VARIABLE in line
               for line in lines):
        problems.append(f"job `{job}` does not download ${ARCHIVE_VARIABLE} with `curl -fsSL --retry …`")
    if not any(re.search(r"\btar\b", line) and "-xJ" in line and "--strip-components=1" in line
               and re.search(r"-C\s+\.particles\b", line) for line in lines):
        problems.append(f"job `{job}` does not unpack with `tar -xJ --strip-components=1 -C .particles`")
    if ".particles/bin" not in text:
        problems.append(f"job `{job}` does not put .particles/bin on the PATH")
    if not any(re.match(r"\s*particles --version\b", line) for line in lines):
        problems.append(f"job `{job}` does not print `particles --version`")
    built = BUILD_COMMANDS.search(text)
    if built:
        problems.append(f"job `{job}` builds or clones particles (`{built.group(0)}`): it takes the archive")
    return problems


def stand_in_archive(folder):
    """A particles-9.9.9-linux-x86_64.tar.xz whose bin/particles answers --version only."""
    path = os.path.join(folder, "particles-9.9.9-linux-x86_64.tar.xz")
    program = (f'#!/bin/sh\n[ "$1" = --version ] && {{ echo "{STAND_IN_VERSION}"; exit 0; }}\n'
               'echo "the stand-in answers --version only" >&2\nexit 99\n').encode()
    with tarfile.open(path, "w:xz") as archive:
        for name, data, mode in (("bin/particles", program, 0o755), ("lib/bundled/README", b"stand-in\n", 0o644)):
            info = tarfile.TarInfo("particles-9.9.9-linux-x86_64/" + name)
            info.size, info.mode = len(data), mode
            archive.addfile(info, io.BytesIO(data))
    return path


def stub_commands(folder):
    """A folder to put first on the PATH: apt-get recording its arguments (nothing is installed),
    and curl (file:// only) and xz -d (Python's lzma) where this machine lacks them."""
    os.makedirs(folder)
    stubs = {"apt-get": '#!/bin/sh\necho "$*" >> "$APT_GET_LOG"\n'}
    if not shutil.which("curl"):
        stubs["curl"] = (f"#!{sys.executable}\nimport shutil, sys, urllib.parse, urllib.request\n"
                         "args = sys.argv[1:]\nout = args[args.index('-o') + 1]\nurl = args[-1]\n"
                         "if not url.startswith('file://'): sys.exit('curl stand-in: ' + repr(url) + ' is no file:// URL')\n"
                         "shutil.copyfile(urllib.request.url2pathname(urllib.parse.urlparse(url).path), out)\n")
    if not shutil.which("xz"):
        stubs["xz"] = (f"#!{sys.executable}\nimport lzma, sys\n"
                       "assert '-d' in sys.argv[1:], sys.argv\n"
                       "sys.stdout.buffer.write(lzma.decompress(sys.stdin.buffer.read()))\n")
    for name, text in stubs.items():
        path = os.path.join(folder, name)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        os.chmod(path, 0o755)


def rehearse(job, scripts, github):
    """Runs job `job`'s set-up commands (shell texts, in order, each as its runner does: GitHub
    one bash per step with $GITHUB_PATH read after each, GitLab one bash for all) on a stand-in
    archive: with the variable set, unset, and with a wrong SHA-256. What went wrong."""
    return list(rehearsed(job, tuple(scripts), github))


@functools.lru_cache(maxsize=None)   # the copies broken on purpose mostly leave the set-up as it was
def rehearsed(job, scripts, github):
    problems = []
    with tempfile.TemporaryDirectory(prefix="ci-setup.") as scratch:
        archive = stand_in_archive(scratch)
        with open(archive, "rb") as f:
            sha256 = hashlib.sha256(f.read()).hexdigest()
        stubs = os.path.join(scratch, "stubs")
        stub_commands(stubs)
        cases = (("set", pathlib.Path(archive).as_uri(), sha256),
                 ("unset", "", ""),
                 ("wrong SHA-256", pathlib.Path(archive).as_uri(), "0" * 64))
        for case, url, digest in cases:
            work = os.path.join(scratch, case.replace(" ", "-"))
            temp = work + ".tmp"
            os.makedirs(work)
            os.makedirs(temp)
            env = {k: v for k, v in os.environ.items() if not k.startswith(("PARTICLES_", "GITHUB_", "CI_"))}
            env.update(PARTICLES_ARCHIVE_URL=url, PARTICLES_ARCHIVE_SHA256=digest, TMPDIR=temp, RUNNER_TEMP=temp,
                       APT_GET_LOG=os.path.join(temp, "apt-get.log"), GITHUB_PATH=os.path.join(temp, "github-path"),
                       GITHUB_WORKSPACE=work)
            output, code, added = "", 0, []
            for script in scripts if github else ["\n".join(scripts)]:
                if "${{" in script:
                    problems.append(f"job `{job}`: a set-up step holds a ${{{{ }}}} expression; it cannot be run here")
                    return tuple(problems)
                env["PATH"] = os.pathsep.join([stubs] + added + [os.environ.get("PATH", "")])
                try:
                    done = subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", script],
                                          cwd=work, env=env, capture_output=True, text=True, timeout=SETUP_TIMEOUT)
                except subprocess.TimeoutExpired:
                    problems.append(f"job `{job}`, {ARCHIVE_VARIABLE} {case}: its set-up ran over {SETUP_TIMEOUT} s")
                    break
                output += done.stdout + done.stderr
                code = done.returncode
                if code != 0:
                    break
                if os.path.exists(env["GITHUB_PATH"]):   # GitHub puts the newest first
                    with open(env["GITHUB_PATH"], encoding="utf-8") as f:
                        added = [line for line in reversed(f.read().splitlines()) if line]
            installed = ""
            if os.path.exists(env["APT_GET_LOG"]):
                with open(env["APT_GET_LOG"], encoding="utf-8") as f:
                    installed = f.read()
            where = f"job `{job}`, {ARCHIVE_VARIABLE} {case if case != 'wrong SHA-256' else 'set, with a wrong SHA-256'}"
            if case == "set":
                if code != 0:
                    problems.append(f"{where}: the set-up fails (exit {code}):\n{output[-2000:]}")
                elif not os.access(os.path.join(work, ".particles", "bin", "particles"), os.X_OK):
                    problems.append(f"{where}: no .particles/bin/particles after the set-up")
                elif STAND_IN_VERSION not in output:
                    problems.append(f"{where}: the archive's `particles --version` never ran from the PATH:\n{output[-2000:]}")
                if github and installed:
                    problems.append(f"{where}: installs packages (apt-get {installed.strip()}); the runner has what it needs")
                if not github and not any({"install", "curl", "xz-utils", "ca-certificates"} <= set(line.split())
                                          for line in installed.splitlines()):
                    problems.append(f"{where}: does not apt-get install curl xz-utils ca-certificates (got {installed!r})")
            elif case == "unset":
                if code == 0:
                    problems.append(f"{where}: the set-up succeeds")
                elif ARCHIVE_VARIABLE not in output:
                    problems.append(f"{where}: the set-up fails without naming {ARCHIVE_VARIABLE}:\n{output[-2000:]}")
                if installed or os.listdir(work):
                    problems.append(f"{where}: the set-up does something before stopping (apt-get: {installed!r}; "
                                    f"in the checkout: {sorted(os.listdir(work))})")
            elif code == 0:
                problems.append(f"{where}: the set-up succeeds")
    return tuple(problems)


# --- GitHub Actions ----------------------------------------------------------------------------


def action_validator(source):
    """The path of action-validator, installed by scripts/npm-tools, or a failure saying why."""
    npm_tools = os.path.join(source, "scripts", "npm-tools")
    try:
        done = subprocess.run([npm_tools], capture_output=True, text=True, timeout=NPM_TOOLS_TIMEOUT)
    except subprocess.TimeoutExpired:
        fail(f"scripts/npm-tools did not install @action-validator/cli within {NPM_TOOLS_TIMEOUT} s: "
             "is npm's registry reachable from here (npm config get registry)? This test needs it.")
    if done.returncode != 0:
        fail("scripts/npm-tools could not install @action-validator/cli (exit "
             f"{done.returncode}); this test needs npm's registry, or the tool already in "
             "PARTICLES_NPM_TOOLS_DIR (default ~/.cache/particles/npm-tools). Its output:\n"
             + done.stderr[-4000:])
    lines = done.stdout.strip().splitlines()
    if len(lines) != 1 or not os.access(lines[0], os.X_OK):
        fail(f"scripts/npm-tools printed {done.stdout!r}, not the path of an executable action-validator")
    return lines[0]


def validate(validator, path):
    done = subprocess.run([validator, path], capture_output=True, text=True, timeout=VALIDATOR_TIMEOUT)
    return done.returncode, done.stdout + done.stderr


def with_unknown_step_key(text):
    """The workflow with UNKNOWN_KEY added to its first step that has a name."""
    match = re.search(r"^(\s*)- name: .*$", text, flags=re.MULTILINE)
    if not match:
        fail("docs/ci/github-actions.yml has no `- name:` step to break on purpose")
    indent = match.group(1) + "  "
    return text[:match.end()] + f"\n{indent}{UNKNOWN_KEY}: true" + text[match.end():]


def github_problems(workflow):
    """What docs/ci/github-actions.yml promises (docs/ci/README.md) and `workflow` lacks."""
    problems = []
    jobs = workflow.get("jobs") or {}
    env = workflow.get("env") or {}
    if "vars." + ARCHIVE_VARIABLE not in str(env.get(ARCHIVE_VARIABLE, "")):
        problems.append(f"env has no {ARCHIVE_VARIABLE} from the repository variable vars.{ARCHIVE_VARIABLE}")

    def steps_of(job):
        return (jobs.get(job) or {}).get("steps") or []

    def uses(job, action):
        return [s for s in steps_of(job) if str(s.get("uses", "")).startswith(action + "@")]

    def always(step):
        return "always()" in str(step.get("if", ""))

    for job in ("golden", "merge"):
        if job not in jobs:
            problems.append(f"no job `{job}`")
            continue
        if jobs[job].get("runs-on") not in ("ubuntu-24.04", "ubuntu-latest"):
            problems.append(f"job `{job}` does not run on ubuntu-24.04 (or ubuntu-latest)")
        if "container" in jobs[job]:
            problems.append(f"job `{job}` runs in a container: the archive needs none (docs/ci/README.md)")
        runs = [script_text(s.get("run")) for s in steps_of(job)]
        first = next((i for i, run in enumerate(runs) if "particles golden" in run), len(runs))
        setup = [run for run in runs[:first] if run]
        problems += setup_problems(job, "\n".join(setup))
        if not BUILD_COMMANDS.search("\n".join(setup)):   # a build is not run here
            problems += rehearse(job, setup, github=True)
        built = BUILD_COMMANDS.search("\n".join(runs[first:]))
        if built:
            problems.append(f"job `{job}` builds or clones particles (`{built.group(0)}`): it takes the archive")
        if uses(job, "actions/cache") or uses(job, "actions/cache/restore") or uses(job, "actions/cache/save"):
            problems.append(f"job `{job}` caches a build: the archive needs none")

    golden = jobs.get("golden") or {}
    strategy = golden.get("strategy") or {}
    if (strategy.get("matrix") or {}).get("shard") != [1, 2]:
        problems.append("job `golden` has no matrix shard: [1, 2]")
    if strategy.get("fail-fast") is not False:
        problems.append("job `golden` does not set fail-fast: false (a failing shard would cancel the other)")
    checks = [line for s in steps_of("golden") for line in command_lines(script_text(s.get("run")))
              if "particles golden check" in line]
    if len(checks) != 1:
        problems.append(f"job `golden` runs `particles golden check` {len(checks)} times, not once")
    else:
        check = checks[0]
        for needed in ("particles golden check golden/golden.yaml", "-o golden-report", '--jobs "$(nproc)"',
                       "--shard ${{ matrix.shard }}/2"):
            if needed not in check:
                problems.append(f"`{check.strip()}` lacks `{needed}`")
        if "--gl" in check:
            problems.append(f"`{check.strip()}` chooses a GL backend: the cpu raster needs none, nor Mesa")
    shard_uploads = [s for s in uses("golden", "actions/upload-artifact") if always(s)]
    if not any((s.get("with") or {}).get("path", "").rstrip("/") == "golden-report" and
               "matrix.shard" in str((s.get("with") or {}).get("name", "")) for s in shard_uploads):
        problems.append("job `golden` does not always upload golden-report/ under a name per shard")

    merge = jobs.get("merge") or {}
    if "golden" not in ([merge.get("needs")] if isinstance(merge.get("needs"), str) else merge.get("needs") or []):
        problems.append("job `merge` does not need `golden`")
    if not always(merge):
        problems.append("job `merge` does not run always (a failing shard would skip the report)")
    if not uses("merge", "actions/download-artifact"):
        problems.append("job `merge` downloads no artefacts")
    merge_runs = "\n".join(script_text(s.get("run")) for s in steps_of("merge"))
    if not re.search(r"particles golden report .*-o golden-report\b", merge_runs):
        problems.append("job `merge` does not run `particles golden report … -o golden-report`")
    if not any((s.get("with") or {}).get("path", "").rstrip("/") == "golden-report"
               for s in uses("merge", "actions/upload-artifact") if always(s)):
        problems.append("job `merge` does not always upload golden-report/")
    if not any((s.get("with") or {}).get("report_paths") == "golden-report/junit.xml"
               for s in uses("merge", "mikepenz/action-junit-report") if always(s)):
        problems.append("job `merge` does not always publish golden-report/junit.xml as test results")

    for job, body in jobs.items():
        for step in (body or {}).get("steps") or []:
            action = step.get("uses")
            if action and not re.fullmatch(r"[\w.-]+/[\w./-]+@v\d+", str(action)):
                problems.append(f"job `{job}` uses {action}: not pinned to a major version (@vN)")
    return problems


def check_github(source):
    path = os.path.join(source, "docs", "ci", "github-actions.yml")
    with open(path, encoding="utf-8") as f:
        text = f.read()
    validator = action_validator(source)

    code, output = validate(validator, path)
    if code != 0:
        fail(f"action-validator rejects {path} (exit {code}):\n{output}")

    with tempfile.TemporaryDirectory(prefix="ci-recipes.") as scratch:
        broken = os.path.join(scratch, "github-actions.yml")
        with open(broken, "w", encoding="utf-8") as f:
            f.write(with_unknown_step_key(text))
        code, output = validate(validator, broken)
        if code == 0:
            fail(f"action-validator accepts a copy with the unknown step key `{UNKNOWN_KEY}`: it checks nothing")
        if UNKNOWN_KEY not in output:
            fail(f"action-validator rejects the copy with `{UNKNOWN_KEY}` but does not name it:\n{output}")

    workflow = yaml.safe_load(text)
    problems = github_problems(workflow)
    if problems:
        fail(f"{path}:\n  " + "\n  ".join(problems))
    def steps(w, job, needle):
        return [s for s in w["jobs"][job]["steps"] if needle in s.get("run", "")]

    breakages = {
        "no fail-fast": lambda w: w["jobs"]["golden"]["strategy"].pop("fail-fast"),
        "merge not always": lambda w: w["jobs"]["merge"].pop("if"),
        "no --shard": lambda w: [s.update(run=s["run"].replace("--shard", "--shards"))
                                 for s in steps(w, "golden", "golden check")],
        "--gl egl again": lambda w: [s.update(run=s["run"].rstrip() + " --gl egl\n")
                                     for s in steps(w, "golden", "golden check")],
        "junit path": lambda w: [s["with"].update(report_paths="junit.xml")
                                 for s in w["jobs"]["merge"]["steps"] if "junit" in s.get("uses", "")],
        "unpinned": lambda w: w["jobs"]["merge"]["steps"][0].update(uses="actions/checkout@main"),
        "no stop on an unset URL": lambda w: [s.update(run=re.sub(r"(?s)if \[ -z .*?\n\s*fi\n", "", s["run"], count=1))
                                              for s in steps(w, "golden", ARCHIVE_VARIABLE)],
        "not unpacked into .particles": lambda w: [s.update(run=s["run"].replace("--strip-components=1 ", ""))
                                                   for s in steps(w, "merge", ARCHIVE_VARIABLE)],
        "not on the PATH": lambda w: [s.update(run=s["run"].replace('>> "$GITHUB_PATH"', ">> /dev/null"))
                                      for s in steps(w, "golden", ARCHIVE_VARIABLE)],
        "built again": lambda w: w["jobs"]["golden"]["steps"].insert(2, {
            "name": "Build", "run": "cmake -S .particles -B build && cmake --build build --target particles"}),
        "in a container": lambda w: w["jobs"]["merge"].update(container="debian:12"),
        "the old variables": lambda w: w["env"].update({ARCHIVE_VARIABLE: "${{ vars.PARTICLES_REPO }}"}),
    }
    expect_caught(breakages, workflow, github_problems, path)
    print(f"{path}: action-validator 0.6.0 accepts it and rejects a copy with `{UNKNOWN_KEY}`; "
          f"its structure holds, and {len(breakages)} broken copies are caught")


# --- GitLab CI ---------------------------------------------------------------------------------


def merged(base, over):
    """GitLab's `extends`: hashes merged key by key, anything else replaced."""
    out = copy.deepcopy(base)
    for key, value in over.items():
        out[key] = merged(out[key], value) if isinstance(value, dict) and isinstance(out.get(key), dict) \
            else copy.deepcopy(value)
    return out


def resolved_job(config, name):
    job = config.get(name) or {}
    parents = job.get("extends", [])
    base = {}
    for parent in [parents] if isinstance(parents, str) else parents:
        base = merged(base, resolved_job(config, parent))
    return merged(base, {k: v for k, v in job.items() if k != "extends"})


def gitlab_problems(config):
    """What docs/ci/gitlab-ci.yml promises (docs/ci/README.md) and `config` lacks."""
    problems = []
    default_image = (config.get("default") or {}).get("image", config.get("image"))
    jobs = {}
    for name in ("golden", "golden-report"):
        if name not in config:
            problems.append(f"no job `{name}`")
            continue
        job = jobs[name] = resolved_job(config, name)
        if job.get("image", default_image) != "debian:12":
            problems.append(f"job `{name}` does not run in image debian:12")
        before = job.get("before_script") or []
        before = [before] if isinstance(before, str) else [str(line) for line in before]
        problems += setup_problems(name, "\n".join(before))
        if not BUILD_COMMANDS.search("\n".join(before)):   # a build is not run here
            problems += rehearse(name, before, github=False)
        if not any(re.search(r"apt-get install .*--no-install-recommends", line) and
                   {"curl", "xz-utils", "ca-certificates"} <= set(line.split()) for line in before):
            problems.append(f"job `{name}` does not apt-get install --no-install-recommends curl xz-utils ca-certificates")
        built = BUILD_COMMANDS.search(script_text(job.get("script")))
        if built:
            problems.append(f"job `{name}` builds or clones particles (`{built.group(0)}`): it takes the archive")
        if job.get("cache"):
            problems.append(f"job `{name}` caches a build: the archive needs none")
        artifacts = job.get("artifacts") or {}
        if artifacts.get("when") != "always":
            problems.append(f"job `{name}`'s artefacts are not kept `when: always`")

    golden = jobs.get("golden", {})
    if golden.get("parallel") != 2:
        problems.append("job `golden` does not run `parallel: 2`")
    checks = [line for line in command_lines(script_text(golden.get("script"))) if "particles golden check" in line]
    if len(checks) != 1:
        problems.append(f"job `golden` runs `particles golden check` {len(checks)} times, not once")
    else:
        check = checks[0]
        for needed in ("particles golden check golden/golden.yaml", '--jobs "$(nproc)"', "$CI_NODE_INDEX/$CI_NODE_TOTAL"):
            if needed not in check:
                problems.append(f"`{check.strip()}` lacks `{needed}`")
        if "--gl" in check:
            problems.append(f"`{check.strip()}` chooses a GL backend: the cpu raster needs none, nor Mesa")
        if not re.search(r"--shard\s+\"?\$CI_NODE_INDEX/\$CI_NODE_TOTAL", check):
            problems.append(f"`{check.strip()}` lacks `--shard $CI_NODE_INDEX/$CI_NODE_TOTAL`")
        output = re.search(r"-o\s+\"?([^\s\"]+)", check)
        paths = (golden.get("artifacts") or {}).get("paths") or []
        if not output or not any(output.group(1).startswith(p.rstrip("/") + "/") or output.group(1) == p.rstrip("/")
                                 for p in paths):
            problems.append(f"`{check.strip()}` writes outside the job's artefact paths {paths}")

    report = jobs.get("golden-report", {})
    needs = report.get("needs") or []
    if "golden" not in [n.get("job") if isinstance(n, dict) else n for n in needs]:
        problems.append("job `golden-report` does not need `golden`")
    if report.get("when") != "always":
        problems.append("job `golden-report` does not run `when: always` (a failing shard would skip the report)")
    if not re.search(r"particles golden report .*-o golden-report\b", script_text(report.get("script"))):
        problems.append("job `golden-report` does not run `particles golden report … -o golden-report`")
    artifacts = report.get("artifacts") or {}
    if "golden-report/" not in (artifacts.get("paths") or []):
        problems.append("job `golden-report` does not keep golden-report/")
    if (artifacts.get("reports") or {}).get("junit") != "golden-report/junit.xml":
        problems.append("job `golden-report` does not report golden-report/junit.xml as JUnit")
    return problems


def expect_caught(breakages, document, problems_of, path):
    """Each breakage of `document` must give a problem: the checks are not vacuous."""
    for what, breaking in breakages.items():
        broken = copy.deepcopy(document)
        breaking(broken)
        if not problems_of(broken):
            fail(f"the checks of {path} miss a copy broken on purpose ({what})")


def check_gitlab(source):
    path = os.path.join(source, "docs", "ci", "gitlab-ci.yml")
    with open(path, encoding="utf-8") as f:
        config = yaml.safe_load(f)
    problems = gitlab_problems(config)
    if problems:
        fail(f"{path}:\n  " + "\n  ".join(problems))
    def before(c, edit):
        c[".particles"]["before_script"] = edit(c[".particles"]["before_script"])

    breakages = {
        "artefacts on success only": lambda c: c["golden"]["artifacts"].pop("when"),
        "no parallel": lambda c: c["golden"].pop("parallel"),
        "no --shard": lambda c: c["golden"].update(script=[s.replace("--shard", "--shards") for s in c["golden"]["script"]]),
        "--gl egl again": lambda c: c["golden"].update(script=[s + " --gl egl" for s in c["golden"]["script"]]),
        "junit path": lambda c: c["golden-report"]["artifacts"]["reports"].update(junit="junit.xml"),
        "report on success only": lambda c: c["golden-report"].pop("when"),
        "a musl image": lambda c: c["default"].update(image="alpine:3"),
        "no stop on an unset URL": lambda c: before(c, lambda b: [s for s in b if "-z " not in s]),
        "curl and xz not installed": lambda c: before(c, lambda b: [s for s in b if "apt-get" not in s]),
        "apt-get before the stop": lambda c: before(c, lambda b: sorted(b, key=lambda s: "apt-get" not in s)),
        "not unpacked into .particles": lambda c: before(c, lambda b: [s.replace("-C .particles", "") for s in b]),
        "not on the PATH": lambda c: before(c, lambda b: [s for s in b if not s.startswith("export PATH")]),
        "built again": lambda c: before(c, lambda b: b + ["cmake --build .particles/build --target particles"]),
        "a build cache": lambda c: c[".particles"].update(cache={"key": "particles", "paths": [".particles-bin/"]}),
    }
    expect_caught(breakages, config, gitlab_problems, path)
    print(f"{path}: its structure holds, and {len(breakages)} broken copies are caught")


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("github", "gitlab"):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    (check_github if sys.argv[1] == "github" else check_gitlab)(sys.argv[2])


if __name__ == "__main__":
    main()
