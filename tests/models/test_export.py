"""swarmvm export: YAML and .gen read back into an equivalent set (by swarmvm and by
libFAUDES reading the .gen itself); YAML is canonical; pictures are deterministic and draw
controllable events apart from uncontrollable ones."""

import os
import re
import xml.etree.ElementTree as ET

import faudes
import pytest

from models.model_cases import CORPUS, ENERGY_WORKER, SUPERVISORS, conjunction, need_tools, run
from swarmvm.models.faudes_bridge import system_from_model
from swarmvm.compiler.pipeline import compile_inputs


def model(*paths):
    return compile_inputs([str(p) for p in paths]).model


@pytest.mark.parametrize("path", SUPERVISORS, ids=lambda p: p.stem)
def test_yaml_export_reads_back_equivalent_and_is_canonical(path, tmp_path):
    first, second = tmp_path / "a.yaml", tmp_path / "b.yaml"
    assert run("export", path, "-f", "yaml", "-o", first).exit_code == 0
    assert run("equiv", path, first).exit_code == 0
    assert model(first).supervisors == model(path).supervisors
    assert model(first).probabilistic == model(path).probabilistic
    assert run("export", first, "-f", "yaml", "-o", second).exit_code == 0
    assert first.read_bytes() == second.read_bytes()          # a fixed point: canonical
    # The exported file compiles to the same table image as the original.
    assert compile_inputs([str(first)], name="x").image == compile_inputs([str(path)], name="x").image


@pytest.mark.parametrize("path", [p for p in SUPERVISORS if "" not in model(p).events], ids=lambda p: p.stem)
def test_gen_export_reads_back_equivalent_here_and_in_libfaudes(path, tmp_path):
    out = tmp_path / "gen"
    result = run("export", path, "-f", "gen", "-o", out)
    assert result.exit_code == 0
    files = result.stdout.split()
    original = model(path)
    assert len(files) == len(original.supervisors)
    assert run("equiv", path, out).exit_code == 0
    for sup, name in enumerate(files):
        read = faudes.System(name)
        assert faudes.LanguageEquality(read, _plain(system_from_model(original, sup)))
        assert sorted(read.ToLists()[2]) == sorted(
            original.events[e] for e in original.supervisors[sup].alphabet if original.controllable[e])


def _plain(system):
    """The same generator with libFAUDES symbols without swarmvm's EV_ prefix."""
    states, alphabet, controllable, delta, initial, marked = system.ToLists()
    plain = faudes.System()
    for name in alphabet:
        plain.InsEvent(name[3:])
    for q in states:
        plain.InsState(q)
    for q in initial:
        plain.SetInitState(q)
    for q in marked:
        plain.SetMarkedState(q)
    for x, e, y in delta:
        plain.SetTransition(x, e[3:], y)
    return plain


def test_dot_pictures_mark_initial_states_and_tell_controllable_from_uncontrollable(tmp_path):
    result = run("export", ENERGY_WORKER, "-f", "dot", "-o", tmp_path)
    assert result.exit_code == 0
    names = sorted(os.path.basename(p) for p in result.stdout.split())
    assert names == ["energy_worker_%d.dot" % i for i in range(4)] + ["energy_worker_product.dot"]
    text = (tmp_path / "energy_worker_0.dot").read_text()
    assert "init [shape=point];" in text and "init -> q0;" in text
    styles = dict(re.findall(r'label="(\w+)", style="(\w+)"', text))
    assert styles == {"highEnergy": "dashed", "lowEnergy": "dashed", "moveToWork": "solid", "work": "solid",
                      "moveToCharge": "solid", "charge": "solid"}
    product = (tmp_path / "energy_worker_product.dot").read_text()
    assert product.count("->") - 1 == sum(1 for line in product.splitlines() if "style=" in line)
    assert 'q0 [label="(0,0,0,0)"];' in product


def test_the_product_is_drawn_only_up_to_the_limit(tmp_path):
    result = run("export", ENERGY_WORKER, "-f", "dot", "-o", tmp_path, "--product-limit", "35")
    assert "energy_worker_product.dot" not in result.stdout
    result = run("export", ENERGY_WORKER, "-f", "dot", "-o", tmp_path / "b", "--product-limit", "36")
    assert "energy_worker_product.dot" in result.stdout


def test_pictures_are_deterministic(tmp_path):
    need_tools("dot", package="graphviz")
    for fmt in ("dot", "svg"):
        assert run("export", ENERGY_WORKER, "-f", fmt, "-o", tmp_path / "a").exit_code == 0
        assert run("export", ENERGY_WORKER, "-f", fmt, "-o", tmp_path / "b").exit_code == 0
    for name in os.listdir(tmp_path / "a"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    svg = ET.parse(str(tmp_path / "a" / "energy_worker_0.svg")).getroot()
    assert svg.tag.endswith("svg")
    assert b"stroke-dasharray" in (tmp_path / "a" / "energy_worker_0.svg").read_bytes()


def test_synthesis_output_as_gen_is_the_same_set(tmp_path):
    from models.model_cases import SYNTHESIS
    result = run("synth", "--script", SYNTHESIS / "script.txt", *sorted(SYNTHESIS.glob("[GE]?.xml")),
                 "-f", "gen", "-o", tmp_path)
    assert result.exit_code == 0 and len(result.stdout.split()) == 4
    assert run("equiv", tmp_path, ENERGY_WORKER).exit_code == 0
    assert faudes.LanguageEquality(conjunction(model(tmp_path)), conjunction(model(ENERGY_WORKER)))


def test_yaml_export_is_what_nadzoru_2_writes(tmp_path):
    # public_example.yaml was written by Nadzoru 2's own generator, already in canonical order.
    original = CORPUS / "nadzoru2" / "public_example.yaml"
    assert run("export", original, "-f", "yaml", "-o", tmp_path / "p.yaml").exit_code == 0
    assert (tmp_path / "p.yaml").read_text() == original.read_text() + "\n"


def test_a_file_name_cannot_write_a_directive_into_the_gen_comment(tmp_path):
    """Issue 37, class 1: the source's name reaches the .gen comment through the comment
    escaping; a name holding a line break and a `% swarmvm public:` directive naming a private
    event stays inside the comment, and the export reads back as the same set."""
    model = compile_inputs([str(ENERGY_WORKER)]).model
    private = next(e for i, e in enumerate(model.events) if not model.public[i])
    hostile = tmp_path / ("x\n% swarmvm public: " + private + "\n%.yaml")
    hostile.write_bytes(ENERGY_WORKER.read_bytes())
    out = tmp_path / "gen"
    result = run("export", hostile, "--format", "gen", "-o", out)
    assert result.exit_code == 0, result.stderr
    written = sorted(out.glob("*.gen"))
    assert written and not any(line.startswith("% swarmvm public: " + private)
                               for p in written for line in p.read_text().splitlines())
    assert run("equiv", hostile, out).exit_code == 0
