"""docs/semantics.md's table "One step in each runtime" is the runtimes' one map: each numbered
step of "One step" has its row, and each function a cell names is defined in the file the cell
(or its column's head) names. A rename in one runtime, or a step added to the page, fails here
until the table says where it went."""

import re

from checkout import ROOT

PAGE = ROOT / "docs" / "semantics.md"
FILE = re.compile(r"\(`([\w/.]+\.(?:py|c|h|hpp))`\)")


def numbered_steps(page: str) -> list[str]:
    """The numbered steps of the section "One step", as the table's first column writes them:
    ``1. Poll``."""
    section = page.split("\n## One step\n", 1)[1].split("\n## ", 1)[0]
    return ["%s. %s" % found for found in re.findall(r"^(\d+)\. \*\*(.+?)\.\*\*", section, re.M)]


def table_rows(page: str) -> tuple[list[str], list[list[str]]]:
    """(the file named at the head of each runtime's column, the rows as lists of cells)."""
    section = page.split("\n### One step in each runtime\n", 1)[1].split("\n## ", 1)[0]
    lines = [line for line in section.splitlines() if line.startswith("|")]
    cells = [[cell.strip() for cell in line.strip("|").split("|")] for line in lines]
    heads = [FILE.search(head).group(1) for head in cells[0][1:]]
    return heads, cells[2:]


def definitions(path: str, name: str) -> bool:
    """Whether the file at ``path`` defines function ``name`` (a method ``Class.name``: the
    class and the method), in its language's spelling of a definition."""
    text = (ROOT / path).read_text()
    owner, _, name = name.rpartition(".")
    if path.endswith(".py"):
        found = re.search(r"^\s*def %s\(" % re.escape(name), text, re.M) is not None
        return found and (not owner or re.search(r"^class %s\b" % re.escape(owner), text, re.M) is not None)
    # C and C++: the name, its parameter list, then the body (not a call: a call ends in ';' or ')').
    definition = r"(?<![\w.>])%s\s*\((?:[^;{}()]|\([^()]*\))*\)\s*(?:const\s*)?\{" % re.escape(name)
    return re.search(definition, text) is not None


def problems(page: str) -> list[str]:
    """What is wrong with the page's table: steps without a row, functions not where it says."""
    heads, rows = table_rows(page)
    found = []
    firsts = [row[0] for row in rows]
    found += ["step %r has no row" % step for step in numbered_steps(page) if step not in firsts]
    for row in rows:
        for head, cell in zip(heads, row[1:]):
            for entry in cell.split(", "):
                names = re.findall(r"`([\w.]+)`", FILE.sub("", entry))
                where = FILE.search(entry)
                path = where.group(1) if where else head
                if len(names) != 1 or not definitions(path, names[0]):
                    found.append("%s: %r is not a function of %s" % (row[0], entry, path))
    return found


def test_every_step_has_a_row_and_every_named_function_exists():
    assert problems(PAGE.read_text()) == []


def test_the_table_names_the_six_steps_and_four_runtimes():
    heads, rows = table_rows(PAGE.read_text())
    assert len(numbered_steps(PAGE.read_text())) == 6
    assert len(heads) == 4 and all((ROOT / head).is_file() for head in heads)


def test_a_renamed_function_or_a_missing_row_is_reported():
    page = PAGE.read_text()
    renamed = page.replace("| 1. Poll | `_poll` |", "| 1. Poll | `_poll_each` |")
    assert problems(renamed) == ["1. Poll: '`_poll_each`' is not a function of runtime_py/swarmvm_reference.py"]
    dropped = re.sub(r"^\| 4\. Control phase .*\n", "", page, flags=re.M)
    assert problems(dropped) == ["step '4. Control phase' has no row"]
    elsewhere = page.replace("`VM._fire` (`runtime_py/swarmvm_vm.py`)", "`VM._fire` (`runtime_c/swarmvm.c`)")
    assert problems(elsewhere) == ["fire (3 and 6): '`VM._fire` (`runtime_c/swarmvm.c`)' is not a function of "
                                   "runtime_c/swarmvm.c"]
