"""libFAUDES as an independent oracle: the language of every local supervisor the compiler
builds (read back from the table image) equals the language libFAUDES builds from the source
automaton, read here straight from the XML; and from the compiled energy_worker.yaml."""

from pathlib import Path
import xml.etree.ElementTree as ET

import faudes
import pytest

from swarmvm.models.faudes_bridge import build_system
from swarmvm.compiler.pipeline import compile_inputs

AUTOMATA = Path(__file__).parent.parent / "corpus" / "automata"
XML = sorted(AUTOMATA.glob("*.xml"))


def faudes_from_xml(path):
    """A libFAUDES generator from Nadzoru 2 XML, read here with ElementTree (not swarmvm's
    loader), every state marked (closed language)."""
    data = ET.parse(path).getroot().find("data")
    names = {e.get("id"): e.get("name") for e in data.findall("event")}
    ids = [s.get("id") for s in data.findall("state")]
    initial = next(i for i, s in enumerate(data.findall("state")) if s.get("initial").strip() == "True")
    transitions = [(ids.index(t.get("source")), names[t.get("event")], ids.index(t.get("target")))
                   for t in data.findall("transition")]
    return build_system(((n, False) for n in names.values()), len(ids), initial, None, transitions)


def faudes_from_image(vm, image, sup):
    """A libFAUDES generator for supervisor ``sup`` of a table image, read by the Python VM."""
    image = vm.Image.parse(image)
    events = [(image.names[e], False) for e in range(image.num_events) if image.sup_alphabet[sup] >> e & 1]
    first = image.sup_first_state[sup]
    transitions = []
    for q in range(image.sup_num_states[sup]):
        defined = image.state_defined[first + q]
        for rank, e in enumerate(e for e in range(image.num_events) if defined >> e & 1):
            transitions.append((q, image.names[e], image.targets[image.state_first[first + q] + rank]))
    return build_system(events, image.sup_num_states[sup], image.sup_initial[sup], None, transitions)


@pytest.mark.parametrize("path", XML, ids=lambda p: p.name)
def test_compiled_language_equals_libfaudes_language(vm, path):
    image = compile_inputs([str(path)]).image
    assert faudes.LanguageEquality(faudes_from_image(vm, image, 0), faudes_from_xml(path))


def test_compiled_yaml_supervisors_equal_their_source_automata(vm):
    image = compile_inputs([str(AUTOMATA.parent / "openswarm" / "energy_worker.yaml")]).image
    for sup in range(4):
        source = faudes_from_xml(AUTOMATA / ("energy_worker_Sloc%d.xml" % (sup + 1)))
        assert faudes.LanguageEquality(faudes_from_image(vm, image, sup), source)
    # And the oracle can tell languages apart: supervisor 0 is not supervisor 2.
    assert not faudes.LanguageEquality(faudes_from_image(vm, image, 0), faudes_from_xml(AUTOMATA / "energy_worker_Sloc3.xml"))
