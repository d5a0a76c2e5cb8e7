"""libFAUDES as an independent oracle: the language of every local supervisor the compiler
builds (read back from the table image) equals the language libFAUDES builds from the source
automaton, read here straight from the XML; and from the compiled energy_worker.yaml."""

from pathlib import Path
import xml.etree.ElementTree as ET

import faudes
import pytest

from swarmvm.pipeline import compile_inputs

AUTOMATA = Path(__file__).parent.parent / "corpus" / "automata"
XML = sorted(AUTOMATA.glob("*.xml"))


def faudes_from_xml(path):
    """A libFAUDES generator from Nadzoru 2 XML, every state marked (closed language)."""
    data = ET.parse(path).getroot().find("data")
    g = faudes.Generator()
    names = {e.get("id"): "ev_" + e.get("name") for e in data.findall("event")}
    for name in names.values():
        g.InsEvent(name)
    for s in data.findall("state"):
        label = "s" + s.get("id")
        g.InsMarkedState(label)
        if s.get("initial").strip() == "True":
            g.SetInitState(label)
    for t in data.findall("transition"):
        g.SetTransition("s" + t.get("source"), names[t.get("event")], "s" + t.get("target"))
    return g


def faudes_from_image(vm, image, sup):
    """A libFAUDES generator for supervisor ``sup`` of a table image."""
    image = vm.Image.parse(image)
    g = faudes.Generator()
    for e in range(image.num_events):
        if image.sup_alphabet[sup] >> e & 1:
            g.InsEvent("ev_" + image.names[e])
    first = image.sup_first_state[sup]
    for q in range(image.sup_num_states[sup]):
        g.InsMarkedState("q%d" % q)
    g.SetInitState("q%d" % image.sup_initial[sup])
    for q in range(image.sup_num_states[sup]):
        defined = image.state_defined[first + q]
        events = [e for e in range(image.num_events) if defined >> e & 1]
        for rank, e in enumerate(events):
            target = image.targets[image.state_first[first + q] + rank]
            g.SetTransition("q%d" % q, "ev_" + image.names[e], "q%d" % target)
    return g


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
