"""Model names and Kilobot messages (generator/compiler/naming.py) pinned where `make mutation` found them
unpinned (issue 29, docs/mutation.md): the refusals' messages word for word, a message collision
found after an event that sends nothing, and the event names fixed once derived."""

import dataclasses

import pytest

from swarmvm.boundary.errors import InputError
from swarmvm.compiler.model import Model
from swarmvm.compiler.naming import MAX_MODEL_NAME, EventNames, event_names, file_stem, model_identifier
from swarmvm.targets.argos import argos_names
from swarmvm.targets.kilobot import kilobot_messages


@pytest.mark.parametrize("stem,prefix", [("svm_sct", "svm"), ("Kilo_x", "Kilo"), ("SCT_model", "SCT")])
def test_a_runtime_prefix_is_refused_naming_the_prefix_as_the_model_spells_it(stem, prefix):
    """The message names the prefix taken (the part before the first ``_``), not the rest."""
    with pytest.raises(InputError) as refused:
        model_identifier(stem, "f.yaml")
    assert str(refused.value) == ("f.yaml: --name: model name %r collides with the runtime's own %s_* symbols: "
                                  "give another with --name" % (stem, prefix))


def test_an_empty_model_name_is_refused_as_reserved():
    with pytest.raises(InputError) as refused:
        model_identifier("", "f.yaml")
    assert str(refused.value) == "f.yaml: --name: model name '' is reserved in C, C++ or Python: give another with --name"


def test_a_too_long_file_stem_is_refused_with_its_length_and_the_limits():
    assert file_stem("n" * MAX_MODEL_NAME, "f.yaml", "--output") == "n" * MAX_MODEL_NAME
    with pytest.raises(InputError) as refused:
        file_stem("n" * (MAX_MODEL_NAME + 1), "f.yaml", "--output")
    assert str(refused.value) == ("f.yaml: --output: model name of 237 characters: at most 236, so that the "
                                  "generated file names fit 255 bytes: give a shorter one with --output")


def test_a_kilobot_collision_after_a_private_event_is_still_refused():
    """An event that sends no message is skipped, and the events after it are still checked."""
    model = Model(source="m.yaml", events=("a_private", "abcdefghi1", "abcdefghi2"), controllable=(1, 1, 1),
                  public=(0, 1, 1), supervisors=(), probabilistic=False)
    with pytest.raises(InputError, match="^m.yaml: events: event EV_abcdefghi2: EV_abcdefghi1 and EV_abcdefghi2 "):
        kilobot_messages(model, event_names(model))


@pytest.mark.parametrize("events,controllable,named", [(("a__b",), (1,), "EV_a__b"), (("_x__y",), (0,), "EV__x__y")])
def test_argos_refuses_a_callback_holding_a_double_underscore_naming_the_event(events, controllable, named):
    """C++ reserves identifiers with ``__`` (a sent event's callback, and a received one's)."""
    model = Model(source="m.yaml", events=events, controllable=controllable, public=(1,), supervisors=(),
                  probabilistic=False)
    with pytest.raises(InputError) as refused:
        argos_names(model, event_names(model))
    assert str(refused.value) == "m.yaml: events: event %s: C++ reserves identifiers with '__': rename the event" % named


def test_an_events_names_are_fixed_once_derived():
    """Every target reads the same EventNames: none can rename an event for the targets after it."""
    model = Model(source="m.yaml", events=("go",), controllable=(1,), public=(1,), supervisors=(), probabilistic=False)
    names = event_names(model)[0]
    assert isinstance(names, EventNames) and hash(names) == hash(event_names(model)[0])
    with pytest.raises(dataclasses.FrozenInstanceError):
        names.message = "stop"
