"""The ARGoS target (templates/argos/, docs/robots/argos.md): an e-puck controller in C++17 for
the ARGoS simulator, and its own naming rules.

A public event travels on ARGoS's range-and-bearing as a 16-bit code
(swarmvm.compiler.naming.message_code), and the C++ callbacks are named from the events; both
rules are ARGoS's alone, so a model the other targets generate is refused here for this target only."""

from ..boundary.errors import InputError
from ..compiler.model import Model
from ..compiler.naming import EventNames, event_names
from ..compiler.pipeline import Compiled
from ..compiler.runtime_files import CPP_RUNTIME_HEADERS, RUNTIME_CPP, TEMPLATES
from .record import Readme, Target


def argos_names(model: Model, events: list[EventNames]) -> None:
    """InputError naming the event when its C++ callbacks would hold ``__`` (reserved to the
    implementation in C++, not in C or Python), or when two messages share a 16-bit
    range-and-bearing code."""
    codes: dict[int, str] = {}
    for e in events:
        if "__" in e.stem:
            raise InputError(model.source, "events", "C++ reserves identifiers with '__': rename the event",
                             "event %s" % e.const)
        if e.message is not None and e.code is not None:
            first = codes.setdefault(e.code, e.message)
            if first != e.message:
                raise InputError(model.source, "events", "messages %r and %r have the same 16-bit ARGoS code %d: "
                                 "rename one" % (first, e.message, e.code), "event %s" % e.const)


def rules(compiled: Compiled) -> dict[str, object]:
    """ARGoS's naming rules (:func:`argos_names`); no extra template values."""
    argos_names(compiled.model, event_names(compiled.model))
    return {}


TARGET = Target(
    "argos",
    "ARGoS e-puck controller (C++17): image header, generated CCI_Controller base class, controller skeleton, CMakeLists.txt, example .argos",
    templates=(("argos/image.hpp.j2", "{name}_image.hpp", False),
               ("argos/base.h.j2", "{name}_base.h", False),
               ("argos/controller.h.j2", "{name}_controller.h", True),
               ("argos/controller.cpp.j2", "{name}_controller.cpp", True),
               ("argos/CMakeLists.txt.j2", "CMakeLists.txt", True),
               ("argos/experiment.argos.j2", "{name}.argos", True)),
    template_folder=TEMPLATES / "argos",
    page="robots/argos.md",
    copies=tuple((RUNTIME_CPP / n, n) for n in (*CPP_RUNTIME_HEADERS, "swarmvm_argos.hpp", "swarmvm_argos_controller.hpp",
                                                 "swarmvm_argos_report.hpp", "swarmvm_argos.cmake")),
    rules=rules,
    readme=Readme("argos/readme.md.j2", (
        ("{name}_image.hpp", "the table image as a constexpr array, event constants"),
        ("{name}_base.h", "the generated controller base class: binds every event by name, the public events' "
                          "messages, the private events' methods pure virtual"),
        ("{name}_controller.[ch]*", "your controller, derived from the base: the private events' Check_EVENT and "
                                    "On_EVENT methods"),
        ("CMakeLists.txt", "includes swarmvm_argos.cmake and builds the controller library"),
        ("{name}.argos", "the experiment (arena, robots, the controller's parameters)"),
        ("swarmvm*", "the C++ VM and its ARGoS glue (a copy of swarmvm's runtime), and swarmvm_argos.cmake, which "
                     "finds ARGoS"),
        ("{name}.svm", "the table image"),
        ("README.md", "this file"))))
