"""Exact mode of the Python SCT/SCTPub (docs/compat.md) against an oracle written here from the
published Python VM's step as issue 17 describes it (not from its code, which is not kept):

- the check of every uncontrollable event that has one, in the file's event order, before any
  transition; then, in that order (SCTPub: public events first), each event whose check was true
  is applied (every supervisor whose alphabet holds it moves) and its callback runs right after;
- then the enabled controllable events in file order; with n > 0 of them the k-th is taken,
  k = random.randint(0, 1000000000) % n from the global random module, applied, its callback run.

Both run every corpus supervisor for thousands of steps with checks that have side effects (they
draw from a shared world and flip flags other checks read); after every step the states, the
events applied, the order of every check and callback call and the global random state must be
the same."""

import random
from pathlib import Path

import pytest
import yaml

CORPUS = sorted(str(p) for p in (Path(__file__).resolve().parents[1] / "corpus").glob("*/*.yaml"))
STEPS = 2000


class PublishedStep:
    """The oracle: the published VM's tables read straight from the YAML file, indices the file's."""

    def __init__(self, path, public_first):
        doc = yaml.safe_load(Path(path).read_text())
        self.events = [str(e) for e in doc["events"]]
        self.EV = {name: i for i, name in enumerate(self.events)}
        self.controllable = [int(c) for c in doc["ev_controllable"]]
        public = doc.get("ev_public", doc.get("ev_shared", [0] * len(self.events)))
        self.public = [int(p) for p in public]
        self.alphabet = [[int(x) for x in row] for row in doc["sup_events"]]
        self.state = [int(s) for s in doc.get("sup_current_state", doc["sup_init_state"])]     # where it starts
        data, starts = doc["sup_data"], doc["sup_data_pos"]
        # moves[s][state] = {event: target}, from each supervisor's block of state records
        self.moves = []
        for s, start in enumerate(starts):
            pos, table = int(start), []
            end = int(starts[s + 1]) if s + 1 < len(starts) else len(data)
            while pos < end:
                count = int(data[pos])
                moves = {}      # a linear search finds an event's first transition in the file
                for k in range(count):
                    moves.setdefault(self.EV[str(data[pos + 1 + 3 * k])],
                                     int(data[pos + 2 + 3 * k]) * 256 + int(data[pos + 3 + 3 * k]))
                table.append(moves)
                pos += 1 + 3 * count
            self.moves.append(table)
        self.public_first = public_first
        self.callbacks = {}

    def add_callback(self, event, clbk, ci, data):
        self.callbacks[event] = (clbk, ci, data)

    def _apply(self, event):
        for s, table in enumerate(self.moves):
            if self.alphabet[s][event] and event in table[self.state[s]]:
                self.state[s] = table[self.state[s]][event]
        clbk, _, data = self.callbacks.get(event, (None, None, None))
        if clbk is not None:
            clbk(data)

    def _enabled(self, event):
        return all(not self.alphabet[s][event] or event in table[self.state[s]] for s, table in enumerate(self.moves))

    def run_step(self):
        inputs = [e for e in range(len(self.events)) if not self.controllable[e]]
        true = [e for e in inputs if self.callbacks.get(e, (None, None))[1] is not None
                and self.callbacks[e][1](self.callbacks[e][2])]
        if self.public_first:
            true = [e for e in true if self.public[e]] + [e for e in true if not self.public[e]]
        for e in true:
            self._apply(e)
        enabled = [e for e in range(len(self.events)) if self.controllable[e] and self._enabled(e)]
        fired = list(true)
        if enabled:
            choice = enabled[random.randint(0, 1000000000) % len(enabled)]
            self._apply(choice)
            fired.append(choice)
        return fired


class World:
    """Side-effecting checks and logging callbacks, bound by name as a published controller does."""

    def __init__(self, sct, names, seed, acting=None):
        self.draw, self.flags, self.calls = random.Random(seed), {}, []
        for name in names:
            index = sct.EV[name]
            act = (lambda data, name=name: self.act(name)) if acting is None or name in acting else None
            sct.add_callback(index, act, lambda data, name=name: self.check(name), {"name": name})

    def check(self, name):
        self.calls.append("check " + name)
        seen = self.flags.pop(name, False)            # a check that clears what another one set
        other = "EV_" + str(self.draw.randrange(1000))
        self.flags[other] = True
        return seen or self.draw.random() < 0.3

    def act(self, name):
        self.calls.append("act " + name)
        self.flags[name] = True                        # an action that a later check reads


def run(sct, names, step, steps, acting=None):
    world = World(sct, names, seed=11, acting=acting)
    random.seed(5)
    rows = []
    for _ in range(steps):
        del world.calls[:]
        fired = step()
        rows.append((list(getattr(sct, "sup_current_state", None) or sct.state), fired, list(world.calls),
                     random.getstate()))
    return rows


@pytest.mark.parametrize("public_first", [False, True], ids=["SCT", "SCTPub"])
@pytest.mark.parametrize("path", CORPUS, ids=lambda p: Path(p).stem)
def test_exact_mode_matches_the_published_step(vm, path, public_first):
    oracle = PublishedStep(path, public_first)
    compat = (vm.SCTPub if public_first else vm.SCT)(path)
    assert compat.EV == oracle.EV and compat.ev_controllable == oracle.controllable
    expected = run(oracle, list(oracle.EV), oracle.run_step, STEPS)

    def compat_step():
        compat.run_step()
        return compat.last_events

    got = run(compat, list(oracle.EV), compat_step, STEPS)
    for number, (want, have) in enumerate(zip(expected, got), 1):
        assert have[:3] == want[:3], "step %d" % number
        assert have[3] == want[3], "random state after step %d" % number
    assert any(len(row[1]) > 1 for row in got), "the run should fire several events in a step"


@pytest.mark.parametrize("public_first", [False, True], ids=["SCT", "SCTPub"])
@pytest.mark.parametrize("path", CORPUS, ids=lambda p: Path(p).stem)
def test_exact_mode_with_actions_on_controllable_events_only(vm, path, public_first):
    """As published controllers mostly are (checks on the uncontrollable events, actions on the
    controllable ones): the exact step then moves the inputs without looking for actions, and
    still steps as the published one does."""
    oracle = PublishedStep(path, public_first)
    compat = (vm.SCTPub if public_first else vm.SCT)(path)
    acting = {name for name, index in oracle.EV.items() if oracle.controllable[index]}
    expected = run(oracle, list(oracle.EV), oracle.run_step, 500, acting)
    assert run(compat, list(oracle.EV), lambda: compat.run_step() or compat.last_events, 500, acting) == expected
    assert any(len(row[1]) > 1 for row in expected), "the run should fire several events in a step"


class PublishedStyleDrone:
    """A controller written for the published VM, as the drone study's robot program is: the
    VM class is all it is given; callbacks are its methods, registered by name; the lostBid
    check clears the flag the capableTask check reads (the side effect that makes order matter)."""

    def __init__(self, sct_class, path):
        self.sct = sct_class(path)
        self.log, self.offered, self.lost = [], False, False
        ev = self.sct.EV
        for name in ("lostBid", "notCapableTask", "notCondReturn", "condReturn", "capableTask", "wonBid"):
            self.sct.add_callback(ev["EV_" + name], None, getattr(self, "check_" + name), None)
        for name in ("bid", "deliver", "return"):
            self.sct.add_callback(ev["EV_" + name], getattr(self, "on_" + name), None, None)

    def check_lostBid(self, _data):
        lost, self.lost, self.offered = self.lost, False, False
        return lost

    def check_capableTask(self, _data):
        self.offered = self.offered or random.random() < 0.5
        return self.offered

    def check_notCapableTask(self, _data):
        return not self.offered and random.random() < 0.3

    def check_wonBid(self, _data):
        won = random.random() < 0.4
        self.lost = not won
        return won

    def check_condReturn(self, _data):
        return random.random() < 0.2

    def check_notCondReturn(self, _data):
        return random.random() < 0.5

    def on_bid(self, _data):
        self.log.append("bid")

    def on_deliver(self, _data):
        self.log.append("deliver")

    def on_return(self, _data):
        self.log.append("return")


def test_a_published_style_controller_runs_unchanged(vm):
    path = next(p for p in CORPUS if p.endswith("/uav.yaml"))
    runs = []
    for sct_class in (lambda p: PublishedStep(p, public_first=False), vm.SCT):
        random.seed(42)
        drone = PublishedStyleDrone(sct_class, path)
        states = []
        for _ in range(500):
            drone.sct.run_step()
            states.append(list(getattr(drone.sct, "sup_current_state", None) or drone.sct.state))
        runs.append((drone.log, states, random.getstate()))
    assert runs[0] == runs[1]
    assert {"bid", "deliver", "return"} <= set(runs[0][0])


def test_the_yaml_needs_no_pack_and_its_image_keeps_the_order(vm, tmp_path):
    """SCT("x.yaml") compiles the file (no .svm needed); the image `swarmvm pack` writes from it
    keeps the file's event order and state numbers, so exact mode runs from the image alone, as
    on a robot without YAML support; an image without them refuses exact mode."""
    from swarmvm import api
    from swarmvm.compiler.pipeline import compile_inputs
    source = next(p for p in CORPUS if p.endswith("/network_worker.yaml"))
    (tmp_path / "supervisor.yaml").write_bytes(Path(source).read_bytes())
    from_yaml = vm.SCT(str(tmp_path / "supervisor.yaml"))          # no supervisor.svm beside it
    assert from_yaml.exact and list(from_yaml.EV) == PublishedStep(source, False).events
    api.write_image([source], str(tmp_path / "robot.svm"))          # what `swarmvm pack` writes
    runs = [run(sct, list(from_yaml.EV), lambda sct=sct: sct.run_step() or sct.last_events, 300)
            for sct in (from_yaml, vm.SCT(str(tmp_path / "robot.svm")))]
    assert runs[0] == runs[1]
    (tmp_path / "bare.svm").write_bytes(compile_inputs([source], names=False).image)
    with pytest.raises(ValueError, match="exact mode needs the supervisor file's event order"):
        vm.SCT(str(tmp_path / "bare.svm"))
    canonical = vm.SCT(str(tmp_path / "robot.svm"), exact=False)
    assert list(canonical.EV) == sorted(canonical.EV)       # events by name


def test_the_exact_draw_defers_to_a_replaced_randint(vm, monkeypatch, tmp_path):
    """The exact step draws as ``random.randint(0, 1000000000)`` does, bit for bit (the global
    random state is compared step by step with the published step's above); when randint is
    replaced, the step calls the replacement and picks the draw's event in file order."""
    path = tmp_path / "two.yaml"
    path.write_text("num_events: 2\nnum_supervisors: 1\nevents: [ EV_b, EV_a ]\nev_controllable: [ 1, 1 ]\n"
                    "sup_events: [ [ 1, 1 ] ]\nsup_init_state: [ 0 ]\nsup_data_pos: [ 0 ]\n"
                    "sup_data: [ 2, EV_b, 0, 0, EV_a, 0, 0 ]\n")
    sct = vm.SCT(str(path))
    draws = iter([1, 0, 3])
    calls = []
    monkeypatch.setattr(random, "randint", lambda a, b: calls.append((a, b)) or next(draws))
    chosen = []
    for _ in range(3):
        sct.run_step()
        chosen.extend(sct.last_events)
    assert chosen == [1, 0, 1] and [sct.EV[n] for n in ("EV_b", "EV_a")] == [0, 1]
    assert calls == [(0, 1000000000)] * 3


@pytest.mark.parametrize("exact", [True, False], ids=["exact", "canonical"])
def test_an_action_that_registers_again_leaves_the_run_unchanged(vm, exact):
    """An input's action that calls add_callback again makes a new VM plan while the inputs
    fire; the step finishes out of line with the same choice, the same draws (exact mode: the
    global random state) and the same last_events and input_buffer as a run without it."""
    path = next(p for p in CORPUS if p.endswith("/uav.yaml"))
    runs = []
    for again in (False, True):
        sct = vm.SCT(path, exact=exact)
        step = [0]
        for name, index in sct.EV.items():
            if sct.ev_controllable[index]:
                continue
            def check(_d, i=index):
                return (step[0] * 13 + i * 5) % 7 < 2
            action = None
            if again:
                def action(_d, index=index, check=check):
                    sct.add_callback(index, None, check, None)
            sct.add_callback(index, action, check, None)
        random.seed(3)
        rows = []
        for step[0] in range(200):
            sct.run_step()
            rows.append((list(sct.last_events), list(sct.input_buffer), list(sct.sup_current_state),
                         random.getstate()))
        runs.append(rows)
    assert runs[0] == runs[1]
    assert any(len(row[1]) > 0 and len(row[0]) > len(row[1]) for row in runs[0])   # inputs, then a choice


def random_supervisor(seed):
    """A supervisor.yaml the published VM runs, in the variants of issue 24: names without
    ``EV_`` or with '-', states with a second transition on an event, a current state other than
    the initial one (reachable from it or not)."""
    draw = random.Random(seed)
    n_events, n_sups = draw.randint(2, 9), draw.randint(1, 3)
    style = seed % 3
    events = [("e%d" % i, "EV_go-%d" % i, "EV_x%d" % i)[style if style != 2 else i % 3] for i in range(n_events)]
    controllable = [draw.randint(0, 1) for _ in events]
    controllable[0], controllable[1] = 0, 1
    alphabets = [[1 if draw.random() < 0.7 else 0 for _ in events] for _ in range(n_sups)]
    for alphabet in alphabets:
        alphabet[draw.randrange(n_events)] = 1
    data, positions, inits, currents = [], [], [], []
    for alphabet in alphabets:
        positions.append(len(data))
        n_states = draw.randint(1, 5)
        for _ in range(n_states):
            moves = [e for e in range(n_events) if alphabet[e] and draw.random() < 0.6]
            moves += [draw.choice(moves)] if moves and draw.random() < 0.3 else []     # nondeterministic
            data.append(len(moves))
            for e in moves:
                data += [events[e], 0, draw.randrange(n_states)]
        inits.append(draw.randrange(n_states))
        currents.append(draw.randrange(n_states))
    return ("num_events: %d\nnum_supervisors: %d\nevents: [ %s ]\nev_controllable: %s\nsup_events: %s\n"
            "sup_init_state: %s\nsup_current_state: %s\nsup_data_pos: %s\nsup_data: [ %s ]\n"
            % (n_events, n_sups, ", ".join(events), controllable, alphabets, inits, currents, positions,
               ", ".join(map(str, data))))


@pytest.mark.parametrize("seed", range(24))
def test_random_supervisors_in_the_published_variants(vm, tmp_path, seed):
    """Names as written (no EV_, '-'), the start from sup_current_state, the first of two
    transitions on one event: SCT and SCTPub step as the oracle does."""
    path = tmp_path / "supervisor.yaml"
    path.write_text(random_supervisor(seed))
    for public_first in (False, True):
        oracle = PublishedStep(str(path), public_first)
        compat = (vm.SCTPub if public_first else vm.SCT)(str(path))
        assert compat.EV == oracle.EV and compat.sup_current_state == oracle.state
        names = list(oracle.EV)
        expected = run(oracle, names, oracle.run_step, 200)
        assert run(compat, names, lambda: compat.run_step() or compat.last_events, 200) == expected


def test_registration_as_published(vm, tmp_path):
    """A check on a controllable event is accepted (and, as the published step polls only
    uncontrollable events, never called); registering again replaces action and check."""
    path = tmp_path / "two.yaml"
    path.write_text("num_events: 2\nnum_supervisors: 1\nevents: [ in, out ]\nev_controllable: [ 0, 1 ]\n"
                    "sup_events: [ [ 1, 1 ] ]\nsup_init_state: [ 0 ]\nsup_data_pos: [ 0 ]\n"
                    "sup_data: [ 2, in, 0, 0, out, 0, 0 ]\n")
    for sct in (vm.SCT(str(path)), PublishedStep(str(path), False)):
        calls = []
        sct.add_callback(sct.EV["out"], lambda _d: calls.append("out"), lambda _d: calls.append("check out"), None)
        sct.add_callback(sct.EV["in"], lambda _d: calls.append("first"), lambda _d: True, None)
        sct.add_callback(sct.EV["in"], None, lambda _d: calls.append("check in") or True, None)
        sct.run_step()
        assert calls == ["check in", "out"], type(sct)
        sct.add_callback(sct.EV["in"], lambda _d: calls.append("in"), None, None)     # no check: never occurs
        sct.run_step()
        assert calls == ["check in", "out", "out"]


def _pack(yaml_path, svm_path):
    from swarmvm import api
    api.write_image([str(yaml_path)], str(svm_path))


def test_a_stale_or_missing_image_is_refused(vm, tmp_path, monkeypatch):
    """Without the compiler, SCT("x/supervisor.yaml") reads x/supervisor.svm: refused, with the
    command that fixes it, when missing or packed from other bytes of the YAML file."""
    source = next(p for p in CORPUS if p.endswith("/uav.yaml"))
    yaml_path, svm_path = tmp_path / "supervisor.yaml", tmp_path / "supervisor.svm"
    yaml_path.write_bytes(Path(source).read_bytes())
    monkeypatch.setitem(__import__("sys").modules, "swarmvm.compiler.pipeline", None)     # a robot: no compiler
    fix = "run swarmvm pack %s -o %s" % (yaml_path, svm_path)
    with pytest.raises(FileNotFoundError, match="cannot read table image %s for %s: %s" % (svm_path, yaml_path, fix)):
        vm.SCT(str(yaml_path))
    monkeypatch.undo()
    _pack(yaml_path, svm_path)
    monkeypatch.setitem(__import__("sys").modules, "swarmvm.compiler.pipeline", None)
    assert list(vm.SCT(str(yaml_path)).EV) == PublishedStep(source, False).events
    yaml_path.write_bytes(Path(source).read_bytes() + b"# edited\n")
    with pytest.raises(ValueError, match="%s is stale: it was packed from another version of %s: %s"
                       % (svm_path, yaml_path, fix)):
        vm.SCT(str(yaml_path))


def test_the_packed_image_is_deterministic_and_keeps_the_start(tmp_path):
    """`swarmvm pack` twice gives the same bytes; the image records sup_current_state."""
    from swarmvm.compiler.runtime_files import image_format
    swarmvm_format = image_format()
    path = tmp_path / "supervisor.yaml"
    path.write_text(random_supervisor(4))
    _pack(path, tmp_path / "a.svm")
    _pack(path, tmp_path / "b.svm")
    raw = (tmp_path / "a.svm").read_bytes()
    assert raw == (tmp_path / "b.svm").read_bytes()
    image = swarmvm_format.Image.parse(raw)
    import hashlib
    assert image.source.digest == hashlib.sha256(path.read_bytes()).digest()
    assert image.source.written == sorted(image.source.written, key=lambda n: n.replace("-", "_").removeprefix("EV_"))
