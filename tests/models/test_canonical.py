"""Canonical form: re-exports that permute events and states compile to the same bytes, states
are numbered breadth-first, unreachable states are dropped with a warning, and generation is
byte-identical from run to run with no absolute path in the output."""

import random
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm.targets import TARGETS

CORPUS = Path(__file__).parent.parent / "corpus"
SUPERVISORS = sorted(CORPUS.glob("*/*.yaml"))


def reexport(path, out, rng, old_spelling):
    """Write the same supervisors with events and every supervisor's states permuted, in the
    old (``[ a,b ]``, ev_shared) or new (leading blank line, ``[ a, b ]``, ev_public) spelling."""
    doc = yaml.safe_load(Path(path).read_text())
    n = doc["num_events"]
    order = list(range(n))
    rng.shuffle(order)                       # order[new] = old
    events = [doc["events"][i] for i in order]
    data, positions, inits, prob_pos, prob = [], [], [], [], []
    old_pos = doc["sup_data_pos"] + [len(doc["sup_data"])]
    ctrl = doc["ev_controllable"]
    old_prob = doc.get("sup_data_prob")
    old_prob_pos = doc.get("sup_data_prob_pos")
    for s in range(doc["num_supervisors"]):
        rows, pos = [], old_pos[s]
        while pos < old_pos[s + 1]:
            k = doc["sup_data"][pos]
            rows.append([(doc["sup_data"][pos + 1 + 3 * j], doc["sup_data"][pos + 2 + 3 * j] * 256
                          + doc["sup_data"][pos + 3 + 3 * j]) for j in range(k)])
            pos += 1 + 3 * k
        probs = []
        if old_prob is not None:
            p = old_prob_pos[s]
            for row in rows:
                k = old_prob[p]
                probs.append(old_prob[p + 1:p + 1 + k])
                p += 1 + k
        perm = list(range(len(rows)))
        rng.shuffle(perm)                    # perm[old] = new
        inverse = {new: old for old, new in enumerate(perm)}
        positions.append(len(data))
        prob_pos.append(len(prob))
        for new in range(len(rows)):
            row = rows[inverse[new]]
            shuffled = list(range(len(row)))
            rng.shuffle(shuffled)
            data.append(len(row))
            for j in shuffled:
                event, target = row[j]
                data += [event, perm[target] // 256, perm[target] % 256]
            if old_prob is not None:
                cont = [j for j in range(len(row)) if ctrl[doc["events"].index(row[j][0])]]
                weights = dict(zip(cont, probs[inverse[new]]))
                kept = [j for j in shuffled if j in weights]
                prob += [len(kept)] + [weights[j] for j in kept]
        inits.append(perm[doc["sup_init_state"][s]])
    sep = "," if old_spelling else ", "

    def flat(values):
        return "[ " + sep.join(str(v) for v in values) + " ]"

    lines = ["" if not old_spelling else None, "num_events: %d" % n, "num_supervisors: %d" % doc["num_supervisors"],
             "events: " + flat(events)]
    public = doc.get("ev_public", doc.get("ev_shared"))
    if public is not None:
        lines.append(("ev_shared: " if old_spelling else "ev_public: ") + flat([public[i] for i in order]))
    lines += ["ev_controllable: " + flat([ctrl[i] for i in order]),
              "sup_events: [ " + sep.join(flat([row[i] for i in order]) for row in doc["sup_events"]) + " ]",
              "sup_init_state: " + flat(inits), "sup_current_state: " + flat(inits),
              "sup_data_pos: " + flat(positions), "sup_data: " + flat(data)]
    if old_prob is not None:
        lines += ["sup_data_prob_pos: " + flat(prob_pos), "sup_data_prob: " + flat(prob)]
    Path(out).write_text("\n".join(line for line in lines if line is not None) + "\n")


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.name)
def test_permuted_reexports_compile_to_identical_images(path, tmp_path):
    original = compile_inputs([str(path)]).image
    for trial in range(4):
        out = tmp_path / ("re%d.yaml" % trial)
        reexport(path, out, random.Random(trial), old_spelling=trial % 2 == 0)
        assert compile_inputs([str(out)]).image == original


def test_states_are_numbered_breadth_first_in_event_order(tmp_path):
    src = tmp_path / "bfs.yaml"
    # File states: 0 -b-> 2, 0 -a-> 3, 3 -a-> 1, initial 0. BFS by name: 0, then a->3, b->2, then 3's a->1.
    src.write_text("num_events: 2\nnum_supervisors: 1\nevents: [ EV_b, EV_a ]\nev_controllable: [ 1, 1 ]\n"
                   "sup_events: [ [1, 1] ]\nsup_init_state: [ 0 ]\nsup_data_pos: [ 0 ]\n"
                   "sup_data: [ 2, EV_b, 0, 2, EV_a, 0, 3, 0, 0, 1, EV_a, 0, 1 ]\n")
    model = compile_inputs([str(src)]).model
    assert model.events == ("a", "b")
    assert model.supervisors[0].states == (((0, 1, None), (1, 2, None)), ((0, 3, None),), (), ())


def test_unreachable_states_are_dropped_with_a_warning(tmp_path):
    src = tmp_path / "unreach.yaml"
    src.write_text("num_events: 1\nnum_supervisors: 1\nevents: [ EV_a ]\nev_controllable: [ 1 ]\n"
                   "sup_events: [ [1] ]\nsup_init_state: [ 1 ]\nsup_data_pos: [ 0 ]\n"
                   "sup_data: [ 1, EV_a, 0, 1, 1, EV_a, 0, 1 ]\n")
    compiled = compile_inputs([str(src)])
    assert len(compiled.model.supervisors[0].states) == 1
    assert compiled.model.warnings == ("unreach.yaml: supervisor 0: 1 unreachable state(s) dropped (states 0)",)
    result = CliRunner().invoke(main, ["pack", str(src), "-o", str(tmp_path / "u.svm")])
    assert result.exit_code == 0
    assert "swarmvm: warning: unreach.yaml: supervisor 0: 1 unreachable state(s) dropped" in result.stderr


def test_source_automata_and_compiled_supervisor_give_the_same_image():
    xml = [str(CORPUS / "automata" / ("energy_worker_Sloc%d.xml" % i)) for i in range(1, 5)]
    assert compile_inputs(xml).image == compile_inputs([str(CORPUS / "openswarm" / "energy_worker.yaml")]).image


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_generation_is_byte_identical_and_has_no_absolute_paths(target, tmp_path):
    outputs = []
    for run in ("a", "b"):
        out = tmp_path / run
        result = CliRunner().invoke(main, ["gen", str(CORPUS / "openswarm" / "network_worker.yaml"),
                                           "--target", target, "-o", str(out)])
        assert result.exit_code == 0, result.stderr
        outputs.append({p.relative_to(out): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()})
    assert outputs[0] == outputs[1] and outputs[0]
    for content in outputs[0].values():
        assert str(tmp_path).encode() not in content and str(CORPUS).encode() not in content
