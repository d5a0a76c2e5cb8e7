"""WP's part of `make prove` (docs/proof.md, "WP"): the functions of the image checks whose
properties WP proves, in units, and which configurations can share a unit's proof.

Eva cannot prove check_indices' walk (its reads are in bounds by relations between header fields
that intervals do not keep); WP proves it from the function's contract, and svm_validate's other
helpers' contracts, with CVC4 and Z3 through Why3. WP's result depends only on the code it is run
on, not on the harness, so a unit runs on `swarmvm.c` alone, and once for every configuration
whose build of the unit is the same code: `unit_key` is a digest of Frama-C's own printing of the
unit's functions, the functions they call, the structures they use and the file's other
declarations, with the ABI, so that two builds share a proof only where their WP inputs cannot
differ (the configurations differ mostly in limits, which check_indices does not read)."""

from __future__ import annotations

import hashlib
import re
from dataclasses import dataclass, replace


@dataclass(frozen=True)
class Unit:
    """A set of functions WP proves every property of (with their run-time errors when `rte`:
    functions Eva takes by their contracts), and functions of which it proves only the assigns
    clauses (`assigns_only`: their other properties are Eva's)."""

    name: str
    functions: tuple[str, ...]
    rte: bool
    assigns_only: tuple[str, ...] = ()
    # WP's -wp-prop selection of the functions' properties ("" for all of them)
    props: str = ""
    # whether this unit proves the file's lemmas (`-wp-prop @lemma`; the report does not list them)
    lemmas: bool = False


# check_indices and what it calls: Eva takes check_indices by its contract where the images are
# unknown (Config.unknown_images), so WP proves their bodies free of run-time errors.
CHECKS = Unit("checks", ("check_indices", "mask_beyond", "beyond_events", "rd_copy", "rd_raw", "le16", "popcount8"),
              rte=True, lemmas=True)
# svm_validate and its other helpers: Eva proves their bodies free of run-time errors and the
# preconditions of the calls they make; WP proves their contracts, their loops' assigns, and the
# preconditions check_indices is called with (its `validated:` clauses), which Eva cannot.
VALIDATE = Unit("validate", ("validate", "trailer_end", "section_end", "crc16", "crc_byte", "rd16_raw", "name_char",
                             "_crc_ccitt_update"), rte=False, assigns_only=("name_repeats",),
                props="-@requires,+validated")
UNITS = (CHECKS, VALIDATE)
UNIT_FUNCTIONS = frozenset(f for u in UNITS for f in u.functions)

_WORD = re.compile(r"[A-Za-z_]\w*")
# The first word of a global annotation (a contract is any other `/*@ ... */` before a declaration)
_GLOBAL_ANNOTATION = re.compile(r"(lemma|axiomatic|predicate|logic|inductive|axiom|type|global|ghost)\b")


@dataclass(frozen=True)
class Global:
    """One top-level declaration of Frama-C's printed code, with the ACSL comment before it, and
    the names it declares (none for a lemma: every lemma is part of every unit)."""

    kind: str       # "function", "annotation" (lemmas) or "declaration" (types, enums, variables)
    names: frozenset[str]
    text: str


def _without_attributes(text: str) -> str:
    """`text` without its `__attribute__((...))` groups (Frama-C prints GCC's attributes in the
    declarator: `static uint8_t __attribute__((__cold__)) ( __attribute__((__noinline__)) rd_raw)`)."""
    while (at := text.find("__attribute__")) >= 0:
        depth, end = 0, at + len("__attribute__")
        while end < len(text):
            depth += {"(": 1, ")": -1}.get(text[end], 0)
            end += 1
            if depth == 0 and text[end - 1] == ")":
                break
        text = text[:at] + text[end:]
    return text


def _declared(text: str) -> tuple[str, frozenset[str]]:
    """The kind and names of the declaration `text` (without its contract)."""
    words = _WORD.findall(text)
    head = " ".join(line.strip() for line in text.splitlines()).split("{", 1)[0]
    head = _without_attributes(head).strip().rstrip(";").strip()
    if words[:1] == ["enum"] and "(" not in head:        # its tag and constants
        return "declaration", frozenset(words[1:])
    if words[:1] in (["struct"], ["union"]) and "(" not in head and ("{" in text or len(_WORD.findall(head)) == 2):
        return "declaration", frozenset(words[1:2])     # a definition, or a declaration of the tag
    if words[:1] == ["typedef"]:    # `typedef T name;` or `typedef R (*name)(...);`
        pointer = re.search(r"\(\s*\*\s*(\w+)\s*\)", head)
        return "declaration", frozenset([pointer.group(1) if pointer else _WORD.findall(head)[-1]])
    if not head.endswith(")"):      # a variable: its name is before its size or initialiser
        return "declaration", frozenset(_WORD.findall(re.split(r"[\[=]", head, maxsplit=1)[0])[-1:])
    depth, at = 0, len(head)
    while at > 0:       # back to the "(" that opens the parameter list
        at -= 1
        depth += {")": 1, "(": -1}.get(head[at], 0)
        if depth == 0:
            break
    return "function", frozenset(_WORD.findall(head[:at])[-1:])


def split_globals(printed: str) -> list[Global]:
    """Frama-C's `-print` output as its top-level declarations, in order: a declaration goes from a
    line at column 0 to the `;` or closing brace that brings the braces back to 0, and takes the
    `/*@ ... */` comment (a contract) just before it; a global annotation stands alone."""
    result: list[Global] = []
    lines = printed.splitlines()
    comment: list[str] = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("/*@"):
            block = [line]
            while "*/" not in block[-1] and i + 1 < len(lines):
                i += 1
                block.append(lines[i])
            if _GLOBAL_ANNOTATION.match(" ".join(block)[3:].lstrip()):
                result.append(Global("annotation", frozenset(), "\n".join(block)))
            else:
                comment += block
            i += 1
            continue
        if not line or line[0] in " \t" or line.startswith(("/*", "#")):
            i += 1
            continue
        body, depth = [line], line.count("{") - line.count("}")
        while not (depth == 0 and body[-1].rstrip().endswith((";", "}"))) and i + 1 < len(lines):
            i += 1
            body.append(lines[i])
            depth += lines[i].count("{") - lines[i].count("}")
        kind, names = _declared("\n".join(body))
        result.append(Global(kind, names, "\n".join(comment + body)))
        comment = []
        i += 1
    return result


def unit_input(unit: Unit, printed: str) -> str:
    """What WP reads of `printed` when it proves `unit`: the unit's functions, every lemma, and,
    until nothing more is named, each declaration a chosen text names (the functions they call,
    their types, structures, enums and tables). Names of the harness or of other runtime files
    that the unit does not use (svm_vm_t, which holds the limits) are left out, so that builds
    that differ only there share the unit's proof."""
    globals_ = split_globals(printed)
    wanted = set(unit.functions + unit.assigns_only)
    chosen = {n for n, g in enumerate(globals_)
              if g.kind == "annotation" or (g.kind == "function" and g.names & wanted)}
    while True:
        words = {w for n in chosen for w in _WORD.findall(globals_[n].text)}
        more = {n for n, g in enumerate(globals_) if n not in chosen and g.names & words}
        if not more:
            break
        chosen |= more
    return "\n".join(globals_[n].text for n in sorted(chosen))


def unit_key(unit: Unit, machdep: str, printed: str) -> str:
    """The digest two configurations share exactly when WP's inputs for `unit` are the same."""
    return hashlib.sha256("\0".join((unit.name, ",".join(unit.functions), ",".join(unit.assigns_only), machdep,
                                      unit_input(unit, printed))).encode()).hexdigest()[:16]


def within(unit: Unit, reached: set[str]) -> Unit:
    """`unit` with only the functions a configuration runs (`reached`): WP proves nothing of the
    others there (the store's configurations link svm_validate but never call it)."""
    return replace(unit, functions=tuple(f for f in unit.functions if f in reached),
                   assigns_only=tuple(f for f in unit.assigns_only if f in reached))


def present(unit: Unit, printed: str) -> tuple[list[str], list[str]]:
    """The unit's functions (all properties; assigns only) that `printed` defines."""
    defined = {name for g in split_globals(printed) if g.kind == "function" and g.text.rstrip().endswith("}")
               for name in g.names}
    return [f for f in unit.functions if f in defined], [f for f in unit.assigns_only if f in defined]


def lemmas(printed: str) -> list[str]:
    """The names of the lemmas `printed` declares."""
    return re.findall(r"^\s*lemma (\w+):", printed, re.M)
