"""A new target is one module, one template folder and one docs page (issue 39, docs/extending.md):
the throwaway toy target (throwaway/) copied alone into a scratch folder and registered through
SWARMVM_TARGET_PATH passes the target-generic checks (target_checks.py), its own naming rule
refuses a model for it alone, its build command builds its output, and ``swarmvm footprint``
recognises its ELF by the record (machine and symbol) and checks it against the record's limits."""

import os
import shutil
from pathlib import Path

import pytest

from conformance.cases import supervisor_yaml
from swarmvm.footprint import measure
from swarmvm.targets import TARGET_PATH, TARGETS, module_from_file
from swarmvm.targets.record import Elf, Target
from target_builds import build_in_place
from target_checks import (NAME, check_docs_page, check_refuses_names_as_the_others, check_renders_deterministically,
                           gen, swarmvm)

THROWAWAY = Path(__file__).resolve().parent / "throwaway"


@pytest.fixture
def toy(tmp_path):
    """(the toy's record, the environment that registers it): its three parts alone in a folder."""
    folder = tmp_path / "toy_target"
    shutil.copytree(THROWAWAY, folder)
    assert sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()) == [
        "docs/toy.md", "targets/toy.py", "templates/toy/Makefile.j2", "templates/toy/main.c.j2"]
    env = dict(os.environ, **{TARGET_PATH: str(folder / "targets")})
    listed = swarmvm("gen", "--help", env=env)
    assert "toy" in listed.stdout and "toy" not in swarmvm("gen", "--help").stdout
    return module_from_file(folder / "targets" / "toy.py").TARGET, env


def test_the_toy_passes_the_target_generic_checks(toy, tmp_path):
    record, env = toy
    assert "toy" not in TARGETS
    check_renders_deterministically(record, tmp_path / "render", env)
    check_refuses_names_as_the_others(record, tmp_path / "names", env)
    check_docs_page(record)


def test_the_toys_own_rule_refuses_a_model_for_it_alone(toy, tmp_path):
    record, env = toy
    model = tmp_path / "m.yaml"
    model.write_text(supervisor_yaml(["toy_go"], [1], [{"toy_go"}], [[[("toy_go", 0)]]]))
    refused = gen(record, tmp_path / "toy", env=env, model=model)
    assert refused.returncode == 2 and refused.stderr == (
        "swarmvm: error: m.yaml: events: event EV_toy_go: target toy: the toy keeps names starting with 'toy'\n")
    assert swarmvm("check", str(model), "--target", "toy", env=env).returncode == 2
    assert swarmvm("gen", str(model), "--target", "c", "-o", str(tmp_path / "c"), env=env).returncode == 0


def test_footprint_recognises_the_toys_elf_and_checks_its_limits(toy, tmp_path):
    record, env = toy
    folder = tmp_path / "toy"
    assert gen(record, folder, "--name", NAME, env=env).returncode == 0
    build_in_place(record, folder, NAME).check_returncode()
    report = swarmvm("footprint", str(folder / ("%s.elf" % NAME)), env=env)
    assert report.returncode == 1
    assert "| toy | %s |" % NAME in report.stdout
    assert "Toy flash <= %d B" % 1000 in report.stdout
    assert "exceeds the Toy's 1000 B" in report.stderr
    # without its record the same ELF is no known target
    unknown = swarmvm("footprint", str(folder / ("%s.elf" % NAME)))
    assert unknown.returncode == 2 and "machine EM_X86_64 is not a known VM target" in unknown.stderr


def test_a_second_target_of_a_machine_is_told_apart_by_a_symbol(monkeypatch):
    """The CapBot asks for no symbol: an ARM image is its own unless another ARM target's record
    names a symbol the image defines; two that ask equally are refused, not guessed."""
    other = Target("other_m4", "a second Cortex-M target", (), THROWAWAY, "", elf=Elf("EM_ARM", symbols=("other_board",)))
    monkeypatch.setitem(TARGETS, "other_m4", other)
    assert measure.recognise("a.elf", "EM_ARM", lambda: {"svm_step", "main"}) == "capbot"
    assert measure.recognise("a.elf", "EM_ARM", lambda: {"svm_step", "other_board"}) == "other_m4"
    twin = Target("twin_m4", "a third", (), THROWAWAY, "", elf=Elf("EM_ARM", symbols=("twin_board",)))
    monkeypatch.setitem(TARGETS, "twin_m4", twin)
    with pytest.raises(measure.FootprintError, match="both targets other_m4 and twin_m4 recognise"):
        measure.recognise("a.elf", "EM_ARM", lambda: {"other_board", "twin_board"})
    with pytest.raises(measure.FootprintError, match="machine EM_Z80 is not a known VM target"):
        measure.recognise("a.elf", "EM_Z80", lambda: set())
