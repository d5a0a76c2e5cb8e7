"""Measurements live in benchmarks and docs pages, not in code comments (issue 28, point 5).

A comment saying a choice "saves about 4 % of a step" or "takes under a second" goes stale the
day the code or the machine changes, and nothing reruns it: the figure belongs on the docs page
that owns it (docs/footprint.md, docs/limits.md, ...), or in the benchmark that reports it, and
the comment keeps the reason and names the page. This test reads every comment of the source
folders (Python ``#`` comments, C and C++ ``/* */`` and ``//``, the templates' comments in the
language they render, Jinja's ``{# #}``) and fails on a measurement-looking phrase that
ALLOWED does not explain. Hardware specifications (a Kilobot tick is 32.8 ms) are facts, not
measurements: the patterns look for what a measurement says (a share of a step, a speed ratio,
what a change cost or saved, how long the project's own work took, a date, a commit), so a
specification rarely matches, and one that does is listed with its source."""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

from imports import ROOT

FOLDERS = ("generator", "runtime_c", "runtime_cpp", "runtime_py", "studies", "templates", "firmware")
C_LIKE = (".c", ".h", ".cpp", ".hpp", ".ino")
HASH_COMMENTED = ("Makefile", ".txt", ".cmake", ".conf", ".yaml", ".yml", ".mk", ".flags", ".argos")

_NUMBER = r"\d[\d,]*(?:\.\d+)?(?:\s?[-–]\s?\d[\d,]*(?:\.\d+)?)?"      # 4, 1.01-1.07, 3,284-3,984
PATTERNS = {
    "a share of a step or a run": re.compile(
        _NUMBER + r"\s?%\s(?:of\b|off\b|more\b|fewer\b|less\b|faster\b|slower\b|smaller\b|larger\b)"),
    "a speed or size ratio": re.compile(r"(?<![\w.])" + _NUMBER + r"(?:x|×)(?![\w-])"),
    "what a change cost or saved": re.compile(
        r"\b(?:cost|costs|saved|saves|saving|grew|shrank)\s(?:only\s|about\s|up\sto\s)?" + _NUMBER
        + r"\s?(?:B|kB|KB|bytes|cycles|instructions|%)(?![\w])"),
    "a measurement named as one": re.compile(
        r"\b(?:[Mm]easured|[Bb]enchmarked|[Pp]rofiled|[Tt]imed)\s(?:on|at|there|with|here)\b|\(measured\b"),
    "how long the project's own work took": re.compile(
        r"\b(?:takes?|took|runs? in|finishes in)\s(?:about\s|under\s|over\s|less than\s)?(?:" + _NUMBER
        + r"\s?(?:ms|µs|us|s|seconds?|minutes?)\b|a second\b)"),
    "a build's size against a limit": re.compile(
        r"(?<![\w.])" + _NUMBER + r"\s?(?:B|kB|KB|bytes)\sof\s(?:its\s|the\s)?\d"),
    "a date": re.compile(r"\b20[2-9]\d-[01]\d(?:-[0-3]\d)?\b|\b(?:in|as of|since|until)\s20[2-9]\d\b"),
    "a commit": re.compile(r"(?<![\w./-])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}(?![\w./-])"),
}

# {(file, the matched text): why it is not a measurement}. Keep it exact: an entry that no
# longer matches fails too.
ALLOWED: dict[tuple[str, str], str] = {
}


def _python_comments(text: str) -> list[tuple[int, str]]:
    tokens = tokenize.generate_tokens(io.StringIO(text).readline)
    return [(token.start[0], token.string) for token in tokens if token.type == tokenize.COMMENT]


_C_COMMENT = re.compile(r"/\*.*?\*/|(?<![:\"'\w])//[^\n]*", re.S)
_HASH_COMMENT = re.compile(r"(?m)^[ \t]*#(?![{%])[^\n]*|(?<=\s)#\s[^\n]*")
_JINJA_COMMENT = re.compile(r"\{#.*?#\}", re.S)


def _matches_with_lines(text: str, pattern: re.Pattern[str]) -> list[tuple[int, str]]:
    return [(text.count("\n", 0, m.start()) + 1, m.group(0)) for m in pattern.finditer(text)]


def comments(path: Path) -> list[tuple[int, str]]:
    """(line, text) of every comment of ``path``, by the language it is (a template's: the
    language it renders, after its own Jinja comments)."""
    text = path.read_text(encoding="utf-8")
    found = []
    name = path.name
    if name.endswith(".j2"):
        found += _matches_with_lines(text, _JINJA_COMMENT)
        name = name[:-3]
    if name.endswith(".py"):
        if path.name.endswith(".j2"):          # a Python template is not Python until rendered
            return found + _matches_with_lines(text, _HASH_COMMENT)
        return found + _python_comments(text)
    if name.endswith(C_LIKE):
        return found + _matches_with_lines(text, _C_COMMENT)
    if name.endswith(HASH_COMMENTED) or name == "Makefile":
        return found + _matches_with_lines(text, _HASH_COMMENT)
    return found


def source_files() -> list[Path]:
    suffixes = (".py", ".j2", *C_LIKE, *HASH_COMMENTED)
    return sorted(path for folder in FOLDERS for path in (ROOT / folder).rglob("*")
                  if path.is_file() and (path.name.endswith(suffixes) or path.name == "Makefile"))


def measurements(files: list[Path], root: Path = ROOT) -> dict[tuple[str, str], list[str]]:
    """{(file, matched text): ["line N: what it looks like", ...]} over the files' comments."""
    found: dict[tuple[str, str], list[str]] = {}
    for path in files:
        for line, comment in comments(path):
            for kind, pattern in PATTERNS.items():
                for match in pattern.finditer(comment):
                    where = "line %d: %s" % (line + comment.count("\n", 0, match.start()), kind)
                    found.setdefault((path.relative_to(root).as_posix(), match.group(0)), []).append(where)
    return found


def test_no_comment_carries_a_measurement():
    found = measurements(source_files())
    unexplained = {key: where for key, where in found.items() if key not in ALLOWED}
    stale = sorted(key for key in ALLOWED if key not in found)
    assert not unexplained and not stale, (
        "measurements in comments (move the figure to the docs page that owns it, keep the reason "
        "and name the page; or add a hardware fact to ALLOWED saying why): %r; ALLOWED entries that no "
        "longer match: %r" % (unexplained, stale))


def test_each_pattern_finds_the_comment_it_is_for(tmp_path):
    """The checker can fail: one comment of each kind, in each comment syntax; code and strings
    are not comments."""
    samples = {
        "a.c": "/* the table shortens a step by 4 % of its cycles */\nint x; // 1.01-1.07x the baseline's\n",
        "b.py": "x = 1  # a second call cost 330-390 B of flash\ny = '# 5 % of nothing'\n",
        "c.h": "#define A 1 /* Measured on the Kilobot core at -O3 */\n",
        "d.py": "# 20,000 states take under a second\n# network_worker: 28,788 B of 28,672\n",
        "e.cpp": "// as of 2026, see commit e4f6e67\nconst char *u = \"http://x/2026-01-01\";\n",
        "Makefile.j2": "{# 3 % fewer cycles #}\n# network_worker took 12 s\nCFLAGS = -O3 {{ x }}\n",
    }
    for name, text in samples.items():
        (tmp_path / name).write_text(text)
    found = measurements(sorted(tmp_path / name for name in samples), tmp_path)
    assert found == {
        ("a.c", "4 % of"): ["line 1: a share of a step or a run"],
        ("a.c", "1.01-1.07x"): ["line 2: a speed or size ratio"],
        ("b.py", "cost 330-390 B"): ["line 1: what a change cost or saved"],
        ("c.h", "Measured on"): ["line 1: a measurement named as one"],
        ("d.py", "take under a second"): ["line 1: how long the project's own work took"],
        ("d.py", "28,788 B of 2"): ["line 2: a build's size against a limit"],
        ("e.cpp", "as of 2026"): ["line 1: a date"],
        ("e.cpp", "e4f6e67"): ["line 1: a commit"],
        ("Makefile.j2", "3 % fewer"): ["line 1: a share of a step or a run"],
        ("Makefile.j2", "took 12 s"): ["line 2: how long the project's own work took"],
    }
