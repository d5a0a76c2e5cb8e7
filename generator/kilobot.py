"""What the Kilobot target (templates/kilobot/) needs computed and checked before rendering.

A Kilobot message carries 9 bytes: the application sends a public event's name as its payload
(EV_x sends "x", and a received "x" makes EV__x occur), cut to 9 characters. Two public events
whose message names agree on those 9 characters would be one message on the wire, so the
model is refused before anything is written."""

from .errors import InputError

MESSAGE_BYTES = 9


def message_name(name, controllable):
    """The name an event's message carries: an uncontrollable public "_x" receives "x"."""
    return name[1:] if not controllable and name.startswith("_") else name


def prepare(compiled):
    """Template values of the Kilobot target: ``messages`` (event index -> the name its message
    carries, for public events). Raises InputError naming the first two public events whose messages collide."""
    model = compiled.model
    messages, seen = {}, {}
    for i, name in enumerate(model.events):
        if not model.public[i]:
            continue
        wire = message_name(name, model.controllable[i])
        first = seen.setdefault(wire[:MESSAGE_BYTES], (wire, name))
        if first[0] != wire:
            raise InputError(model.source, "events", "public events EV_%s and EV_%s send the same Kilobot message %r "
                             "(a message carries the first %d characters of the name): rename one"
                             % (first[1], name, wire[:MESSAGE_BYTES], MESSAGE_BYTES))
        messages[i] = wire
    return dict(messages=messages)
