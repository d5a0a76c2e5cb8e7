"""An image of one supervisor of one state, written section by section with the format's own
writer (swarmvm_format.assemble): the checksum is right and only what a test makes odd is. The
image reader's and the VM's kill tests (tests/mutation_kills/) build their images with it."""

import struct
from typing import Optional, Sequence

from swarmvm.compiler.runtime_files import image_format

F = image_format()


def one_state_image(events: int = 3, controllable: int = 0b001, alphabet: Optional[int] = None,
                    defined: Optional[int] = None, targets: Optional[Sequence[int]] = None, first_successor: int = 0,
                    transitions: Optional[int] = None, probs: Optional[Sequence[int]] = None,
                    sections: Optional[dict[str, bytes]] = None) -> bytes:
    """``alphabet`` and ``defined`` (the state's events) default to every event; ``targets`` to a
    self-loop (target 0) per defined event, from ``first_successor``; ``transitions`` (the
    header's count) to as many as targets; ``probs`` one Q15 value per transition; ``sections``
    added as they are (names, order, source). Masks are (events + 7) // 8 bytes."""
    every = (1 << events) - 1
    alphabet = every if alphabet is None else alphabet
    defined = every if defined is None else defined
    targets = [0] * bin(defined).count("1") if targets is None else targets
    width = (events + 7) // 8

    def mask(value: int) -> bytes:
        return value.to_bytes(width, "little")

    body = {"controllable": mask(controllable), "public": mask(0),
            "supervisors": mask(alphabet) + F.SUPERVISOR_RECORD.pack(0, 1, 0),
            "states": mask(defined) + F.STATE_RECORD.pack(first_successor), "targets": bytes(targets),
            **(sections or {})}
    if probs is not None:
        body["probs"] = struct.pack("<%dH" % len(probs), *probs)
    return F.assemble(events, 1, 1, len(targets) if transitions is None else transitions, 1, body)
