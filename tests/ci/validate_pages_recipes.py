#!/usr/bin/python3
"""Checks the documentation site's CI recipes (docs/ci/pages-github.yml, docs/ci/pages-gitlab.yml;
docs/ci/README.md, "Publishing particles' documentation"): a copy publishes what scripts/docs
builds.

  github SOURCE_DIR   pages-github.yml passes @action-validator/cli (GitHub's workflow schema,
                      as tests/ci/validate_recipes.py runs it), and has the structure promised: a
                      build job that runs scripts/docs and uploads build/docs/html with
                      actions/upload-pages-artifact, and a deploy job after it with actions/deploy-pages,
                      `pages: write` and `id-token: write`, on pushes to main.
  gitlab SOURCE_DIR   pages-gitlab.yml has a job named `pages` that runs scripts/docs, moves
                      build/docs/html to public, keeps public as its artifact, and runs only on the
                      default branch.
Each structural check must also fail on a copy broken on purpose.

usage: validate_pages_recipes.py github|gitlab SOURCE_DIR
"""
import copy
import os
import sys

import yaml

sys.dont_write_bytecode = True
from validate_recipes import action_validator, fail, script_text, validate  # noqa: E402


def github_problems(workflow):
    problems = []
    jobs = workflow.get("jobs") or {}
    build, deploy = jobs.get("build") or {}, jobs.get("deploy") or {}
    steps = build.get("steps") or []
    runs = "\n".join(script_text(step.get("run")) for step in steps)
    if "scripts/docs" not in runs:
        problems.append("the build job does not run scripts/docs")
    uploads = [s for s in steps if str(s.get("uses", "")).startswith("actions/upload-pages-artifact@")]
    if not uploads or (uploads[0].get("with") or {}).get("path") != "build/docs/html":
        problems.append("the build job does not upload build/docs/html with actions/upload-pages-artifact")
    if "build" not in ([deploy.get("needs")] if isinstance(deploy.get("needs"), str) else deploy.get("needs") or []):
        problems.append("the deploy job does not wait for the build job")
    if not any(str(s.get("uses", "")).startswith("actions/deploy-pages@") for s in deploy.get("steps") or []):
        problems.append("the deploy job does not run actions/deploy-pages")
    permissions = deploy.get("permissions") or {}
    if permissions.get("pages") != "write" or permissions.get("id-token") != "write":
        problems.append("the deploy job lacks `pages: write` and `id-token: write`")
    # PyYAML reads the key `on` as True.
    triggers = workflow.get("on", workflow.get(True)) or {}
    if "main" not in ((triggers.get("push") or {}).get("branches") or []):
        problems.append("the workflow does not run on pushes to main")
    return problems


def gitlab_problems(config):
    problems = []
    job = config.get("pages")
    if not isinstance(job, dict):
        return ["no job named `pages` (the only one GitLab Pages publishes)"]
    script = script_text(job.get("script"))
    if "scripts/docs" not in script:
        problems.append("the pages job does not run scripts/docs")
    if "mv build/docs/html public" not in script:
        problems.append("the pages job does not move build/docs/html to public")
    if "public" not in ((job.get("artifacts") or {}).get("paths") or []):
        problems.append("the pages job does not keep public as its artifact")
    rules = " ".join(str(rule.get("if", "")) for rule in job.get("rules") or [])
    if "$CI_DEFAULT_BRANCH" not in rules:
        problems.append("the pages job runs on other branches than the default one")
    return problems


def broken_github(workflow):
    """Copies, each with one promise broken, and the problem each must show."""
    out = []
    copy1 = copy.deepcopy(workflow)
    copy1["jobs"]["build"]["steps"] = [s for s in copy1["jobs"]["build"]["steps"] if "scripts/docs" not in str(s.get("run"))]
    out.append((copy1, "does not run scripts/docs"))
    copy2 = copy.deepcopy(workflow)
    del copy2["jobs"]["deploy"]["permissions"]["id-token"]
    out.append((copy2, "id-token"))
    copy3 = copy.deepcopy(workflow)
    copy3["jobs"]["deploy"]["needs"] = []
    out.append((copy3, "does not wait"))
    return out


def broken_gitlab(config):
    out = []
    copy1 = copy.deepcopy(config)
    copy1["pages"]["script"] = [line for line in copy1["pages"]["script"] if "mv " not in line]
    out.append((copy1, "move build/docs/html"))
    copy2 = copy.deepcopy(config)
    copy2["pages"]["rules"] = []
    out.append((copy2, "other branches"))
    copy3 = {"docs": copy.deepcopy(config["pages"])}
    out.append((copy3, "no job named `pages`"))
    return out


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("github", "gitlab"):
        print(__doc__, file=sys.stderr)
        return 2
    which, source = sys.argv[1], sys.argv[2]
    path = os.path.join(source, "docs", "ci", f"pages-{which}.yml")
    with open(path, encoding="utf-8") as f:
        recipe = yaml.safe_load(f)
    if which == "github":
        validator = action_validator(source)
        code, output = validate(validator, path)
        if code != 0:
            fail(f"action-validator refuses {path}:\n{output}")
        problems, broken = github_problems(recipe), broken_github(recipe)
    else:
        problems, broken = gitlab_problems(recipe), broken_gitlab(recipe)
    if problems:
        fail(f"{path}: " + "; ".join(problems))
    for copy_, expected in broken:
        found = (github_problems if which == "github" else gitlab_problems)(copy_)
        if not any(expected in problem for problem in found):
            fail(f"a copy of {path} broken on purpose was not caught (expected a problem about {expected!r}; got {found})")
    print(f"{path}: every promise holds, and {len(broken)} broken copies are caught")
    return 0


if __name__ == "__main__":
    sys.exit(main())
