"""What the Kilobot target (templates/kilobot/) needs computed and checked before rendering.

A Kilobot message carries 9 bytes: the application sends a public event's message name
(generator/compiler/naming.py) as its payload, cut to 9 characters, so two messages that agree on those
characters are refused before anything is written."""

from ..compiler.naming import event_names, kilobot_messages


def prepare(compiled):
    """Template values of the Kilobot target: ``messages`` (event index -> its message name, for
    public events) and ``wires`` (the distinct message names, in event order)."""
    events = event_names(compiled.model)
    wires = kilobot_messages(compiled.model, events)
    return dict(messages={e.index: e.message for e in events if e.message is not None}, wires=wires)
