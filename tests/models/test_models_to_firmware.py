"""The README's models-to-firmware path: synth -> gen -> make, from the energy worker's
plants and specifications to a running C program whose table image is byte for byte the
one compiled from the published supervisor.yaml."""

import subprocess

from models.model_cases import ENERGY_WORKER, SYNTHESIS, need_tools, run
from swarmvm.compiler.pipeline import compile_inputs


def test_synthesised_tables_are_the_published_ones_byte_for_byte(tmp_path):
    out = tmp_path / "energy_worker.yaml"
    assert run("synth", "--script", SYNTHESIS / "script.lua", *sorted(SYNTHESIS.glob("[GE]?.nza")), "-o", out).exit_code == 0
    assert compile_inputs([str(out)]).image == compile_inputs([str(ENERGY_WORKER)]).image


def test_three_commands_from_models_to_a_running_program(tmp_path):
    need_tools("make", "cc", package="build-essential")
    model = tmp_path / "worker.yaml"
    assert run("synth", "--script", SYNTHESIS / "script.txt", *sorted(SYNTHESIS.glob("[GE]?.xml")), "-o", model).exit_code == 0
    assert run("gen", model, "--target", "c", "-o", tmp_path / "c").exit_code == 0
    subprocess.run(["make", "-s", "CFLAGS=-std=c99 -Wall -Werror -O2 -DSVM_STEPS=200"], cwd=tmp_path / "c", check=True,
                   capture_output=True)
    assert subprocess.run([str(tmp_path / "c" / "worker")], timeout=10).returncode == 0
