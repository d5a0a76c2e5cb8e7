"""What the ARGoS target (templates/argos/) checks before rendering: its own naming rules.

A public event travels on ARGoS's range-and-bearing as a 16-bit code, and the C++ callbacks are
named from the events; both rules are ARGoS's alone (swarmvm.compiler.naming.argos_names), so a model
the other targets generate is refused here for this target only."""

from ..compiler.naming import argos_names, event_names


def prepare(compiled) -> dict:
    """No extra template values; InputError when the model breaks an ARGoS-only rule."""
    argos_names(compiled.model, event_names(compiled.model))
    return {}
