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

usage: validate_recipes.py github|gitlab SOURCE_DIR
"""
import copy
import os
import re
import subprocess
import sys
import tempfile

import yaml

# Under CTest's TIMEOUT (300 s, CMakeLists.txt), so that an unreachable registry ends with the
# message below rather than a killed test. scripts/npm-tools gives up after about 3 min on a
# registry that never answers, 15 s on a refused connection.
NPM_TOOLS_TIMEOUT = 270
VALIDATOR_TIMEOUT = 60
UNKNOWN_KEY = "frobnicate-particles"


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
    for name in ("PARTICLES_REPO", "PARTICLES_REF"):
        if name not in env:
            problems.append(f"env has no {name}")

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
        container = jobs[job].get("container")
        image = container.get("image") if isinstance(container, dict) else container
        if image != "debian:12":
            problems.append(f"job `{job}` does not run in container debian:12")
        runs = "\n".join(script_text(s.get("run")) for s in steps_of(job))
        for needed in ('"$PARTICLES_REPO"', '"$PARTICLES_REF"', ".particles/scripts/deps"):
            if needed not in runs:
                problems.append(f"job `{job}` never uses {needed}")
        restored = uses(job, "actions/cache/restore") + uses(job, "actions/cache")
        if not any("PARTICLES_REF" in str((s.get("with") or {}).get("key", "")) for s in restored):
            problems.append(f"job `{job}` restores no cache keyed on PARTICLES_REF")
        if not uses(job, "actions/cache/save") and not uses(job, "actions/cache"):
            problems.append(f"job `{job}` saves no cache")

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
        for needed in ("particles golden check golden/golden.yaml", "-o golden-report", "--gl egl",
                       "--shard ${{ matrix.shard }}/2"):
            if needed not in check:
                problems.append(f"`{check.strip()}` lacks `{needed}`")
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
    breakages = {
        "no fail-fast": lambda w: w["jobs"]["golden"]["strategy"].pop("fail-fast"),
        "merge not always": lambda w: w["jobs"]["merge"].pop("if"),
        "no --shard": lambda w: [s.update(run=s["run"].replace("--shard", "--shards"))
                                 for s in w["jobs"]["golden"]["steps"] if "golden check" in s.get("run", "")],
        "junit path": lambda w: [s["with"].update(report_paths="junit.xml")
                                 for s in w["jobs"]["merge"]["steps"] if "junit" in s.get("uses", "")],
        "unpinned": lambda w: w["jobs"]["merge"]["steps"][0].update(uses="actions/checkout@main"),
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
        before = script_text(job.get("before_script"))
        for needed in ('"$PARTICLES_REPO"', '"$PARTICLES_REF"', ".particles/scripts/deps"):
            if needed not in before:
                problems.append(f"job `{name}` never uses {needed} before its script")
        cache = job.get("cache") or {}
        if "$PARTICLES_REF" not in str(cache.get("key", "")) or not cache.get("paths"):
            problems.append(f"job `{name}` has no cache keyed on $PARTICLES_REF")
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
        for needed in ("particles golden check golden/golden.yaml", "--gl egl", "$CI_NODE_INDEX/$CI_NODE_TOTAL"):
            if needed not in check:
                problems.append(f"`{check.strip()}` lacks `{needed}`")
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
    breakages = {
        "artefacts on success only": lambda c: c["golden"]["artifacts"].pop("when"),
        "no parallel": lambda c: c["golden"].pop("parallel"),
        "no --shard": lambda c: c["golden"].update(script=[s.replace("--shard", "--shards") for s in c["golden"]["script"]]),
        "junit path": lambda c: c["golden-report"]["artifacts"]["reports"].update(junit="junit.xml"),
        "report on success only": lambda c: c["golden-report"].pop("when"),
        "no cache key": lambda c: c[".particles"]["cache"].update(key="particles"),
        "other image": lambda c: c["default"].update(image="ubuntu:24.04"),
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
