"""Generated ARGoS projects built and run in real ARGoS: each project built with its own
CMakeLists.txt, experiments run headless with their output read from the files ARGoS writes.
Shared by the tests in tests/targets/argos/ and by `make argos-demo` (firmware/argos_demo.py)."""

import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from checkout import ROOT
from swarmvm.compiler.naming import fnv1a

ARGOS_SH = ROOT / "scripts" / "argos.sh"
CORPUS = ROOT / "tests" / "corpus" / "openswarm"
NO_ARGOS = 3   # exit status of scripts/argos.sh: no ARGoS and no source archive
SWARMVM = [sys.executable, "-m", "swarmvm"]   # this Python's, whether or not its venv is on PATH


@dataclass(frozen=True)
class Project:
    """A folder written by `swarmvm gen --target argos` for the supervisor `supervisor`, its
    files named after `name`."""
    folder: Path
    name: str
    supervisor: Path


def find_argos():
    """(exit status, install prefix or None, stderr) of scripts/argos.sh: finds ARGoS, or builds
    it once from its source archive. Its stderr is passed on to this process's as it comes: a
    build's stages and progress must reach the terminal of `make argos-demo` during the wait."""
    with subprocess.Popen([str(ARGOS_SH)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as process:
        said = []
        for line in process.stderr:   # stdout is one line, read after: no pipe fills up meanwhile
            sys.stderr.write(line)
            sys.stderr.flush()
            said.append(line)
        prefix = process.stdout.read().strip()
    return process.returncode, Path(prefix) if process.returncode == 0 else None, "".join(said)


def generate(supervisor, folder, name=None):
    """`swarmvm gen SUPERVISOR --target argos -o FOLDER [--name NAME]`."""
    supervisor = Path(supervisor)
    name = name or supervisor.stem
    subprocess.run([*SWARMVM, "gen", str(supervisor), "--target", "argos", "-o", str(folder), "--name", name],
                   check=True, capture_output=True)
    return Project(Path(folder), name, supervisor)


def build(project, compiler, locate):
    """Configures and builds a generated project with its CMakeLists.txt, -Werror added, into
    its build/ folder; `locate` is the -D option that says where ARGoS is (the environment's
    ARGOS_PREFIX is cleared so that it is the only hint). Returns the configure and build output
    (verbose: the compile commands)."""
    log = project.folder / "cmake.log"
    with open(log, "w") as out:
        for command in (["cmake", "-S", str(project.folder), "-B", str(project.folder / "build"),
                         "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + compiler, "-DCMAKE_CXX_FLAGS=-Werror",
                         locate],
                        ["cmake", "--build", str(project.folder / "build"), "--", "VERBOSE=1"]):
            result = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, env=dict(os.environ, ARGOS_PREFIX=""))
            if result.returncode != 0:
                raise RuntimeError("%s failed:\n%s" % (" ".join(command[:2]), log.read_text()))
    return log.read_text()


def experiment(project, variant, robots=None, length=None, random_seed=None, options=None, report=None):
    """A copy of the generated .argos file named `variant`.argos, with the given changes: number
    of e-pucks, length in seconds, random seed, <options> and <report> attributes."""
    tree = ET.parse(project.folder / (project.name + ".argos"))
    root = tree.getroot()
    settings = root.find("framework/experiment")
    if length is not None:
        settings.set("length", str(length))
    if random_seed is not None:
        settings.set("random_seed", str(random_seed))
    if robots is not None:
        root.find("arena/distribute/entity").set("quantity", str(robots))
    params = root.find("controllers")[0].find("params")
    for element, changes in (("options", options), ("report", report)):
        for key, value in (changes or {}).items():
            params.find(element).set(key, value)
    path = project.folder / (variant + ".argos")
    tree.write(path)
    return path


def run_argos(project, experiment_file):
    """Runs `argos3 -c FILE` headless in the project folder. Returns (exit status, LOG output,
    LOGERR output), both read from the files ARGoS wrote."""
    log = project.folder / (experiment_file.stem + ".log")
    err = project.folder / (experiment_file.stem + ".err")
    result = subprocess.run([str(ARGOS_SH), "run", "-n", "-c", experiment_file.name, "-l", log.name, "-e", err.name],
                            cwd=project.folder, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    return result.returncode, log.read_bytes().decode(), err.read_bytes().decode()


def robot_lines(log, kind):
    """LOG lines "<kind> <robot id> <rest>" of an ARGoS run, as {robot id: [rest, ...]}."""
    lines = {}
    for line in log.splitlines():
        if line.startswith(kind + " "):
            robot, rest = line[len(kind) + 1:].split(" ", 1)
            lines.setdefault(robot.rstrip(":"), []).append(rest)
    return lines


def robot_seed(seed, robot):
    """The VM seed of the robot with id `robot` in an experiment seeded `seed`, as the generated
    controller computes it (swarmvm::robot_seed)."""
    return seed ^ fnv1a(robot)


def write_script(project, steps, seed):
    """`swarmvm script` for the project's supervisor into events.txt in its folder."""
    script = project.folder / "events.txt"
    with open(script, "w") as out:
        subprocess.run([*SWARMVM, "script", str(project.supervisor), "--steps", str(steps), "--seed", str(seed)],
                       stdout=out, check=True)
    return script


def reference_trace(project, script, seed, options, robot):
    """`swarmvm trace` of the project's supervisor for one robot (its VM seed), as lines."""
    out = project.folder / ("reference_%s.txt" % robot)
    with open(out, "w") as trace:
        subprocess.run([*SWARMVM, "trace", str(project.supervisor), "--script", str(script), "--seed", str(seed)]
                       + ["--%s=%s" % item for item in (options or {}).items()], stdout=trace, check=True)
    return out.read_text().splitlines()


SWITCH_PAGE = ROOT / "docs" / "compat.md"
SWITCH_SECTION = "### Switching an OpenSwarm ARGoS project over"


def switch_blocks():
    """The fenced blocks of docs/compat.md's switch section, in order, as (language, text): the
    steps the switch tests run as written."""
    text = SWITCH_PAGE.read_text()
    start = text.index(SWITCH_SECTION)
    following = re.compile(r"^#{1,3} ", re.M).search(text, start + len(SWITCH_SECTION))
    section = text[start:following.start() if following else len(text)]
    return re.findall(r"^```(\w+)\n(.*?)^```$", section, re.M | re.S)


def needed_libraries(folder):
    """The shared libraries a built project's plugins need (readelf's NEEDED entries)."""
    needed = set()
    for plugin in (folder / "build").rglob("*.so"):
        dynamic = subprocess.run(["readelf", "-d", str(plugin)], capture_output=True, text=True, check=True).stdout
        needed.update(re.findall(r"\(NEEDED\).*\[(.*)\]", dynamic))
    return needed
