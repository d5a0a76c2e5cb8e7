"""Read a table image (``.svm``) back as the supervisor set it was packed from, so that every verb
that reads a supervisor reads an image too.

The image holds the canonical tables; with its names section, the events' names; with its order
section (packed from a supervisor file), each event's and each state's place in that file; with
its source section, the file's digest, current states and names as written. The set rebuilt
here has all of that back in the file's order and numbering, so that compiling it gives the
image again, byte for byte, and exact mode works from it as from the file. States the file had
but the image dropped (unreachable ones) come back as empty rows, dropped again with the same
warning. An image packed ``--no-names`` has no event names: no verb that names code, callbacks
or script lines after events can use it, and it is refused in one line saying so."""

import os
from fractions import Fraction
from typing import Optional

from ..boundary.errors import InputError, read_input
from ..compiler.model import LocalSupervisor, Supervisors, Transition
from ..compiler.runtime_files import image_format


def _event_order(image_names: list[str], order: Optional[list[int]]) -> list[int]:
    """Canonical event indices in the file's order (canonical order without an order section)."""
    if order is None:
        return list(range(len(image_names)))
    return sorted(range(len(image_names)), key=lambda e: order[e])


def read_svm(path: str, published: bool = False) -> Supervisors:
    """The supervisor set of the image at ``path``; InputError for an image any runtime refuses
    (its own message) or one without names. ``published`` changes nothing: the image already
    holds the names the published VMs read (its source section)."""
    fmt = image_format()
    raw = read_input(path)
    try:
        image = fmt.Image.parse(raw)
    except fmt.ImageError as exc:
        raise InputError(path, "image", str(exc))
    if image.names is None:
        raise InputError(path, "image", "packed with --no-names: it has no event names to read a supervisor by "
                         "(swarmvm check and trace read it; pack the supervisor again without --no-names for the rest)")
    names = list(image.names)
    file_events = _event_order(names, image.order)
    supervisors = []
    for s in range(image.num_supervisors):
        first, count = image.sup_first_state[s], image.sup_num_states[s]
        number = (image.state_order[first:first + count] if image.state_order is not None else list(range(count)))
        rows: list[list[Transition]] = [[] for _ in range(max(number) + 1)]
        for local in range(count):
            g = first + local
            defined, at = image.state_defined[g], image.state_first[g]
            row = []
            for rank, e in enumerate(e for e in range(image.num_events) if defined >> e & 1):
                probability = None
                if image.probs is not None and image.controllable >> e & 1:
                    probability = Fraction(image.probs[at + rank], fmt.Q15_ONE)
                row.append((e, Transition(names[e], number[image.targets[at + rank]], probability)))
            rows[number[local]] = [t for _, t in sorted(row, key=lambda pair: file_events.index(pair[0]))]
        alphabet = frozenset(names[e] for e in range(image.num_events) if image.sup_alphabet[s] >> e & 1)
        supervisors.append(LocalSupervisor(alphabet=alphabet, initial=number[0], states=rows))
    events = [names[e] for e in file_events]
    spec = Supervisors(
        source=os.path.basename(path), events=events,
        controllable={names[e]: bool(image.controllable >> e & 1) for e in range(image.num_events)},
        public={names[e]: bool(image.public >> e & 1) for e in range(image.num_events)},
        supervisors=supervisors, size_bytes=len(raw), probabilistic=image.probs is not None,
        file_order=image.order is not None)
    if image.source is not None:
        spec.digest = image.source.digest
        spec.written = [image.source.written[e] for e in file_events]
        spec.current = [image.state_order[image.sup_first_state[s] + start] if image.state_order is not None else start
                        for s, start in enumerate(image.source.start)]
    return spec
