"""The image writer (generator/compiler/image.py) pinned where `make mutation` found it unpinned (issue 29,
docs/mutation.md): a model without events refused, the names section written unless asked not to,
and the banner digest by known answers."""

import pytest

from swarmvm.boundary.errors import InputError
from swarmvm.compiler.image import digest, pack
from swarmvm.compiler.model import CanonicalSupervisor, Model
from swarmvm.compiler.runtime_files import image_format
from swarmvm.compiler.tables import build_tables


def two_events():
    return Model(source="m.yaml", events=("go", "stop"), controllable=(True, False), public=(False, False),
                 supervisors=(CanonicalSupervisor(frozenset({0, 1}), (((0, 0, None), (1, 0, None)),)),),
                 probabilistic=False)


def test_a_model_without_events_is_refused_and_one_event_is_enough():
    """Automata may declare no events; the format needs one."""
    one_state = (CanonicalSupervisor(frozenset(), ((),)),)
    with pytest.raises(InputError) as refused:
        pack(build_tables(Model("m.yaml", (), (), (), one_state, False)), "m.yaml")
    assert str(refused.value) == "m.yaml: events: no events: a supervisor set needs at least one"
    assert pack(build_tables(Model("m.yaml", ("go",), (True,), (False,), one_state, False)), "m.yaml")


def test_an_image_carries_the_event_names_unless_told_not_to():
    read = image_format().Image.parse
    assert read(pack(build_tables(two_events()), "m.yaml")).names == ["go", "stop"]
    assert read(pack(build_tables(two_events()), "m.yaml", names=False)).names is None


def test_the_digest_is_the_first_16_hex_digits_of_the_sha256():
    """SHA-256 of "" and of "abc" (FIPS 180-2's example), cut to 16 digits."""
    assert digest(b"") == "e3b0c44298fc1c14"
    assert digest(b"abc") == "ba7816bf8f01cfea"
