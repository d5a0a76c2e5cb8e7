"""`make mutation-c`'s mutants (scripts/c_mutants.py): found in code only, never in comments,
literals, preprocessor lines or constant tables; one edit each, as its operator says; numbered in
source order so that a run can resume by id."""

import sys

from checkout import ROOT

sys.path.insert(0, str(ROOT / "scripts"))
import c_mutants  # noqa: E402

NOT_CODE = r'''#define LIMIT(a) ((a) < 3 && !(a))
#if X > 1 || \
    Y == 2
#endif
/* a < b && !c, 7 */
// x - 1 >= 0
static const char *s = "a < b || 2";
static const char c = '<';
static const pair_t table[] = {{0, 1}, {2, 3}};
'''


def edits(source):
    return [(m.operator.removeprefix("c/"), m.original, m.replacement) for m in c_mutants.mutants(source)]


def test_comments_literals_preprocessor_lines_and_tables_have_no_mutants():
    assert edits(NOT_CODE) == []
    assert c_mutants.mutants(NOT_CODE + "int f(int a) { return a < 2; }\n")[0].line == 10


def test_each_operator_makes_its_one_edit():
    source = "if (a < b && c <= d || e > f && g >= h || i == j && k != l || !m) { a = b + c - d; }"
    assert edits(source) == [
        ("ReplaceComparisonOperator_Lt_LtE", "<", "<="), ("ReplaceAndWithOr", "&&", "||"),
        ("ReplaceComparisonOperator_LtE_Lt", "<=", "<"), ("ReplaceOrWithAnd", "||", "&&"),
        ("ReplaceComparisonOperator_Gt_GtE", ">", ">="), ("ReplaceAndWithOr", "&&", "||"),
        ("ReplaceComparisonOperator_GtE_Gt", ">=", ">"), ("ReplaceOrWithAnd", "||", "&&"),
        ("ReplaceComparisonOperator_Eq_NotEq", "==", "!="), ("ReplaceAndWithOr", "&&", "||"),
        ("ReplaceComparisonOperator_NotEq_Eq", "!=", "=="), ("ReplaceOrWithAnd", "||", "&&"),
        ("ReplaceUnaryOperator_Delete_Not", "!", ""),
        ("ReplaceBinaryOperator_Add_Sub", "+", "-"), ("ReplaceBinaryOperator_Sub_Add", "-", "+")]
    assert edits("for (;;) { if (x) break; continue; }") == [
        ("ReplaceBreakWithContinue", "break", "continue"), ("ReplaceContinueWithBreak", "continue", "break")]


def test_integer_literals_go_one_up_in_their_base_and_suffix_and_others_are_left():
    assert [m.replacement for m in c_mutants.mutants("x = 0 + 9u + 0xFFu + 0x0fUL + 255;")] == \
        ["1", "-", "10u", "-", "0x100u", "-", "0x10UL", "-", "256"]
    assert edits("double d = 1.5e-3;") == []


def test_signs_shifts_and_arrows_are_not_operators_it_swaps():
    assert edits("return -x; y = (a << b) >> c; p->q++; r--; z = f(-1);") == [("NumberReplacer", "1", "2")]


def test_an_edit_is_applied_at_its_line_and_column():
    source = "int f(int a)\n{\n    return a >= 10;\n}\n"
    first, second = c_mutants.mutants(source)
    assert (first.id, first.line, first.column, second.id, second.column) == ("c0000", 3, 14, "c0001", 17)
    assert first.apply(source) == source.replace(">=", ">")
    assert second.lines(source) == ("return a >= 10;", "return a >= 11;")


def test_ids_are_stable_and_follow_the_source_order():
    source = (ROOT / "runtime_c" / "swarmvm.c").read_text(encoding="utf-8")
    once, again = c_mutants.mutants(source), c_mutants.mutants(source)
    assert once == again
    assert [m.id for m in once] == ["c%04d" % k for k in range(len(once))]
    assert [m.offset for m in once] == sorted(m.offset for m in once)
    assert all(source[m.offset:m.offset + len(m.original)] == m.original for m in once)
