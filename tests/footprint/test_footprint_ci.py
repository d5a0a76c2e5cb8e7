"""Footprint reports in CI (issue 25, point 6; docs/footprint.md, "In a user's CI" and "The
project's own CI"): the GitHub Actions workflow and the GitLab CI job the docs give, read from
the docs and run step by step against the bundled example; `make footprint`'s comparison of the
example with the baseline kept in the repository; and `--cycles` from an installed swarmvm,
which builds the simavr board from the package's own C source into an empty cache.

The recipes run as a CI would run them, with the machine's tools in place of their install
steps (the swarmvm of the Python running the tests, avr-gcc, simavr, kilolib built in the cache
as `kilolib/`) and the test standing in for the CI's artifact store: GitHub's artifact actions
copy files in and out of it, GitLab's job-artifacts API is served from it over HTTP."""

import hashlib
import http.server
import json
import os
import re
import shutil
import subprocess
import threading
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

from checkout import EXAMPLE, ROOT
from footprint_images import KILOBOT_INDIRECT
from targets.kilobot.needs import board_or_skip, kilolib_or_skip

DOC = ROOT / "docs" / "footprint.md"
YAML_BLOCK = re.compile(r"^```yaml\n(.*?)^```", re.M | re.S)
INDIRECT = [arg for declaration in KILOBOT_INDIRECT for arg in ("--indirect", declaration)]
TIGHT_BUDGET = "[tool.swarmvm.footprint.kilobot]\nflash = 1000\n"      # the example's image is ~12 kB


def recipes():
    """The docs' YAML blocks that are CI recipes: (GitHub workflow, GitLab job name and job)."""
    github = gitlab = None
    for block in YAML_BLOCK.findall(DOC.read_text()):
        data = yaml.safe_load(block)
        if "jobs" in data:
            github = data
        else:
            ((name, job),) = [(k, v) for k, v in data.items() if isinstance(v, dict) and "script" in v]
            gitlab = name, job
    assert github is not None and gitlab is not None, "docs/footprint.md: both recipes as ```yaml blocks"
    return github, gitlab


@pytest.fixture
def user_repository(tmp_path):
    """A user's checkout after the recipes' install steps: the supervisor, and kilolib built."""
    board_or_skip()
    folder = tmp_path / "repository"
    folder.mkdir()
    shutil.copy(EXAMPLE, folder / "supervisor.yaml")
    (folder / "kilolib").symlink_to(kilolib_or_skip())
    return folder


def fresh_copy(repository, name):
    """The repository as another run's checkout (a new workspace, as CI gives each run)."""
    folder = repository.parent / name
    shutil.copytree(repository, folder, symlinks=True)
    return folder


def shrink(report: dict) -> dict:
    """The report of an image 100 B and 50 cycles smaller: what a change has grown from."""
    image = report["images"][0]
    image["flash"]["total"] -= 100
    image["flash"]["application"] -= 100
    image["cycles"]["worst"] -= 50
    return report


# ---- GitHub Actions -------------------------------------------------------------------------

def test_the_github_workflow_runs_on_pull_requests_and_main_and_keeps_the_report():
    github, _ = recipes()
    triggers = github.get("on", github.get(True))         # YAML 1.1 reads the key `on` as true
    assert triggers["push"]["branches"] == ["main"] and "pull_request" in triggers
    (job,) = github["jobs"].values()
    steps = job["steps"]
    assert all(("run" in step) != ("uses" in step) for step in steps)
    download = next(s for s in steps if s.get("uses", "").startswith("dawidd6/action-download-artifact@"))
    upload = next(s for s in steps if s.get("uses", "").startswith("actions/upload-artifact@"))
    assert download["with"]["branch"] == "main" and download["with"]["workflow"] == "footprint.yml"
    assert download["with"]["name"] == upload["with"]["name"] and upload["with"]["path"] == "footprint.json"
    assert upload["if"] == "always()" and steps.index(download) < steps.index(upload)
    assert any("$GITHUB_STEP_SUMMARY" in s.get("run", "") for s in steps)


def run_github(workflow: dict, folder: Path, artifacts: dict) -> tuple[list[int | None], str]:
    """Each step of the workflow's job in order, as GitHub's runner would: ``run`` steps in bash
    (-e, pipefail), a failed step skipping the later ones unless they say ``if: always()``; the
    artifact actions copy between ``folder`` and ``artifacts`` (name -> file name -> bytes).
    Returns each step's exit status (None: not run, or an action) and the job summary."""
    summary = folder.parent / ("%s-summary.md" % folder.name)
    summary.write_text("")
    environment = dict(os.environ, GITHUB_STEP_SUMMARY=str(summary))
    statuses: list[int | None] = []
    failed = False
    for step in next(iter(workflow["jobs"].values()))["steps"]:
        assert step.get("if", "always()") == "always()", "a condition the test does not evaluate: %s" % step["if"]
        if (failed and "if" not in step) or step.get("name", "").startswith("Install"):
            statuses.append(None)
            continue
        uses, given = step.get("uses", ""), step.get("with", {})
        if uses.startswith("dawidd6/action-download-artifact@"):
            for name, data in artifacts.get(given["name"], {}).items():
                (folder / given["path"]).mkdir(exist_ok=True)
                (folder / given["path"] / name).write_bytes(data)
        elif uses.startswith("actions/upload-artifact@"):
            artifacts[given["name"]] = {given["path"]: (folder / given["path"]).read_bytes()}
        elif "run" in step:
            result = subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", step["run"]],
                                    cwd=folder, env=environment, capture_output=True, text=True, timeout=600)
            statuses.append(result.returncode)
            failed = failed or result.returncode != 0
            continue
        statuses.append(None)
    return statuses, summary.read_text()


def test_the_github_workflow_on_main_then_on_a_pull_request(user_repository):
    github, _ = recipes()
    artifacts: dict = {}
    statuses, summary = run_github(github, fresh_copy(user_repository, "main"), artifacts)
    assert all(status in (None, 0) for status in statuses), statuses
    assert "| kilobot | robot |" in summary and "Against" not in summary       # nothing to compare with yet
    main = json.loads(artifacts["footprint"]["footprint.json"])
    assert main["images"][0]["cycles"]["steps"] == 40

    artifacts["footprint"]["footprint.json"] = json.dumps(shrink(main)).encode()
    statuses, summary = run_github(github, fresh_copy(user_repository, "pull"), artifacts)
    assert all(status in (None, 0) for status in statuses), statuses
    assert "Against baseline/footprint.json: 1 changed" in summary
    assert re.search(r"\(was \d+: \+100 B, \+0\.\d\d %\)", summary) and ": +50 cycles, +" in summary
    assert "Growth allowed: 10 % per column." in summary


def test_the_github_workflow_fails_on_a_budget_and_still_publishes_and_keeps_the_report(user_repository):
    github, _ = recipes()
    folder = fresh_copy(user_repository, "over")
    (folder / "pyproject.toml").write_text(TIGHT_BUDGET)
    artifacts: dict = {}
    statuses, summary = run_github(github, folder, artifacts)
    assert 1 in statuses and statuses[statuses.index(1) + 1:] == [None]     # the upload, run whatever came
    assert "over its budget of 1000 B" in summary
    assert json.loads(artifacts["footprint"]["footprint.json"])["violations"]


# ---- GitLab CI ------------------------------------------------------------------------------

def test_the_gitlab_job_reports_junit_and_keeps_the_report_always():
    _, (name, job) = recipes()
    assert job["artifacts"]["when"] == "always" and job["artifacts"]["paths"] == ["footprint.json"]
    assert job["artifacts"]["reports"]["junit"] == "footprint-junit.xml"
    assert all(isinstance(line, str) for line in job["before_script"] + job["script"])
    assert any("$CI_DEFAULT_BRANCH" in line and "?job=$CI_JOB_NAME" in line for line in job["script"])


class ArtifactsAPI(http.server.BaseHTTPRequestHandler):
    """GitLab's "a single artifact file of a branch's latest successful pipeline", from a dict."""
    files: dict = {}
    seen: list = []

    def do_GET(self):
        self.seen.append((self.path, self.headers.get("JOB-TOKEN")))
        data = self.files.get(self.path)
        self.send_response(200 if data is not None else 404)
        self.end_headers()
        self.wfile.write(data if data is not None else b'{"message":"404 Not found"}')

    def log_message(self, *args):
        pass


@pytest.fixture
def gitlab_api():
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), ArtifactsAPI)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    ArtifactsAPI.files, ArtifactsAPI.seen = {}, []
    yield "http://127.0.0.1:%d/api/v4" % server.server_address[1], ArtifactsAPI
    server.shutdown()


def run_gitlab(job_name: str, job: dict, folder: Path, api_url: str) -> subprocess.CompletedProcess:
    """The job's ``script`` as GitLab's runner runs it: its lines in order in one bash (-e,
    pipefail), with the predefined variables the job uses."""
    environment = dict(os.environ, CI_API_V4_URL=api_url, CI_PROJECT_ID="7", CI_DEFAULT_BRANCH="main",
                       CI_JOB_NAME=job_name, CI_JOB_TOKEN="job-token")
    return subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", "\n".join(job["script"])],
                          cwd=folder, env=environment, capture_output=True, text=True, timeout=600)


def test_the_gitlab_job_on_main_then_on_a_merge_request(user_repository, gitlab_api):
    _, (name, job) = recipes()
    url, api = gitlab_api
    main = fresh_copy(user_repository, "main")
    first = run_gitlab(name, job, main, url)
    assert first.returncode == 0, first.stderr
    assert "| kilobot | robot |" in first.stdout and "Against" not in first.stdout
    assert api.seen == [("/api/v4/projects/7/jobs/artifacts/main/raw/footprint.json?job=%s" % name, "job-token")]

    report = json.loads((main / "footprint.json").read_text())
    api.files[api.seen[0][0]] = json.dumps(shrink(report)).encode()
    request = fresh_copy(user_repository, "request")
    second = run_gitlab(name, job, request, url)
    assert second.returncode == 0, second.stderr
    assert "Against main.json: 1 changed" in second.stdout and ": +100 B, " in second.stdout
    cases = ET.parse(request / "footprint-junit.xml").getroot().iter("testcase")
    assert any("growth" in case.get("name") for case in cases)


def test_the_gitlab_job_fails_on_a_budget_with_the_failure_in_junit(user_repository, gitlab_api):
    _, (name, job) = recipes()
    url, _ = gitlab_api
    folder = fresh_copy(user_repository, "over")
    (folder / "pyproject.toml").write_text(TIGHT_BUDGET)
    result = run_gitlab(name, job, folder, url)
    assert result.returncode == 1
    assert "kilobot/robot: flash" in result.stderr and "over its budget of 1000 B" in result.stderr
    failed = [case for case in ET.parse(folder / "footprint-junit.xml").getroot().iter("testcase")
              if case.find("failure") is not None]
    assert [case.get("name") for case in failed] == ["flash <= 1000 B (budget)"]
    assert (folder / "footprint.json").is_file()                             # kept as the artifact


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
