"""The C++ drop-in (runtime_cpp/sct.h: SCT, SCTPub) steps exactly as the published C++ VM: the
published sct.cpp of ../shared/reference/ (an oracle, built here with yaml-cpp against real
ARGoS, never copied) and the drop-in are built into the same driver (sct_drive.cpp: callbacks
registered the published way, checks with side effects), given the same ARGoS random seed, and
must print the same calls and states for every step of every corpus supervisor and of random
supervisors in the variants the published VM runs and swarmvm once refused or misread (names
without `EV_` or holding `-`, nondeterministic transitions, a start state other than the
initial one), with every registration of sct_drive.cpp: once, again (which replaces action and
check; a check on a controllable event), and with checks that throw argos::CARGoSException (the
driver catches it as such). The drop-in reads the image `swarmvm pack` writes beside the YAML
file; the oracle reads the YAML file."""

import os
import random
import shutil
import subprocess
from pathlib import Path

import pytest
import yaml

from checkout import ROOT
from swarmvm import api
from swarmvm.compiler.runtime_files import RUNTIME_CPP

pytestmark = pytest.mark.emulator   # real ARGoS's libraries

REFERENCE = ROOT.parent / "shared" / "reference" / "openswarm-sct-cpp"
DRIVER = Path(__file__).with_name("sct_drive.cpp")
CORPUS = sorted((ROOT / "tests" / "corpus").glob("*/*.yaml"))
STEPS = 1000
REGISTRATIONS = ("both", "again", "throws")
RANDOM_SUPERVISORS = 12


@pytest.fixture(scope="module")
def drivers(argos_prefix, tmp_path_factory):
    """(oracle, drop-in) executables and the environment to run them in."""
    if not (REFERENCE / "sct.cpp").is_file() or shutil.which("pkg-config") is None or subprocess.run(
            ["pkg-config", "--exists", "yaml-cpp"]).returncode != 0:
        if os.environ.get("CI") == "true":
            pytest.fail("the published sct.cpp (../shared/reference/) and yaml-cpp (libyaml-cpp-dev) are needed")
        pytest.skip("needs ../shared/reference/openswarm-sct-cpp and yaml-cpp (apt install libyaml-cpp-dev)")
    out = tmp_path_factory.mktemp("sct_exact")
    common = ["g++", "-std=c++17", "-O1", "-I%s" % (argos_prefix / "include"), str(DRIVER)]
    libs = ["-L%s" % (argos_prefix / "lib" / "argos3"), "-largos3core_simulator"]
    oracle, dropin = out / "published", out / "swarmvm"
    subprocess.run([*common[:4], "-w", "-I%s" % REFERENCE, *common[4:], str(REFERENCE / "sct.cpp"), "-o", str(oracle),
                    *libs, "-lyaml-cpp"], check=True)
    subprocess.run([*common[:4], "-Wall", "-Wextra", "-Werror", "-I%s" % RUNTIME_CPP, *common[4:], "-o", str(dropin),
                    *libs], check=True)
    env = dict(os.environ, LD_LIBRARY_PATH=str(argos_prefix / "lib" / "argos3"))
    return oracle, dropin, env


def published_lines(drivers, supervisor, mode, registration, steps):
    """The step lines of the oracle and of the drop-in on ``supervisor`` (its image packed beside it)."""
    oracle, dropin, env = drivers
    runs = [subprocess.run([str(exe), str(supervisor), mode, str(steps), "1445", registration], capture_output=True,
                           text=True, env=env) for exe in (oracle, dropin)]
    assert [r.returncode for r in runs] == [0, 0], runs[0].stderr + runs[1].stderr
    # (ARGoS's log adds a colour reset at exit: only the step lines count)
    return ([line for line in r.stdout.splitlines() if line.startswith("sup:[")] for r in runs)


def assert_same_run(drivers, supervisor, modes, steps):
    for mode in modes:
        for registration in REGISTRATIONS:
            want, got = published_lines(drivers, supervisor, mode, registration, steps)
            assert len(want) == steps
            for step, (expected, line) in enumerate(zip(want, got), 1):
                assert line == expected, "%s %s %s: step %d" % (supervisor.parent.name, mode, registration, step)
            assert got == want


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: p.stem)
def test_the_drop_in_steps_as_the_published_vm(drivers, path, tmp_path):
    supervisor = tmp_path / "supervisor.yaml"
    shutil.copy(path, supervisor)
    api.write_image([str(supervisor)], str(tmp_path / "supervisor.svm"))
    # The published SCTPub reads ev_shared, which not every file has.
    modes = ["plain"] + (["pub"] if "ev_shared" in yaml.safe_load(path.read_text()) else [])
    assert_same_run(drivers, supervisor, modes, STEPS)


def random_supervisor(rng):
    """A supervisor.yaml the published VM runs as its author meant, in the variants swarmvm once
    refused or misread: names as written with and without `EV_`, some holding `-`; a state's
    second transition on an event (the published search takes the first); sup_current_state
    other than sup_init_state."""
    n_events = rng.randint(3, 9)
    stems = rng.sample(["go", "stop", "e9", "turn-left", "bid", "a-b-c", "x", "lost_bid", "won", "r2-d2"], n_events)
    names = [("EV_" if rng.random() < 0.5 else "") + stem for stem in stems]
    controllable = [rng.randint(0, 1) for _ in names]
    n_sups = rng.randint(1, 3)
    alphabets = [[rng.random() < 0.7 for _ in names] for _ in range(n_sups)]
    for e in range(n_events):                       # every event in some supervisor
        if not any(a[e] for a in alphabets):
            alphabets[rng.randrange(n_sups)][e] = True
    data, positions, states = [], [], []
    for alphabet in alphabets:
        positions.append(len(data))
        own = [e for e in range(n_events) if alphabet[e]]
        count = rng.randint(1, 5)
        states.append(count)
        for _ in range(count):
            transitions = [(e, rng.randrange(count)) for e in own if rng.random() < 0.6]
            if transitions and rng.random() < 0.3:   # nondeterministic: a second transition on an event
                transitions.append((transitions[0][0], rng.randrange(count)))
                rng.shuffle(transitions)
            data.append(str(len(transitions)))
            for e, target in transitions:
                data += [names[e], str(target // 256), str(target % 256)]

    def flow(values):
        return "[ %s ]" % ",".join(str(v) for v in values)

    return "\n".join([
        "num_events: %d" % n_events, "num_supervisors: %d" % n_sups, "events: " + flow(names),
        "ev_controllable: " + flow(controllable), "ev_shared: " + flow(rng.randint(0, 1) for _ in names),
        "sup_events: " + flow(flow(int(x) for x in a) for a in alphabets),
        "sup_init_state: " + flow(0 for _ in alphabets),
        "sup_current_state: " + flow(rng.randrange(count) for count in states),
        "sup_data_pos: " + flow(positions), "sup_data: " + flow(data), ""])


@pytest.mark.parametrize("seed", range(RANDOM_SUPERVISORS))
def test_random_supervisors_run_as_on_the_published_vm(drivers, seed, tmp_path):
    supervisor = tmp_path / "supervisor.yaml"
    supervisor.write_text(random_supervisor(random.Random(seed)))
    api.write_image([str(supervisor)], str(tmp_path / "supervisor.svm"))
    assert_same_run(drivers, supervisor, ["plain", "pub"], 300)
