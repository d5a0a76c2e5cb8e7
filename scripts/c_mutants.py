"""The mutants of a C file (`make mutation-c`, scripts/mutation_c.py, docs/mutation.md): where an
operator, a literal or a jump can be changed, and the source each change gives.

A small tokenizer, not a C parser: it only has to tell code from what is not code (comments,
string and character literals, preprocessor lines, whose macro bodies are left alone) and an
operator from its longer neighbours (`<` from `<<`, `<=` and `->`). Each mutant is one edit of
one token; mutants are numbered in source order, so the same source always gives the same ids and
an interrupted run can resume by id."""

import re
from dataclasses import dataclass

# One token per match, tried in this order: a preprocessor line runs to the end of its last
# backslash-continued line (comments inside it included); punctuators longest first.
TOKEN = re.compile(r"""
    (?P<directive>^[ \t]*\#(?:/\*.*?\*/|\\\n|[^\n])*)
  | (?P<comment>/\*.*?\*/|//[^\n]*)
  | (?P<literal>"(?:\\.|[^"\\\n])*"|'(?:\\.|[^'\\\n])*')
  | (?P<number>\.?\d(?:[eEpP][+-]|[\w.])*)
  | (?P<word>[A-Za-z_]\w*)
  | (?P<punct>\.\.\.|<<=|>>=|->|\+\+|--|<<|>>|<=|>=|==|!=|&&|\|\||[-+*/%&|^]=|[^\s\w])
  | (?P<space>\s+)
""", re.S | re.M | re.X)

# An integer literal the off-by-one operator rewrites: decimal or hexadecimal, any suffix.
INTEGER = re.compile(r"(?P<digits>0[xX][0-9a-fA-F]+|[1-9][0-9]*|0)(?P<suffix>[uUlL]*)")

# Each operator: the token it applies to and what it makes of it (cosmic-ray's names for the
# Python ones, under c/). Comparisons go to their boundary twin or their negation, one each.
SWAPS = {
    "<": ("ReplaceComparisonOperator_Lt_LtE", "<="), "<=": ("ReplaceComparisonOperator_LtE_Lt", "<"),
    ">": ("ReplaceComparisonOperator_Gt_GtE", ">="), ">=": ("ReplaceComparisonOperator_GtE_Gt", ">"),
    "==": ("ReplaceComparisonOperator_Eq_NotEq", "!="), "!=": ("ReplaceComparisonOperator_NotEq_Eq", "=="),
    "&&": ("ReplaceAndWithOr", "||"), "||": ("ReplaceOrWithAnd", "&&"),
    "!": ("ReplaceUnaryOperator_Delete_Not", ""),
    "break": ("ReplaceBreakWithContinue", "continue"), "continue": ("ReplaceContinueWithBreak", "break"),
}
BINARY_SWAPS = {"+": ("ReplaceBinaryOperator_Add_Sub", "-"), "-": ("ReplaceBinaryOperator_Sub_Add", "+")}
# Words after which `+` or `-` is a sign, not an operator (`return -1`, `case -2`).
SIGN_BEFORE = {"return", "case", "sizeof", "else", "do"}


@dataclass(frozen=True)
class Mutant:
    """One edit: ``original`` at ``offset`` (line and column, both from 1) becomes ``replacement``."""

    id: str
    operator: str
    line: int
    column: int
    offset: int
    original: str
    replacement: str

    def apply(self, source: str) -> str:
        return source[:self.offset] + self.replacement + source[self.offset + len(self.original):]

    def lines(self, source: str) -> tuple[str, str]:
        """The mutated line's text before and after the edit, stripped (the report's columns)."""
        start = source.rfind("\n", 0, self.offset) + 1
        end = source.find("\n", self.offset)
        end = len(source) if end < 0 else end
        line = source[start:end]
        cut = self.offset - start
        return line.strip(), (line[:cut] + self.replacement + line[cut + len(self.original):]).strip()


def tokens(source: str) -> list[tuple[str, str, int]]:
    """(kind, text, offset) of each token of ``source`` but blanks."""
    found = []
    pos = 0
    while pos < len(source):
        match = TOKEN.match(source, pos)
        if match is None:       # a character no C token starts with (a stray `\`, `@`): skipped
            pos += 1
            continue
        if match.lastgroup != "space":
            found.append((match.lastgroup or "", match.group(), pos))
        pos = match.end()
    return found


def plus_one(literal: str) -> str | None:
    """An integer literal's value plus one in the same base and suffix; None for other numbers."""
    match = INTEGER.fullmatch(literal)
    if match is None:
        return None
    digits, suffix = match["digits"], match["suffix"]
    if digits[:2].lower() == "0x":
        return digits[:2] + format(int(digits, 16) + 1, "X" if digits[2:].isupper() else "x") + suffix
    return str(int(digits) + 1) + suffix


def mutation(kind: str, text: str, previous: tuple[str, str] | None) -> tuple[str, str] | None:
    """(operator, replacement) for one token, or None when no operator applies to it."""
    if kind == "number":
        bigger = plus_one(text)
        return None if bigger is None else ("NumberReplacer", bigger)
    if kind in ("punct", "word") and text in SWAPS:
        return SWAPS[text]
    if kind == "punct" and text in BINARY_SWAPS and previous is not None:
        before_kind, before = previous
        if before_kind == "number" or before in (")", "]") or (before_kind == "word" and before not in SIGN_BEFORE):
            return BINARY_SWAPS[text]
    return None


def mutants(source: str) -> list[Mutant]:
    """Every mutant of ``source``, in source order, ids c0000, c0001, ...

    The entries of a brace initializer (`= { ... }`: the CRC and popcount tables) are data, not
    code: off by one, each would be a mutant that only an input hitting that entry kills, and
    they would outnumber the code's mutants; they are left out."""
    found: list[Mutant] = []
    previous = None
    table_depth = 0         # braces open since an initializer's `= {`
    for kind, text, offset in tokens(source):
        if kind in ("directive", "comment"):
            continue
        if text == "{" and (table_depth or previous == ("punct", "=")):
            table_depth += 1
        elif text == "}" and table_depth:
            table_depth -= 1
        change = None if table_depth else mutation(kind, text, previous)
        previous = (kind, text)
        if change is None:
            continue
        line = source.count("\n", 0, offset) + 1
        column = offset - (source.rfind("\n", 0, offset) + 1) + 1
        found.append(Mutant("c%04d" % len(found), "c/" + change[0], line, column, offset, text, change[1]))
    return found
