"""Each format number is defined once: the compiler and its templates import it, never retype it.

The image format's limits and fixed-point one live in runtime_py/swarmvm_format.py, the
Kilobot's message length in swarmvm.targets.kilobot; a retyped copy would silently disagree the day one
changes. This test reads the compiler's source (generator/, with ``ast``: integer literals and
strings other than docstrings, which only explain, for the large numbers) and the templates
(every Jinja expression, and the text around them for the large numbers) for the values of those numbers, and fails on
any use not in ALLOWED, which says why each one is not the format's number. Values small enough
to be everyday numbers (8 bits, 16-bit halves, 1 and 2 bytes) are not looked for."""

import ast
import re
from pathlib import Path

from swarmvm.compiler import naming
from swarmvm.compiler.runtime_files import TEMPLATES, image_format, python_vm
from swarmvm.targets import kilobot

F = image_format()
GENERATOR = Path(naming.__file__).resolve().parents[1]     # generator/, the package swarmvm

# {value: the definitions it is the value of}: the numbers a retyped copy would show as.
WATCHED = {}
for name, value in [("MAX_EVENTS", F.MAX_EVENTS), ("MAX_SUPERVISORS", F.MAX_SUPERVISORS),
                    ("MAX_NAME_LENGTH", F.MAX_NAME_LENGTH), ("MAX_STATES", F.MAX_STATES),
                    ("MAX_TRANSITIONS", F.MAX_TRANSITIONS), ("MAX_IMAGE_SIZE", F.MAX_IMAGE_SIZE),
                    ("Q15_ONE", F.Q15_ONE), ("STREAM_MAX_CHUNKS", F.STREAM_MAX_CHUNKS),
                    ("the states a STATE_WIDTHS width numbers", 1 << 8 * F.STATE_WIDTHS[0]),
                    ("the states a STATE_WIDTHS width numbers", 1 << 8 * F.STATE_WIDTHS[-1]),
                    ("the VM's seed for seed 0", python_vm().XorShift32(0).state),
                    ("kilobot.KILOBOT_MESSAGE_BYTES", kilobot.KILOBOT_MESSAGE_BYTES)]:
    WATCHED.setdefault(value, []).append(name)
# Values also looked for in the compiler's strings and a template's text outside Jinja (smaller
# ones are everyday numbers there: [0-9] in a pattern, a comment's "9 characters").
LARGE = {value for value in WATCHED if value > kilobot.KILOBOT_MESSAGE_BYTES}

# {(file, value): (uses, why none of them is the format's number)}. A file listed here may use
# the value that many times: one more use fails, and so does one fewer (keep this list exact).
ALLOWED = {
    ("compiler/naming.py", 255): (1, "FILE_NAME_BYTES: file systems' limit on a file name"),
    ("targets/kilobot.py", 9): (1, "KILOBOT_MESSAGE_BYTES itself: the payload of kilolib's message_t"),
    ("compiler/naming.py", 65535): (1, "message_code folds FNV-1a to 16 bits (ARGoS range-and-bearing codes)"),
    ("targets/kilobot.py", 65535): (2, "uid_seed: kilolib's kilo_uid is 16 bits, the seed its two halves"),
    ("readers/supervisor_yaml.py", 255): (2, "Nadzoru's sup_data writes a target as two bytes, hi and lo"),
    ("readers/supervisor_yaml.py", 256): (2, "Nadzoru's sup_data writes a target as two bytes, hi and lo"),
    ("models/export.py", 255): (1, "writing Nadzoru's sup_data: a target as two bytes, hi and lo"),
    ("boundary/escape.py", 256): (1, "the \\x escape holds one byte (a language's string escapes)"),
    ("boundary/escape.py", 65536): (1, "the \\u escape holds 16 bits (a language's string escapes)"),
    ("readers/lua_literal.py", 255): (1, "Lua's decimal escape \\ddd holds one byte"),
    ("footprint/qemu_gdb.py", 256): (1, "the GDB remote protocol's checksum is the byte sum modulo 256"),
    ("footprint/cycles.py", 256): (1, "kilolib's Timer0 compare match: 256 counts a tick"),
    ("footprint/kilobot_board/__init__.py", 256): (1, "kilolib's Timer0 compare match: 256 counts a tick"),
    ("boundary/errors.py", 9): (1, "ascii_int's default: 9 digits always fit an int without a big-number parse"),
}

JINJA = re.compile(r"\{\{.*?\}\}|\{%.*?%\}", re.S)
INTEGER = re.compile(r"(?<![\w.])(0[xX][0-9a-fA-F]+|[0-9]+)(?![\w.])")


def _integers(text):
    return [int(token, 16) if token[1:2] in "xX" else int(token) for token in INTEGER.findall(text)]


def _python_uses(source):
    """The watched values among a module's integer literals, and the large ones written in its
    strings (docstrings aside)."""
    tree = ast.parse(source)
    docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                  if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                  and node.body and isinstance(node.body[0], ast.Expr)
                  and isinstance(node.body[0].value, ast.Constant)}
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and type(node.value) is int and node.value in WATCHED:
            yield node.value
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings:
            yield from (value for value in _integers(node.value) if value in LARGE)


def _template_uses(text):
    """The watched values in a template's Jinja expressions, and the large ones in its text."""
    for expression in JINJA.findall(text):
        yield from (value for value in _integers(expression) if value in WATCHED)
    yield from (value for value in _integers(JINJA.sub(" ", text)) if value in LARGE)


def uses():
    """{(file, value): count} of every watched value in generator/ and the templates."""
    found = {}
    files = [(path.relative_to(GENERATOR).as_posix(), _python_uses(path.read_text(encoding="utf-8")))
             for path in sorted(GENERATOR.rglob("*.py"))]
    files += [("templates/" + path, _template_uses(text)) for path, text in _templates(TEMPLATES)]
    for name, values in files:
        for value in values:
            found[name, value] = found.get((name, value), 0) + 1
    return found


def _templates(folder, prefix=""):
    for entry in sorted(folder.iterdir(), key=lambda e: e.name):
        if entry.is_dir():
            yield from _templates(entry, prefix + entry.name + "/")
        elif entry.name.endswith(".j2"):
            yield prefix + entry.name, entry.read_text(encoding="utf-8")


def test_no_format_number_is_retyped():
    found = uses()
    unexplained = {key: "%d use(s) of %s" % (count, " or ".join(WATCHED[key[1]]))
                   for key, count in found.items() if ALLOWED.get(key, (0,))[0] != count}
    stale = {key: why for key, (count, why) in ALLOWED.items() if found.get(key, 0) != count}
    assert not unexplained and not stale, (
        "retyped format numbers (import them from swarmvm_format / swarmvm.targets.kilobot, or add the use to ALLOWED "
        "saying why it is another number): %r; ALLOWED entries that no longer match: %r" % (unexplained, stale))


def test_the_scan_finds_a_retyped_number():
    """The scan sees each kind of retyping: a limit in code, in a string, and in a template."""
    assert list(_python_uses("n = read(high=%d)" % F.MAX_EVENTS)) == [F.MAX_EVENTS]
    assert list(_python_uses("W = re.compile(r'[a-z]{1,%d}')" % F.MAX_NAME_LENGTH)) == [F.MAX_NAME_LENGTH]
    assert list(_python_uses('"""A docstring may say %d."""' % F.Q15_ONE)) == []
    assert list(_template_uses("{{ m[:%d] }}" % kilobot.KILOBOT_MESSAGE_BYTES)) == [kilobot.KILOBOT_MESSAGE_BYTES]
    assert list(_template_uses("#define ONE %d\n" % F.Q15_ONE)) == [F.Q15_ONE]
