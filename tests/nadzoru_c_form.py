"""Nadzoru's C tables written from a supervisor.yaml, in the published programs' form: the
test side of swarmvm's C tables reader (swarmvm.readers.nadzoru_c), written here from what the
published CapBot and Kilobot programs hold (``#define EV_x n`` and the six initialised arrays,
``unsigned long int`` for states and positions), not from Nadzoru's generator.

Two layouts, as the two programs have them: ``header`` (the defines in ``lib/sct/inc/<name>.h``,
the tables in ``lib/sct/src/<name>.c`` which includes it, as FreeBot's work_and_charge branch)
and ``inline`` (one file, the defines above the tables, as the Kilobot program)."""

from pathlib import Path

import yaml

# The per-event flags some exports add (public events); Nadzoru's C has none, the reader takes them.
FLAGS = ("ev_shared", "ev_public")


def _c_list(value) -> str:
    if isinstance(value, list):
        return "{ " + ",".join(_c_list(v) for v in value) + " }"
    return str(value)


def defines(doc: dict) -> str:
    lines = ["#define NUM_EVENTS %s" % doc["num_events"], "#define NUM_SUPERVISORS %s" % doc["num_supervisors"], ""]
    lines += ["#define %s %d\n" % (name, index) for index, name in enumerate(doc["events"])]
    return "\n".join(lines) + "\n"


def tables(doc: dict) -> str:
    """The arrays, with the types and sizes the published programs declare."""
    e, s = doc["num_events"], doc["num_supervisors"]
    return "\n".join([
        "#if FN_SUP",
        "    const unsigned char     ev_controllable[%s] = %s;" % (e, _c_list(doc["ev_controllable"])),
        "    const unsigned char     sup_events[%s][%s] = %s;" % (s, e, _c_list(doc["sup_events"])),
        "    const unsigned long int sup_init_state[%s]     = %s;" % (s, _c_list(doc["sup_init_state"])),
        "    unsigned long int       sup_current_state[%s]  = %s;" % (s, _c_list(doc.get("sup_current_state",
                                                                                    doc["sup_init_state"]))),
        "    const unsigned long int sup_data_pos[%s] = %s;" % (s, _c_list(doc["sup_data_pos"])),
        "    const unsigned char     sup_data[ %d ] = %s;" % (len(doc["sup_data"]), _c_list(doc["sup_data"])),
        *["    const unsigned char     %s[%s] = %s;" % (key, e, _c_list(doc[key])) for key in FLAGS if key in doc],
        "#endif", ""])


def read_yaml(path: Path) -> dict:
    return yaml.load(path.read_text(encoding="utf-8"), Loader=yaml.BaseLoader)


def write(yaml_path: Path, folder: Path, layout: str, name: str = "sct_model") -> Path:
    """The C form of ``yaml_path`` under ``folder``; the path of the file holding the tables."""
    doc = read_yaml(yaml_path)
    if layout == "header":
        (folder / "lib/sct/inc").mkdir(parents=True, exist_ok=True)
        (folder / "lib/sct/src").mkdir(parents=True, exist_ok=True)
        (folder / "lib/sct/inc" / (name + ".h")).write_text("#include <stdlib.h>\n\n/* Struct's */\n" + defines(doc)
                                                           + "\nvoid SCT_init();\nvoid SCT_run_step();\n")
        source = folder / "lib/sct/src" / (name + ".c")
        source.write_text('#include "%s.h"\n#define FN_AP 1\n#define FN_SUP 1\n\n' % name + tables(doc)
                          + "#if FN_AP\n/* the VM follows */\n#endif\n")
        return source
    source = folder / (name + ".c")
    source.write_text(inline(doc))
    return source


def inline(doc: dict) -> str:
    """One C file holding the defines and the tables, in a program, as the Kilobot program."""
    return ("// a Kilobot program with its supervisor inlined\n#include <kilolib.h>\n#define FN_SUP 1\n"
            + defines(doc) + "/* tables */\n" + tables(doc)
            + "int main(void) { kilo_init(); return sup_data[0] > 1 ? 0 : 1; }\n")
