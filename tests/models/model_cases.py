"""Shared helpers of the model tests: corpus paths, the CLI, small automata written as
libFAUDES .gen text, and libFAUDES' language of a set's conjunction (the oracle)."""

import os
import shutil
from pathlib import Path

import faudes
import pytest
from click.testing import CliRunner

from swarmvm.cli.commands import main
from swarmvm.models.faudes_bridge import system_from_model

CORPUS = Path(__file__).resolve().parent.parent / "corpus"
SYNTHESIS = CORPUS / "synthesis" / "energy_worker"
ENERGY_WORKER = CORPUS / "openswarm" / "energy_worker.yaml"
SUPERVISORS = sorted((CORPUS / "openswarm").glob("*.yaml")) + sorted((CORPUS / "nadzoru2").glob("*.yaml"))


def run(*args):
    """``swarmvm ARGS`` in-process; the click Result (exit_code, stdout, stderr)."""
    return CliRunner().invoke(main, [str(a) for a in args])


def gen_text(transitions, controllable=(), initial="q0", marked=None):
    """A libFAUDES .gen generator from 'source event target' lines; every state is marked
    unless ``marked`` lists some."""
    triples = [t.split() for t in transitions]
    states = sorted({t[0] for t in triples} | {t[2] for t in triples} | {initial})
    events = sorted({t[1] for t in triples} | set(controllable))
    alphabet = " ".join(e + (" +C+" if e in controllable else "") for e in events)
    return ("<Generator>\n<Alphabet> %s </Alphabet>\n<States> %s </States>\n<TransRel>\n%s\n</TransRel>\n"
            "<InitStates> %s </InitStates>\n<MarkedStates> %s </MarkedStates>\n</Generator>\n" % (
                alphabet, " ".join(states), "\n".join(transitions), initial,
                " ".join(states if marked is None else marked)))


def conjunction(model):
    """libFAUDES' product of a canonical model's local supervisors (closed languages)."""
    systems = [system_from_model(model, s) for s in range(len(model.supervisors))]
    product = systems[0]
    for system in systems[1:]:
        product = faudes.Parallel(product, system)
    return product


def need_tools(*tools, package):
    """Skip, saying how to get them, when ``tools`` are missing on a user's machine; in CI
    (CI=true) never skip: the test then fails, as a missing tool there is a defect."""
    missing = [t for t in tools if shutil.which(t) is None]
    if missing and not os.environ.get("CI"):
        pytest.skip("needs %s: apt-get install %s" % (", ".join(missing), package))
