"""Footprint reports in CI (issues 25, point 6, and 36, point 5; docs/footprint.md, "In a user's
CI" and "The project's own CI"): the GitHub Actions workflow and the GitLab CI job the docs give,
and the CapBot's workflow (its project built bare-metal for QEMU from the installed swarmvm),
read from the docs and run step by step, in order, as GitHub's and GitLab's runners would, on a
real git repository made here; `make footprint`'s comparison of the example with the baseline
kept in the repository; and `--cycles` from an installed swarmvm, which builds the simavr board
from the package's own C source into an empty cache.

The user's repository: a base commit holding the bundled example as ``supervisor.yaml``, the
controller skeleton gen wrote for it and the repository's budgets, and pull-request commits on
top (a controller grown by a table in flash; the same with a budget it exceeds), each run in a
fresh clone checked out at the pull request. The install steps are not run: the swarmvm of the
Python running the tests (the checkout's editable install, or the wheel under `make
wheel-check`) stands in for the recipes' placeholder ``pip install "swarmvm @
git+https://github.com/OWNER/swarmvm"``, and the machine's avr-gcc, simavr and kilolib (built in
the cache, linked as ``kilolib/``) for the packages and the clone; the CapBot's, the machine's
arm-none-eabi-gcc and QEMU, its wheel URL the placeholder. `gh` and `curl` are replaced
on PATH by the recording stand-ins below (GITHUB_CLI, CURL): the GitHub and GitLab services they
talk to are not reachable from the tests. The test keeps the services' state (comments, notes,
artifacts) between runs, as the services would."""

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tomllib
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import pytest
import yaml

from checkout import EXAMPLE, ROOT
from footprint_images import KILOBOT_INDIRECT
from targets.kilobot.needs import board_or_skip, kilolib_or_skip

INDIRECT = [arg for declaration in KILOBOT_INDIRECT for arg in ("--indirect", declaration)]


def shrink(report: dict) -> dict:
    """The report of an image 100 B and 50 cycles smaller: what a change has grown from."""
    image = report["images"][0]
    image["flash"]["total"] -= 100
    image["flash"]["application"] -= 100
    image["cycles"]["worst"] -= 50
    return report


DOC = ROOT / "docs" / "footprint.md"
YAML_BLOCK = re.compile(r"^```yaml\n(.*?)^```", re.M | re.S)
MARKER = "<!-- swarmvm-footprint -->"
CAPBOT_MARKER = "<!-- swarmvm-footprint-capbot -->"
PLACEHOLDER = 'pip install "swarmvm @ git+https://github.com/OWNER/swarmvm"'
WHEEL = 'pip install "https://github.com/OWNER/swarmvm/releases/download/v0.1.0/swarmvm-0.1.0-py3-none-any.whl"'
BUDGETS = "[tool.swarmvm.footprint.kilobot]\nflash = 16000\nram = 400\n"
TIGHT = "[tool.swarmvm.footprint.kilobot]\nflash = 1000\nram = 400\n"      # the image is ~12 kB
FILTER_BYTES = 300
GROW = """
/* The pull request (tests/footprint/test_footprint_ci.py): a filter's coefficients in flash. */
#include <avr/pgmspace.h>
static const unsigned char filter_table[%d] PROGMEM = {1, 2, 3};
volatile unsigned char filter_out;
__attribute__((constructor)) static void filter(void) { filter_out = pgm_read_byte(&filter_table[filter_out]); }
""" % FILTER_BYTES
SYMBOL_ROW = "| filter_table (robot_controller.c) | .text | — | %d | +%d | new |" % (FILTER_BYTES, FILTER_BYTES)
GITLAB_API = "https://gitlab.example.com/api/v4"
# The CapBot's repository (its workflow builds the project bare-metal for QEMU; the image is ~18 kB).
CAPBOT_BUDGETS = "[tool.swarmvm.footprint.capbot]\nflash = 30000\nram = 4000\n"
CAPBOT_TIGHT = "[tool.swarmvm.footprint.capbot]\nflash = 1000\nram = 4000\n"
CAPBOT_GROW = """
/* The pull request (tests/footprint/test_footprint_ci.py): a filter's coefficients in flash. */
static const unsigned char filter_table[%d] = {1, 2, 3};
volatile unsigned char filter_out;
__attribute__((constructor)) static void filter(void) { filter_out = filter_table[filter_out]; }
""" % FILTER_BYTES


def workflows():
    """The docs' YAML blocks that are CI recipes: {the target a GitHub workflow builds: workflow},
    and the GitLab job's name and job."""
    github, gitlab = {}, None
    for block in YAML_BLOCK.findall(DOC.read_text()):
        data = yaml.safe_load(block)
        if "jobs" in data:
            (target,) = set(re.findall(r"--target (\w+)", block))
            assert target not in github, "docs/footprint.md: two GitHub workflows of %s" % target
            github[target] = data
        else:
            ((name, job),) = [(k, v) for k, v in data.items() if isinstance(v, dict) and "script" in v]
            gitlab = name, job
    assert set(github) == {"kilobot", "capbot"} and gitlab is not None, \
        "docs/footprint.md: the Kilobot's and the CapBot's workflows and the GitLab job as ```yaml blocks"
    return github, gitlab


def recipes():
    """The Kilobot's recipes: (GitHub workflow, GitLab job name and job)."""
    github, gitlab = workflows()
    return github["kilobot"], gitlab


# ---- the user's repository --------------------------------------------------------------------

def git(folder: Path, *args: str) -> str:
    return subprocess.run(["git", "-C", str(folder), *args], check=True, capture_output=True, text=True).stdout.strip()


@dataclass(frozen=True)
class Project:
    """What a target's user repository keeps and how its pull requests change it: the controller
    gen wrote once (the only file of ``firmware/`` committed), the budgets of the base commit and
    of branch ``over``, and what branch ``grow`` appends to the controller."""
    controller: str
    budgets: str
    tight: str
    grow: str


PROJECTS = {
    "kilobot": Project("firmware/robot_controller.c", BUDGETS, TIGHT, GROW),
    "capbot": Project("firmware/src/robot_controller.c", CAPBOT_BUDGETS, CAPBOT_TIGHT, CAPBOT_GROW),
}


class Repository:
    """The user's repository (``origin``) of a ``target``'s project: main at the base commit;
    branch ``grow``, the pull request growing the controller; branch ``over``, the same with a
    budget it exceeds."""

    def __init__(self, root: Path, target: str = "kilobot"):
        project = PROJECTS[target]
        self.root = root
        self.origin = root / "origin"
        self.origin.mkdir()
        self.kilolib = kilolib_or_skip() if target == "kilobot" else None
        git(self.origin, "init", "-q", "-b", "main")
        git(self.origin, "config", "user.email", "dev@example.com")
        git(self.origin, "config", "user.name", "Developer")
        shutil.copy(EXAMPLE, self.origin / "supervisor.yaml")
        (self.origin / "pyproject.toml").write_text(project.budgets)
        kept = "".join("!%s/\n%s/*\n" % (folder, folder) for folder in Path(project.controller).parents[:-2][::-1])
        (self.origin / ".gitignore").write_text("/kilolib\nfirmware/*\n%s!%s\n" % (kept, project.controller))
        subprocess.run(["swarmvm", "gen", "supervisor.yaml", "--target", target, "-o", "firmware", "--name", "robot"],
                       cwd=self.origin, check=True, capture_output=True)
        git(self.origin, "add", ".")
        assert git(self.origin, "diff", "--cached", "--name-only").split() == [
            ".gitignore", project.controller, "pyproject.toml", "supervisor.yaml"]
        git(self.origin, "commit", "-q", "-m", "The supervisor and its controller")
        self.base = git(self.origin, "rev-parse", "HEAD")
        git(self.origin, "checkout", "-q", "-b", "grow")
        with open(self.origin / project.controller, "a") as controller:
            controller.write(project.grow)
        git(self.origin, "commit", "-q", "-am", "A filter in the controller")
        git(self.origin, "checkout", "-q", "-b", "over")
        (self.origin / "pyproject.toml").write_text(project.tight)
        git(self.origin, "commit", "-q", "-am", "A budget the image exceeds")
        git(self.origin, "checkout", "-q", "main")
        controller = (self.origin / project.controller).read_bytes()   # gen's files go: each run generates its own
        shutil.rmtree(self.origin / "firmware")
        (self.origin / project.controller).parent.mkdir(parents=True)
        (self.origin / project.controller).write_bytes(controller)
        self.runs = 0

    def checkout(self, branch: str) -> Path:
        """A fresh clone at ``branch``, as each CI run gets, after the install steps (kilolib)."""
        self.runs += 1
        folder = self.root / ("run%d" % self.runs)
        subprocess.run(["git", "clone", "-q", str(self.origin), str(folder)], check=True, capture_output=True)
        git(folder, "checkout", "-q", branch)
        if self.kilolib is not None:
            (folder / "kilolib").symlink_to(self.kilolib)
        return folder


@pytest.fixture(scope="module")
def repository(tmp_path_factory):
    """One repository for the module's tests: each run clones it, none changes it."""
    board_or_skip()
    return Repository(tmp_path_factory.mktemp("user"))


# ---- the stand-ins for gh and curl ------------------------------------------------------------

# Both stand-ins read their command line alike: the options that take a value, the flags, the rest.
PARSE = '''
def parse(args, valued, start):
    """(positional arguments, {option: [its values]}) of ``args`` from ``start``."""
    positional, options, i = [], {}, start
    while i < len(args):
        if args[i] in valued:
            options.setdefault(args[i], []).append(args[i + 1])
            i += 2
        else:
            (options.setdefault(args[i], []).append(True) if args[i].startswith("-") else positional.append(args[i]))
            i += 1
    return positional, options
'''

GITHUB_CLI = '''#!%(python)s
"""Stands in for GitHub's CLI `gh` and for GitHub behind it, which the tests cannot reach
(tests/footprint/test_footprint_ci.py): records each call, and keeps the pull requests'
comments in %(state)s. Answers what the recipe asks: `gh api` GET of an issue's comments (with
--jq, through jq, or without jq the recipe's one filter), `gh api --method PATCH` of a comment
(-F body=@FILE), `gh pr comment N --body-file FILE`."""
import json, os, re, shutil, subprocess, sys
STATE = %(state)r
state = json.load(open(STATE))
args = sys.argv[1:]
state["calls"].append(args)
%(parse)s
positional, options = parse(args, {"--jq", "--method", "-X", "-F", "--field", "--repo", "-R", "--body-file"}, 1)

def done(output="", status=0):
    json.dump(state, open(STATE, "w"))
    sys.stdout.write(output)
    sys.exit(status)

if not os.environ.get("GH_TOKEN"):
    done("gh: set the GH_TOKEN environment variable\\n", 4)
if args[0] == "api":
    (endpoint,) = positional
    method = (options.get("--method") or options.get("-X") or ["GET"])[0]
    parts = endpoint.split("/")
    if method == "GET" and parts[0] == "repos" and parts[3:4] == ["issues"] and parts[5:] == ["comments"]:
        listing = json.dumps([{"id": c["id"], "body": c["body"]} for c in state["comments"] if c["pr"] == parts[4]])
        if "--jq" in options and shutil.which("jq"):
            listing = subprocess.run(["jq", "-r", options["--jq"][0]], input=listing, text=True, check=True,
                                     capture_output=True).stdout
        elif "--jq" in options:             # no jq here: the one filter the recipe gives, evaluated
            wanted = re.fullmatch(r'\\.\\[\\] \\| select\\(\\.body \\| startswith\\("(.*)"\\)\\) \\| \\.id', options["--jq"][0])
            assert wanted, "gh (stand-in): a --jq filter it does not evaluate without jq"
            listing = "".join("%%d\\n" %% c["id"] for c in json.loads(listing) if c["body"].startswith(wanted.group(1)))
        done(listing)
    if method == "PATCH" and parts[0] == "repos" and parts[3:5] == ["issues", "comments"]:
        ((key, value),) = [field.split("=", 1) for field in options["-F"]]
        assert key == "body" and value.startswith("@")
        (comment,) = [c for c in state["comments"] if str(c["id"]) == parts[5]]
        comment["body"] = open(value[1:]).read()
        done(json.dumps(comment))
elif args[:2] == ["pr", "comment"]:
    (_, pr) = positional
    state["comments"].append({"id": 1000 + len(state["comments"]), "pr": pr, "repo": options["--repo"][0],
                              "body": open(options["--body-file"][0]).read()})
    done("https://github.com/%%s/pull/%%s#issuecomment-%%d\\n" %% (options["--repo"][0], pr, state["comments"][-1]["id"]))
done("gh (stand-in): not a call the recipe makes: %%s\\n" %% args, 1)
'''

CURL = '''#!%(python)s
"""Stands in for `curl` and for the GitLab instance it talks to, which the tests cannot reach
(tests/footprint/test_footprint_ci.py): records each call, serves the job artifacts kept in
%(state)s (404 otherwise, status 22 with --fail) and keeps the merge-request notes posted
(GET, POST, PUT of the notes API)."""
import json, sys, urllib.parse
STATE = %(state)r
state = json.load(open(STATE))
args = sys.argv[1:]
state["calls"].append(args)
%(parse)s
positional, options = parse(args, {"--output", "-o", "--header", "-H", "--request", "-X", "--data-urlencode"}, 0)
(url,) = positional
method = (options.get("--request") or options.get("-X") or ["GET"])[0]
headers = dict(h.split(": ", 1) for h in options.get("--header", []))
path = urllib.parse.urlsplit(url).path

def answer(status, body):
    json.dump(state, open(STATE, "w"))
    if status >= 400 and "--fail" in options:
        sys.exit(22)
    output = options.get("--output", ["-"])[0]
    (sys.stdout.write(body) if output == "-" else open(output, "w").write(body))
    sys.exit(0)

if method == "GET" and "/jobs/artifacts/" in path:
    data = state["artifacts"].get(url)
    answer(200, data) if data is not None else answer(404, '{"message":"404 Not found"}')
if method == "GET" and path.endswith("/notes") and "/merge_requests/" in path:
    answer(200, json.dumps([{"id": n["id"], "body": n["body"]} for n in state["notes"] if n["path"] == path]))
if method in ("POST", "PUT") and "/merge_requests/" in path:
    ((key, value),) = [field.split("@", 1) for field in options["--data-urlencode"]]
    assert key == "body"
    if method == "POST" and path.endswith("/notes"):
        state["notes"].append({"id": 500 + len(state["notes"]), "path": path, "headers": headers,
                               "body": open(value).read()})
        answer(201, json.dumps({"id": state["notes"][-1]["id"]}))
    notes, _, number = path.rpartition("/")
    for note in state["notes"]:
        if method == "PUT" and note["path"] == notes and str(note["id"]) == number:
            note.update(body=open(value).read(), headers=headers)
            answer(200, json.dumps({"id": note["id"]}))
answer(404, '{"message":"404 Not found"}')
'''


class Services:
    """The stand-ins on PATH (folder ``bin``) and the state they keep: GitHub's comments and
    artifacts (the artifact actions are run by the test itself), GitLab's notes and artifacts."""

    def __init__(self, root: Path):
        self.bin = root / "bin"
        self.bin.mkdir()
        self.state = root / "services.json"
        self.save({"calls": [], "comments": [], "notes": [], "artifacts": {}})
        for name, source in (("gh", GITHUB_CLI), ("curl", CURL)):
            (self.bin / name).write_text(source % {"python": sys.executable, "state": str(self.state), "parse": PARSE})
            (self.bin / name).chmod(0o755)
        self.github_artifacts: dict = {}              # branch -> artifact name -> file name -> bytes

    def load(self) -> dict:
        return json.loads(self.state.read_text())

    def save(self, state: dict) -> None:
        self.state.write_text(json.dumps(state))

    def environment(self, **variables: str) -> dict:
        return dict(os.environ, PATH="%s:%s" % (self.bin, os.environ["PATH"]), **variables)


@pytest.fixture
def services(tmp_path):
    return Services(tmp_path)


# ---- GitHub Actions -------------------------------------------------------------------------

EXPRESSION = re.compile(r"\$\{\{\s*([\w.]+)\s*\}\}")


def test_the_github_workflow_runs_on_pull_requests_and_main_and_keeps_the_report_and_chart():
    github, _ = recipes()
    triggers = github.get("on", github.get(True))         # YAML 1.1 reads the key `on` as true
    assert triggers["push"]["branches"] == ["main"] and "pull_request" in triggers
    assert github["permissions"]["pull-requests"] == "write"
    (job,) = github["jobs"].values()
    steps = job["steps"]
    assert all(("run" in step) != ("uses" in step) for step in steps)
    assert steps[0]["uses"].startswith("actions/checkout@") and steps[0]["with"]["fetch-depth"] == 0
    (install,) = [s for s in steps if s.get("name", "").startswith("Install")]
    assert PLACEHOLDER in install["run"].splitlines()[1]
    download = next(s for s in steps if s.get("uses", "").startswith("dawidd6/action-download-artifact@"))
    upload = next(s for s in steps if s.get("uses", "").startswith("actions/upload-artifact@"))
    assert download["with"]["branch"] == "main" and download["with"]["workflow"] == "footprint.yml"
    assert download["with"]["name"] == upload["with"]["name"]
    assert upload["with"]["path"].split() == ["footprint.json", "footprint.svg"]
    assert upload["if"] == "always()" and steps.index(download) < steps.index(upload)
    (comment,) = [s for s in steps if "gh pr comment" in s.get("run", "")]
    assert comment["if"] == "always()" and comment["continue-on-error"] is True
    assert set(comment["env"]) == {"GH_TOKEN", "PR"} and MARKER in comment["run"]
    assert any("$GITHUB_STEP_SUMMARY" in s.get("run", "") for s in steps)


class GitHubRun:
    def __init__(self, statuses, logs, summary, folder, temp):
        self.statuses, self.logs, self.summary, self.folder, self.temp = statuses, logs, summary, folder, temp

    @property
    def log(self) -> str:
        return "".join(self.logs)


def run_github(services: Services, folder: Path, branch: str, pr: int | None = None, target: str = "kilobot") -> GitHubRun:
    """Each step of the workflow's job in order, as GitHub's runner would: ``run`` steps in bash
    (-e, pipefail), with the step's ``env`` (its ``${{ }}`` expressions from the event), a failed
    step skipping the later ones unless they say ``if: always()`` and failing the job unless it
    says ``continue-on-error``; the artifact actions copy between ``folder`` and
    ``services.github_artifacts``. ``pr``: the pull request's number, else a push to ``branch``;
    ``target``: whose workflow (the docs' Kilobot or CapBot one)."""
    workflow = workflows()[0][target]
    services.runs = getattr(services, "runs", 0) + 1
    temp = folder.parent / ("%s-temp" % folder.name)
    temp.mkdir()
    summary = temp / "summary.md"
    summary.write_text("")
    event = {"github.token": "gh-token", "github.event.pull_request.number": "" if pr is None else str(pr)}
    variables = dict(GITHUB_WORKSPACE=str(folder), RUNNER_TEMP=str(temp), GITHUB_STEP_SUMMARY=str(summary),
                     GITHUB_REPOSITORY="developer/robot", GITHUB_SERVER_URL="https://github.com",
                     GITHUB_RUN_ID=str(services.runs), GITHUB_EVENT_NAME="push" if pr is None else "pull_request",
                     GITHUB_BASE_REF="" if pr is None else "main", GITHUB_REF_NAME=branch)
    statuses: list[int | None] = []
    logs: list[str] = []
    failed = False
    for step in next(iter(workflow["jobs"].values()))["steps"]:
        assert step.get("if", "always()") == "always()", "a condition the test does not evaluate: %s" % step["if"]
        logs.append("")
        if (failed and "if" not in step) or step.get("name", "").startswith("Install"):
            statuses.append(None)
            continue
        uses, given = step.get("uses", ""), step.get("with", {})
        if uses.startswith("dawidd6/action-download-artifact@"):
            for name, data in services.github_artifacts.get(given["branch"], {}).get(given["name"], {}).items():
                (folder / given["path"]).mkdir(exist_ok=True)
                (folder / given["path"] / name).write_bytes(data)
        elif uses.startswith("actions/upload-artifact@"):
            services.github_artifacts.setdefault(branch, {})[given["name"]] = {
                path: (folder / path).read_bytes() for path in given["path"].split() if (folder / path).is_file()}
        elif "run" in step:
            def value(match):
                assert match.group(1) in event, "an expression the test does not evaluate: %s" % match.group(0)
                return event[match.group(1)]
            env = {key: EXPRESSION.sub(value, str(text)) for key, text in step.get("env", {}).items()}
            result = subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", step["run"]],
                                    cwd=folder, env=services.environment(**variables, **env),
                                    capture_output=True, text=True, timeout=300)
            statuses.append(result.returncode)
            logs[-1] = result.stdout + result.stderr
            failed = failed or (result.returncode != 0 and not step.get("continue-on-error"))
            continue
        statuses.append(None)
    return GitHubRun(statuses, logs, summary.read_text(), folder, temp)


def before_after(body: str, figure: str) -> tuple[int, int, int, int, int]:
    """before, after, Δ, budget and margin of ``figure``'s row in the report's table."""
    match = re.search(r"^\| %s \(B\) \| (\d+) \| (\d+) \| ([+-]\d+) \| [+-]\d+\.\d\d %% \| (\d+) \| ([+-]\d+) \(" % figure,
                      body, re.M)
    assert match, body
    return tuple(int(group) for group in match.groups())


def assert_reviewable(body: str, base_sha: str, marker: str = MARKER, flash_budget: int = 16000) -> None:
    """What a reviewer needs (issue 36, point 3): before, after, Δ, budget and margin; the symbol
    changes; the commits compared."""
    assert body.startswith(marker + "\n")
    assert "| figure | before | after | Δ | % | budget | margin |" in body
    before, after, delta, budget, margin = before_after(body, "flash")
    assert after - before == delta and FILTER_BYTES < delta < FILTER_BYTES + 100
    assert budget == flash_budget and margin == budget - after
    assert "## The 5 largest section and symbol changes of each row (bytes)" in body and SYMBOL_ROW in body
    assert "Growth allowed: 10 % per column." in body
    assert "(baseline: %s)" % base_sha[:12] in body                          # the base commit measured


def test_a_pull_request_without_a_baseline_builds_the_base_commit_and_keeps_one_comment(repository, services):
    first = run_github(services, repository.checkout("grow"), "grow", pr=5)
    assert all(status in (None, 0) for status in first.statuses), first.log
    assert (first.temp / "base" / "firmware" / "robot.elf").is_file()        # the base commit, built here
    assert git(first.temp / "base", "rev-parse", "HEAD") == repository.base
    assert json.loads((first.folder / "baseline" / "footprint.json").read_text())["images"][0]["commit"]["sha"] \
        == repository.base
    (comment,) = services.load()["comments"]
    assert comment["pr"] == "5" and comment["repo"] == "developer/robot"
    assert_reviewable(comment["body"], repository.base)
    assert "Against baseline/footprint.json: 1 changed" in comment["body"]
    assert "[run 1](https://github.com/developer/robot/actions/runs/1)" in comment["body"]
    assert "Against baseline/footprint.json: 1 changed" in first.summary
    artifact = services.github_artifacts["grow"]["footprint"]
    assert set(artifact) == {"footprint.json", "footprint.svg"} and b"<svg" in artifact["footprint.svg"]

    second = run_github(services, repository.checkout("grow"), "grow", pr=5)
    assert all(status in (None, 0) for status in second.statuses), second.log
    state = services.load()
    (comment,) = state["comments"]                                          # updated, not a second one
    assert "[run 2](https://github.com/developer/robot/actions/runs/2)" in comment["body"]
    assert_reviewable(comment["body"], repository.base)
    patches = [call for call in state["calls"] if call[:3] == ["api", "--method", "PATCH"]]
    creations = [call for call in state["calls"] if call[:2] == ["pr", "comment"]]
    assert len(creations) == 1 and patches == [
        ["api", "--method", "PATCH", "repos/developer/robot/issues/comments/%d" % comment["id"], "-F", "body=@comment.md"]]


def test_main_keeps_its_report_and_a_pull_request_compares_with_it(repository, services):
    main = run_github(services, repository.checkout("main"), "main")
    assert all(status in (None, 0) for status in main.statuses), main.log
    assert "Against" not in main.summary and "| kilobot | robot |" in main.summary    # nothing to compare with yet
    assert not (main.temp / "base").exists() and services.load()["comments"] == []    # a push: no comment
    assert set(services.github_artifacts["main"]["footprint"]) == {"footprint.json", "footprint.svg"}

    pull = run_github(services, repository.checkout("grow"), "grow", pr=6)
    assert all(status in (None, 0) for status in pull.statuses), pull.log
    assert not (pull.temp / "base").exists()                              # main's report was there
    (comment,) = services.load()["comments"]
    assert_reviewable(comment["body"], repository.base)


def test_a_budget_the_pull_request_exceeds_fails_with_annotations_and_still_comments(repository, services):
    run = run_github(services, repository.checkout("over"), "over", pr=7)
    failed = run.statuses.index(1)
    assert run.statuses[failed + 1:] == [0, None]             # the comment and the upload, run whatever came
    stderr = (run.folder / "footprint.err").read_text().splitlines()
    errors = [line for line in run.logs[failed].splitlines() if line.startswith("::error::")]
    assert errors == ["::error::" + line for line in stderr] and len(errors) >= 1
    assert any(re.fullmatch(r"::error::swarmvm: footprint: kilobot/robot: flash \d+ B over its budget of 1000 B \(by \d+ B\)", e)
               for e in errors), errors
    (comment,) = services.load()["comments"]
    assert "over its budget of 1000 B" in comment["body"] and "ram from" not in comment["body"]
    assert "kilobot/robot: flash from 16000 to 1000 B" in comment["body"]      # the budget the change moved
    report = json.loads(services.github_artifacts["over"]["footprint"]["footprint.json"])
    assert report["violations"] and "footprint.svg" in services.github_artifacts["over"]["footprint"]


# ---- the CapBot's GitHub workflow: the project built bare-metal for QEMU ----------------------

@pytest.fixture(scope="module")
def capbot_repository(tmp_path_factory):
    """The CapBot user's repository: its controller is firmware/src/robot_controller.c."""
    missing = [tool for tool in ("arm-none-eabi-gcc", "qemu-system-arm") if shutil.which(tool) is None]
    if missing:
        pytest.skip("needs %s" % ", ".join(missing))
    return Repository(tmp_path_factory.mktemp("capbot-user"), "capbot")


# What the CapBot's workflow says where the Kilobot's says otherwise (beyond its install and build).
KILOBOT_FOR_CAPBOT = (('make -C "$base/firmware/qemu"', 'make -C "$base/firmware" robot.elf KILOLIB="$PWD/kilolib"'),
                      ("firmware/qemu/", "firmware/"), ("--target capbot", "--target kilobot"),
                      (CAPBOT_MARKER, MARKER), ("footprint-capbot", "footprint"))


def test_the_capbot_workflow_is_the_kilobots_with_the_capbot_build():
    """The same steps (baseline, report, annotations, comment, artifact), its own artifact and
    comment marker; swarmvm installed from a wheel, and the firmware built by the qemu/ Makefile."""
    github, _ = workflows()
    kilobot, capbot = (next(iter(github[t]["jobs"].values()))["steps"] for t in ("kilobot", "capbot"))
    assert [s.get("name", s.get("uses")) for s in capbot] == [s.get("name", s.get("uses")) for s in kilobot][:2] + [
        "Install swarmvm from its wheel, the Cortex-M toolchain and QEMU", "Build the firmware bare-metal for QEMU",
        *[s.get("name", s.get("uses")) for s in kilobot][4:]]
    (install,) = [s for s in capbot if s.get("name", "").startswith("Install")]
    assert install["run"].splitlines()[1] == WHEEL and "qemu-system-arm" in install["run"]
    build = capbot[3]["run"].splitlines()
    assert build == ["swarmvm gen supervisor.yaml --target capbot -o firmware --name robot", "make -C firmware/qemu"]
    download = next(s for s in capbot if s.get("uses", "").startswith("dawidd6/action-download-artifact@"))
    upload = next(s for s in capbot if s.get("uses", "").startswith("actions/upload-artifact@"))
    assert download["with"]["workflow"] == "footprint-capbot.yml"
    assert download["with"]["name"] == upload["with"]["name"] == "footprint-capbot"
    comment = next(s for s in capbot if "gh pr comment" in s.get("run", ""))
    assert CAPBOT_MARKER in comment["run"] and MARKER + '"' not in comment["run"]
    for ours, theirs in zip(capbot[4:], kilobot[4:]):       # the rest: the Kilobot's, with the CapBot's image
        run = ours.get("run", "")
        for capbot_text, kilobot_text in KILOBOT_FOR_CAPBOT:
            run = run.replace(capbot_text, kilobot_text)
        assert run == theirs.get("run", ""), ours.get("name")


def test_a_capbot_pull_request_builds_its_base_and_comments_from_the_wheel_alone(capbot_repository, services):
    """The pull request's firmware and the base commit's built bare-metal for QEMU by the qemu/
    Makefile gen wrote (no file of swarmvm's checkout), measured with the sidecar's declarations
    and script in QEMU, compared, and one comment kept; a budget exceeded fails with annotations."""
    first = run_github(services, capbot_repository.checkout("grow"), "grow", pr=8, target="capbot")
    assert all(status in (None, 0) for status in first.statuses), first.log
    base = first.temp / "base" / "firmware" / "qemu"
    assert (base / "robot.elf").is_file() and (base / "robot.footprint.json").is_file()
    assert git(first.temp / "base", "rev-parse", "HEAD") == capbot_repository.base
    report = json.loads((first.folder / "footprint.json").read_text())
    (image,) = report["images"]
    assert image["target"] == "capbot" and image["elf"] == "firmware/qemu/robot.elf"
    assert "unknown" not in image["stack"] and image["cycles"]["steps"] == 20 and report["violations"] == []
    (comment,) = services.load()["comments"]
    assert comment["pr"] == "8"
    assert_reviewable(comment["body"], capbot_repository.base, CAPBOT_MARKER, 30000)
    assert "| capbot | robot | changed |" in comment["body"]
    assert "the `footprint-capbot` artifact of [run 1]" in comment["body"]
    assert set(services.github_artifacts["grow"]["footprint-capbot"]) == {"footprint.json", "footprint.svg"}

    over = run_github(services, capbot_repository.checkout("over"), "over", pr=8, target="capbot")
    failed = over.statuses.index(1)
    assert over.statuses[failed + 1:] == [0, None]
    errors = [line for line in over.logs[failed].splitlines() if line.startswith("::error::")]
    assert any(re.fullmatch(r"::error::swarmvm: footprint: capbot/robot: flash \d+ B over its budget of 1000 B "
                            r"\(by \d+ B\)", e) for e in errors), errors
    (comment,) = services.load()["comments"]                                # updated, not a second one
    assert "over its budget of 1000 B" in comment["body"] and "capbot/robot: flash from 30000 to 1000 B" in comment["body"]


# ---- GitLab CI ------------------------------------------------------------------------------

def test_the_gitlab_job_runs_on_merge_requests_and_main_and_keeps_junit_json_and_chart():
    _, (name, job) = recipes()
    assert [rule["if"] for rule in job["rules"]] == ['$CI_PIPELINE_SOURCE == "merge_request_event"',
                                                     "$CI_COMMIT_BRANCH == $CI_DEFAULT_BRANCH"]
    assert job["variables"]["GIT_DEPTH"] == "0" and PLACEHOLDER in job["before_script"]
    assert job["artifacts"]["when"] == "always" and job["artifacts"]["paths"] == ["footprint.json", "footprint.svg"]
    assert job["artifacts"]["reports"]["junit"] == "footprint-junit.xml" and job["artifacts"]["expose_as"]
    assert all(isinstance(line, str) for line in job["before_script"] + job["script"])
    assert any("$CI_DEFAULT_BRANCH" in line and "?job=$CI_JOB_NAME" in line for line in job["script"])
    assert job["script"][-1] == "exit $status"


def job_temp(folder: Path) -> Path:
    """The job's TMPDIR, where the recipe puts the base commit's worktree."""
    temp = folder.parent / ("%s-tmp" % folder.name)
    temp.mkdir(exist_ok=True)
    return temp


def run_gitlab(services: Services, folder: Path, repository: Repository, merge_request: int | None = None):
    """The job's ``script`` as GitLab's runner runs it: its lines in order in one bash (-e,
    pipefail), with the predefined variables the job uses, of a merge request pipeline (its IID
    and diff base) or, without ``merge_request``, of the default branch."""
    _, (name, job) = recipes()
    services.runs = getattr(services, "runs", 0) + 1
    variables = dict(CI_API_V4_URL=GITLAB_API, CI_PROJECT_ID="7", CI_DEFAULT_BRANCH="main", CI_JOB_NAME=name,
                     CI_JOB_TOKEN="job-token", CI_JOB_ID=str(services.runs), CI_PROJECT_DIR=str(folder),
                     CI_JOB_URL="https://gitlab.example.com/developer/robot/-/jobs/%d" % services.runs,
                     FOOTPRINT_TOKEN="project-token", TMPDIR=str(job_temp(folder)))
    if merge_request is None:
        variables.update(CI_PIPELINE_SOURCE="push", CI_COMMIT_BRANCH="main")
    else:
        variables.update(CI_PIPELINE_SOURCE="merge_request_event", CI_MERGE_REQUEST_IID=str(merge_request),
                         CI_MERGE_REQUEST_DIFF_BASE_SHA=repository.base)
    return subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", "\n".join(job["script"])],
                          cwd=folder, env=services.environment(**variables), capture_output=True, text=True,
                          timeout=300)


def artifact_url(job_name: str) -> str:
    return "%s/projects/7/jobs/artifacts/main/raw/footprint.json?job=%s" % (GITLAB_API, job_name)


def test_a_merge_request_without_a_main_report_builds_the_base_commit_and_posts_a_note(repository, services):
    _, (name, _) = recipes()
    folder = repository.checkout("grow")
    result = run_gitlab(services, folder, repository, merge_request=3)
    assert result.returncode == 0, result.stdout + result.stderr
    assert git(job_temp(folder) / ("footprint-base-%d" % services.runs), "rev-parse", "HEAD") == repository.base
    assert "Against main.json: 1 changed" in result.stdout and SYMBOL_ROW in result.stdout
    state = services.load()
    assert state["calls"][0][-1] == artifact_url(name) and ["--header", "JOB-TOKEN: job-token"] == state["calls"][0][5:7]
    (note,) = state["notes"]
    assert note["path"] == "/api/v4/projects/7/merge_requests/3/notes"
    assert note["headers"] == {"PRIVATE-TOKEN": "project-token"}
    assert_reviewable(note["body"], repository.base)
    assert "Chart: [footprint.svg](https://gitlab.example.com/developer/robot/-/jobs/1/artifacts/file/footprint.svg)" \
        in note["body"]
    assert (folder / "footprint.svg").read_text().lstrip().startswith(("<svg", "<?xml"))
    cases = ET.parse(folder / "footprint-junit.xml").getroot().iter("testcase")
    assert any("growth" in case.get("name") for case in cases)

    again = run_gitlab(services, repository.checkout("grow"), repository, merge_request=3)
    assert again.returncode == 0, again.stdout + again.stderr
    state = services.load()
    (note,) = state["notes"]                                                # updated, not a second one
    assert "/jobs/2/artifacts/file/footprint.svg" in note["body"]
    assert_reviewable(note["body"], repository.base)
    writes = [(call[call.index("--request") + 1], call[-1]) for call in state["calls"] if "--request" in call]
    notes = GITLAB_API + "/projects/7/merge_requests/3/notes"
    assert writes == [("POST", notes), ("PUT", "%s/%d" % (notes, note["id"]))]


def test_the_default_branch_keeps_its_report_and_a_merge_request_compares_with_it(repository, services):
    _, (name, _) = recipes()
    main = repository.checkout("main")
    first = run_gitlab(services, main, repository)
    assert first.returncode == 0, first.stderr
    assert "| kilobot | robot |" in first.stdout and "Against" not in first.stdout
    state = services.load()
    assert state["notes"] == [] and [call[-1] for call in state["calls"]] == [artifact_url(name)]
    state["artifacts"][artifact_url(name)] = (main / "footprint.json").read_text()    # the job's artifact
    services.save(state)

    request = repository.checkout("grow")
    second = run_gitlab(services, request, repository, merge_request=4)
    assert second.returncode == 0, second.stderr
    assert not (job_temp(request) / ("footprint-base-%d" % services.runs)).exists()   # main's report was there
    (note,) = services.load()["notes"]
    assert_reviewable(note["body"], repository.base)


def test_a_budget_the_merge_request_exceeds_fails_the_job_with_the_failure_in_junit(repository, services):
    folder = repository.checkout("over")
    result = run_gitlab(services, folder, repository, merge_request=5)
    assert result.returncode == 1
    budget_lines = re.findall(r"^swarmvm: footprint: kilobot/robot: flash \d+ B over its budget of 1000 B \(by \d+ B\)$",
                              result.stderr, re.M)
    assert len(budget_lines) == 1, result.stderr                   # the JUnit run's stderr is not repeated
    failed = [case for case in ET.parse(folder / "footprint-junit.xml").getroot().iter("testcase")
              if case.find("failure") is not None]
    assert [case.get("name") for case in failed] == ["flash <= 1000 B (budget)"]
    assert json.loads((folder / "footprint.json").read_text())["violations"]      # kept as the artifact
    (note,) = services.load()["notes"]
    assert "over its budget of 1000 B" in note["body"]


# ---- the project's own CI: make footprint's comparison ----------------------------------------

def make_example(build: Path, *variables: str) -> subprocess.CompletedProcess:
    return subprocess.run(["make", "-s", "--no-print-directory", "-C", str(ROOT), "footprint-example",
                           "BUILD=%s" % build, *variables], capture_output=True, text=True, timeout=900)


def test_make_footprint_prints_the_delta_against_the_baseline(build, tmp_path):
    """`make footprint-example` (which `make footprint` ends with) against the repository's
    baseline made smaller: the delta is printed, and 100 B is no failure. Cycles compare only
    across one event script (issue 36): a baseline written before the JSON recorded the script's
    digest is given the digest of the script make writes (steps 40, seed 1), the one it was
    measured with; `make footprint-baseline` writes it."""
    board_or_skip()
    baseline = json.loads((ROOT / "benchmarks" / "footprint-baseline.json").read_text())
    assert [(i["target"], i["supervisor"], i["cycles"]["steps"]) for i in baseline["images"]] == [
        ("kilobot", "energy_worker", 40)]
    events = subprocess.run(["swarmvm", "script", str(EXAMPLE), "--steps", "40", "--seed", "1"], check=True,
                            capture_output=True, text=True).stdout.encode()
    baseline["images"][0]["cycles"].setdefault("script_sha256", hashlib.sha256(events).hexdigest())
    smaller = tmp_path / "smaller.json"
    smaller.write_text(json.dumps(shrink(baseline)))
    result = make_example(build, "FOOTPRINT_BASELINE=%s" % smaller)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Against %s: " % smaller in result.stdout
    assert "| kilobot | energy_worker | changed |" in result.stdout
    assert "+100 B, " in result.stdout and "Growth allowed: 10 % per column." in result.stdout
    assert "cycles/step" in result.stdout and ", 40 steps: mean " in result.stdout


def test_make_footprint_fails_on_a_budget(build, tmp_path):
    board_or_skip()
    budget = tmp_path / "budget.toml"
    budget.write_text("[kilobot.rows.energy_worker]\ncycles = 100\n")
    result = make_example(build, "FOOTPRINT_BUDGET=%s" % budget)
    assert result.returncode != 0
    assert re.search(r"swarmvm: footprint: kilobot/energy_worker: cycles \d+ cycles over its budget of 100 cycles",
                     result.stderr), result.stderr
    assert "footprint-example] Error 1" in result.stderr               # the command's status 1 fails make


def test_the_projects_budgets_hold_on_the_baseline():
    """The baseline in the repository is within the project's own budgets (pyproject.toml)."""
    baseline = json.loads((ROOT / "benchmarks" / "footprint-baseline.json").read_text())
    assert baseline["budget_file"] == "pyproject.toml" and baseline["violations"] == []
    budgets = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["swarmvm"]["footprint"]["kilobot"]
    rows = budgets.pop("rows")
    assert baseline["images"][0]["budget"] == {**budgets, **rows["energy_worker"]}


# ---- --cycles from the installed package ------------------------------------------------------

def test_cycles_build_the_board_from_the_package_into_an_empty_cache(build, tmp_path):
    """`swarmvm footprint --cycles` of the swarmvm on PATH (under `make wheel-check`, the wheel's
    install, away from any checkout): the board's C source comes with the package and is built
    into the user's cache on first use, once."""
    board_or_skip()
    events = tmp_path / "events.txt"
    events.write_text(subprocess.run(["swarmvm", "script", str(EXAMPLE), "--steps", "5", "--seed", "2"],
                                     check=True, capture_output=True, text=True).stdout)
    cache = tmp_path / "cache"
    environment = dict(os.environ, XDG_CACHE_HOME=str(cache))
    elf = build / "kilobot" / "gen" / "energy_worker" / "energy_worker.elf"
    command = ["swarmvm", "footprint", str(elf), *INDIRECT, "--cycles", str(events)]
    first = subprocess.run(command, cwd=tmp_path, env=environment, capture_output=True, text=True)
    assert first.returncode == 0, first.stderr
    assert "events.txt, 5 steps: mean " in first.stdout
    (board,) = (cache / "swarmvm").glob("kilobot_board-*")
    built = board.stat().st_mtime_ns
    again = subprocess.run(command, cwd=tmp_path, env=environment, capture_output=True, text=True)
    assert again.stdout == first.stdout and board.stat().st_mtime_ns == built


def test_cycles_without_a_c_compiler_say_what_is_missing(build, tmp_path, monkeypatch):
    """No board in the cache and no C compiler to build it: the error says what to install."""
    import swarmvm.footprint.kilobot_board
    from swarmvm import api
    from swarmvm.footprint.measure import FootprintError
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.setattr(swarmvm.footprint.kilobot_board.shutil, "which", lambda name: None)
    events = tmp_path / "events.txt"
    events.write_text("-\n")
    elf = build / "kilobot" / "gen" / "energy_worker" / "energy_worker.elf"
    with pytest.raises(FootprintError, match=r"^--cycles: kilobot board: needs a C compiler and simavr's headers"):
        api.measure_footprint([str(elf)], indirect=list(KILOBOT_INDIRECT), cycles=str(events))
