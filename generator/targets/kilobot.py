"""The Kilobot target (templates/kilobot/, docs/robots/kilobot.md): a kilolib application for the
ATmega328P, its messages, its limits and how footprint reads its images.

A Kilobot message carries 9 bytes: the application sends a public event's message name
(swarmvm.compiler.naming) as its payload, cut to 9 characters, so two messages that agree on
those characters are refused before anything is written, for this target only."""

from ..boundary.errors import InputError
from ..compiler.model import Model
from ..compiler.naming import EventNames, event_names
from ..compiler.image import pack
from ..compiler.pipeline import Compiled
from ..compiler.runtime_files import TEMPLATES
from .c import file_order
from .record import Elf, Readme, RobotLimits, Target
from .values import C_RUNTIME_GROUPS, c_copies, features, has_public_inputs, headers, minimal_features, sources

KILOBOT_MESSAGE_BYTES = 9     # a kilolib message_t carries 9 bytes of payload
# 32 KB of flash minus the bootloader at 0x7000; 2 KB of SRAM, 1 KB of it left to the stack
LIMITS = RobotLimits("Kilobot", flash=28672, sram=2048, min_stack=1024)
# What the indirect calls of a generated Kilobot program reach (docs/footprint.md, "Stack"): the
# dispatch the Kilobot runtime (runtime_c/swarmvm_kilobot.c) registers with the VM, the setup and
# loop it gives kilolib's kilo_start, and the message callbacks it (or kilolib's defaults) put in
# the pointers kilolib's timer (__vector_14) and comparator (__vector_23) interrupts call.
KILOBOT_INDIRECT = ("svm_step=svm_kilobot_app_dispatch,dispatch", "kilo_start=setup,loop",
                    "__vector_14=message_tx,message_tx_success,message_tx_dummy,message_tx_success_dummy",
                    "__vector_23=on_message,message_rx_dummy")


def kilobot_messages(model: Model, events: list[EventNames]) -> list[str]:
    """The distinct message names of a Kilobot application, in event order; InputError when two
    of them agree on the 9 bytes a Kilobot message carries."""
    seen: dict[str, EventNames] = {}
    for e in events:
        if e.message is None:
            continue
        first = seen.setdefault(e.message[:KILOBOT_MESSAGE_BYTES], e)
        if first.message != e.message:
            raise InputError(model.source, "events", "%s and %s use the messages %r and %r, one Kilobot message %r "
                             "(a message carries the first %d characters of the name): rename one"
                             % (first.const, e.const, first.message, e.message, e.message[:KILOBOT_MESSAGE_BYTES],
                                KILOBOT_MESSAGE_BYTES), "event %s" % e.const)
    return list(dict.fromkeys(e.message for e in events if e.message is not None))


def uid_seed(uid: int) -> int:
    """The seed a Kilobot's VM runs with by default (runtime_c/swarmvm_kilobot.h,
    SVM_KILOBOT_UID_SEED): its kilo_uid in the top 16 bits, the uid's complement in the bottom 16,
    so that a robot's run can be replayed (e.g. ``ReferenceVM(image, seed=uid_seed(uid))``)."""
    uid &= 0xFFFF
    return uid << 16 | (~uid & 0xFFFF)


def rules(compiled: Compiled) -> dict[str, object]:
    """The Kilobot's naming rule, and what it gives the templates: ``messages`` (event index ->
    its message name, for public events) and ``wires`` (the distinct message names, in event order)."""
    events = event_names(compiled.model)
    wires = kilobot_messages(compiled.model, events)
    return dict(messages={e.index: e.message for e in events if e.message is not None}, wires=wires)


def values(compiled: Compiled) -> dict[str, object]:
    """The runtime its Makefile compiles (more with ``STREAM=1`` and ``LEARNED=1``), the features
    of each build (the streaming one matches a received image's events by name), and each public
    event's message payload (event index -> the first KILOBOT_MESSAGE_BYTES characters of its
    message name), and what the minimal flash profile of the generated program leaves out for this
    model (:func:`~swarmvm.targets.values.minimal_features`), with the image it compiles in:
    ``trusted_image``, the image without its names section (the profile of a build that reads no
    name runs it; c/tables.[ch].j2)."""
    probabilistic = compiled.tables.probs is not None
    events = event_names(compiled.model)
    public_inputs = has_public_inputs(compiled.tables)
    return dict(runtime_sources=sources("core", "kilobot"), runtime_headers=headers("core", "kilobot"),
                stream_sources=sources("stream"), learned_sources=sources("learn"),
                features=features(probabilistic, names=False), stream_features=features(probabilistic, names=True),
                public_inputs=public_inputs, minimal_features=minimal_features(public_inputs),
                trusted_image=pack(compiled.tables, compiled.source, names=False),
                payloads={e.index: e.message[:KILOBOT_MESSAGE_BYTES] for e in events if e.message is not None},
                **file_order(compiled))


TARGET = Target(
    "kilobot",
    "Kilobot application (kilolib, ATmega328P): tables in PROGMEM, messages as public events, new images streamed over messages, Makefile, controller skeleton",
    templates=(("c/tables.h.j2", "{name}_tables.h", False),
               ("c/tables.c.j2", "{name}_tables.c", False),
               ("kilobot/dispatch.c.j2", "{name}_dispatch.c", False),
               ("kilobot/app.h.j2", "{name}_app.h", False),
               ("kilobot/app.c.j2", "{name}_app.c", False),
               ("kilobot/main.c.j2", "{name}_main.c", False),
               ("kilobot/Makefile.j2", "Makefile", False),
               ("kilobot/controller.c.j2", "{name}_controller.c", True)),
    template_folder=TEMPLATES / "kilobot",
    page="robots/kilobot.md",
    copies=c_copies(*C_RUNTIME_GROUPS, "stream", "kilobot", "kilobot_eeprom", "learn"),
    rules=rules, values=values,
    build=("make", "-s", "{name}.elf"),     # with KILOLIB=<kilolib's build folder>
    limits=LIMITS,
    elf=Elf("EM_AVR", architecture="avr", emulator="kilobot_board", make_rule="{build}/kilobot/{name}.elf",
            platform_runtime=("swarmvm_kilobot.c",), indirect=KILOBOT_INDIRECT),
    readme=Readme("kilobot/readme.md.j2", (
        ("Makefile", "builds {name}.hex (and {name}.elf) against your kilolib with its flags and this model's VM "
                     "limits; MAIN= builds your own program instead of {name}_main.c"),
        ("{name}_main.c", "the kilolib program: main, setup, loop and kilolib's message callbacks, each calling the "
                          "Kilobot runtime"),
        ("{name}_app.[ch]", "which message carries each public event, the image, dispatch and stream hook of this "
                            "model"),
        ("{name}_tables.[ch]", "the table image in flash (PROGMEM), event constants"),
        ("{name}_dispatch.c", "the dispatch to your callbacks"),
        ("{name}_controller.c", "{name}_on_EVENT (actions: kilolib calls such as set_motors) and {name}_check_EVENT "
                                "for private uncontrollable events; message events are handled by the runtime"),
        ("swarmvm*", "the C VM and the Kilobot runtime (a copy of swarmvm's): the VM, the calls of "
                     "swarmvm_kilobot.h, the Nadzoru-compatible C API, the image stream receiver, the learned policy "
                     "and its EEPROM store"),
        ("{name}.svm", "the table image"),
        ("{name}.footprint.json", "what swarmvm footprint needs to measure {name}.elf (its indirect calls, an event "
                                  "script for --cycles, the table image's digest), beside where make builds it"),
        ("README.md", "this file"))))
