"""Write a supervisor's tables in the published form, for benchmarks/published_form/published_vm.c.

    python benchmarks/published_form/tables.py SUPERVISOR.yaml DIR [NAME]

writes ``DIR/NAME.h`` (``#include <stdlib.h>``, the ``EV_x`` defines, NUM_EVENTS,
NUM_SUPERVISORS and the SCT_* prototypes, as the published CapBot header) and
``DIR/NAME_tables.c`` (that header included, then the six arrays inside ``#if FN_SUP``), NAME
being ``model`` unless given. The text is tests/nadzoru_c_form.py's, the test side's one writer
of the published form, so the benchmark and the tests build the same tables; events keep the
file's order (the published numbering), which is what the published VM polls and draws in.

``write``'s ``order`` numbers the events otherwise (the same supervisor, its events renamed by
position only): benchmarks/flash_vs_published.py numbers them in the order swarmvm polls and
lists them, so that both VMs apply simultaneous inputs alike and take the same transitions."""

import sys
from pathlib import Path
from typing import Any, Optional

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))

import nadzoru_c_form  # noqa: E402  (the tests' module, found through the path above)

PROTOTYPES = """
void SCT_init(void);
void SCT_reset(void);
void SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data);
void SCT_run_step(void);
"""


def renumbered(doc: dict[str, Any], order: list[str]) -> dict[str, Any]:
    """``doc`` with its events numbered as ``order`` lists them (each of its events once): the
    per-event arrays and each supervisor's alphabet row follow; sup_data names its events, so
    it stays as it is."""
    events = list(doc["events"])
    if sorted(order) != sorted(events):
        raise ValueError("the new order %r is not a permutation of the events %r" % (order, events))
    at = [events.index(name) for name in order]
    out = dict(doc, events=list(order), sup_events=[[row[i] for i in at] for row in doc["sup_events"]])
    for key in ("ev_controllable", *nadzoru_c_form.FLAGS):
        if key in doc:
            out[key] = [doc[key][i] for i in at]
    return out


def write(supervisor: Path, folder: Path, name: str = "model", order: Optional[list[str]] = None) -> tuple[Path, Path]:
    """The header and the tables file of ``supervisor`` under ``folder``; ``order``: the event
    names (``EV_x``, as the file spells them) in the numbering to write, if not the file's."""
    doc = nadzoru_c_form.read_yaml(supervisor)
    if order is not None:
        doc = renumbered(doc, order)
    folder.mkdir(parents=True, exist_ok=True)
    header, source = folder / (name + ".h"), folder / (name + "_tables.c")
    header.write_text("#include <stdlib.h>\n\n" + nadzoru_c_form.defines(doc) + PROTOTYPES, encoding="utf-8")
    source.write_text('#include "%s"\n' % header.name + nadzoru_c_form.tables(doc), encoding="utf-8")
    return header, source


def main(argv: list[str]) -> int:
    if len(argv) not in (2, 3):
        print("usage: tables.py SUPERVISOR.yaml DIR [NAME]", file=sys.stderr)
        return 2
    write(Path(argv[0]), Path(argv[1]), argv[2] if len(argv) == 3 else "model")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
