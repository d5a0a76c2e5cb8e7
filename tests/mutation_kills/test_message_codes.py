"""Message codes and message collisions (generator/compiler/naming.py, generator/targets/argos.py
and kilobot.py), pinned by known answers: mutants of the FNV-1a constants, of the 16-bit fold and of the ARGoS and Kilobot collision checks survived
every other test (issue 29, docs/mutation.md)."""

import pytest

from swarmvm.boundary.errors import InputError
from swarmvm.compiler.model import Model
from swarmvm.compiler.naming import event_names, fnv1a, message_code
from swarmvm.targets.argos import argos_names
from swarmvm.targets.kilobot import KILOBOT_MESSAGE_BYTES, kilobot_messages


def public_model(*events):
    """Controllable public events (each its own message), no supervisors: all the naming rules read."""
    return Model(source="m.yaml", events=tuple(events), controllable=(1,) * len(events), public=(1,) * len(events),
                 supervisors=(), probabilistic=False)


def test_fnv1a_gives_the_published_test_vectors():
    """FNV-1a 32's reference values (offset basis 2166136261, prime 16777619)."""
    assert fnv1a("") == 0x811C9DC5
    assert fnv1a("a") == 0xE40C292C
    assert fnv1a("foobar") == 0xBF9CF968


def test_a_message_code_is_the_fnv1a_folded_to_16_bits_and_never_0():
    assert message_code("a") == 0xE40C ^ 0x292C
    assert message_code("foobar") == 0xBF9C ^ 0xF968
    assert message_code("mndk") == 1        # its fold is 0, "no message" on the wire


def test_argos_refuses_two_messages_with_one_code_and_names_the_code():
    """"mju" and "mps" fold to the same code, 16520."""
    model = public_model("a", "mju", "mps")
    with pytest.raises(InputError) as refused:
        argos_names(model, event_names(model))
    assert str(refused.value) == ("m.yaml: events: event EV_mps: messages 'mju' and 'mps' have the same 16-bit "
                                  "ARGoS code 16520: rename one")


def test_argos_accepts_messages_with_distinct_codes():
    model = public_model("a", "mju", "mpt")
    argos_names(model, event_names(model))


def test_kilobot_messages_collide_on_their_first_9_characters_only():
    """Names that differ in the 9th character are two messages; names that share their first 9
    are one, refused with both events, both names and the 9 characters in the message."""
    assert KILOBOT_MESSAGE_BYTES == 9
    apart = public_model("abcdefgh1", "abcdefgh2")
    assert kilobot_messages(apart, event_names(apart)) == ["abcdefgh1", "abcdefgh2"]
    one = public_model("abcdefghi1", "abcdefghi2")
    with pytest.raises(InputError) as refused:
        kilobot_messages(one, event_names(one))
    assert str(refused.value) == (
        "m.yaml: events: event EV_abcdefghi2: EV_abcdefghi1 and EV_abcdefghi2 use the messages 'abcdefghi1' and "
        "'abcdefghi2', one Kilobot message 'abcdefghi' (a message carries the first 9 characters of the name): "
        "rename one")


def test_kilobot_lists_each_message_once_in_event_order():
    model = Model(source="m.yaml", events=("_go", "go", "stay"), controllable=(0, 1, 0), public=(1, 1, 0),
                  supervisors=(), probabilistic=False)
    assert kilobot_messages(model, event_names(model)) == ["go"]
