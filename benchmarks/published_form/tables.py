"""Write a supervisor's tables in the published form, for benchmarks/published_form/published_vm.c.

    python benchmarks/published_form/tables.py SUPERVISOR.yaml DIR [NAME]

writes ``DIR/NAME.h`` (``#include <stdlib.h>``, the ``EV_x`` defines, NUM_EVENTS,
NUM_SUPERVISORS and the SCT_* prototypes, as the published CapBot header) and
``DIR/NAME_tables.c`` (that header included, then the six arrays inside ``#if FN_SUP``), NAME
being ``model`` unless given. The text is tests/nadzoru_c_form.py's, the test side's one writer
of the published form, so the benchmark and the tests build the same tables; events keep the
file's order (the published numbering), which is what the published VM polls and draws in."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))

import nadzoru_c_form  # noqa: E402  (the tests' module, found through the path above)

PROTOTYPES = """
void SCT_init(void);
void SCT_reset(void);
void SCT_add_callback(unsigned char event, void (*clbk)(void *), unsigned char (*ci)(void *), void *data);
void SCT_run_step(void);
"""


def write(supervisor: Path, folder: Path, name: str = "model") -> tuple[Path, Path]:
    """The header and the tables file of ``supervisor`` under ``folder``."""
    doc = nadzoru_c_form.read_yaml(supervisor)
    folder.mkdir(parents=True, exist_ok=True)
    header, source = folder / (name + ".h"), folder / (name + "_tables.c")
    header.write_text("#include <stdlib.h>\n\n" + nadzoru_c_form.defines(doc) + PROTOTYPES, encoding="utf-8")
    source.write_text('#include "%s"\n' % header.name + nadzoru_c_form.tables(doc), encoding="utf-8")
    return header, source


def main(argv: list[str]) -> int:
    if len(argv) not in (2, 3):
        print("usage: tables.py SUPERVISOR.yaml DIR [NAME]", file=sys.stderr)
        return 2
    write(Path(argv[0]), Path(argv[1]), *argv[2:])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
