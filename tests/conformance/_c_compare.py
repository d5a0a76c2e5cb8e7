"""Comparison of a C harness run with the reference traces, shared by the host and AVR suites."""

from conformance.cases import reference

SVM_ERR_CRC = 4     # swarmvm.h: the corrupted copy the harness offers must be refused for its CRC


def mismatches(batch, traces, info, passes):
    """Human-readable list of every run whose trace differs from the reference (empty = pass)."""
    problems = []
    if not info["end"]:
        problems.append("the harness output has no @end line (crash or timeout)")
    if info["error"] is not None:
        problems.append("the harness refused the image: code %d" % info["error"])
    if 1 in passes and info["refused"] != SVM_ERR_CRC:
        problems.append("a corrupted image copy gave %r, expected SVM_ERR_CRC" % info["refused"])
    for number, run in enumerate(batch.runs):
        expected = reference(batch, run)
        for p in passes:
            got = traces.get((p, number))
            if got != expected:
                first = next((i for i, (a, b) in enumerate(zip(got or [], expected)) if a != b), None)
                detail = ("missing" if got is None else
                          "step %d: %r != %r" % (first + 1, got[first], expected[first]) if first is not None else
                          "%d lines, expected %d" % (len(got), len(expected)))
                problems.append("%s pass %d run %d %s: %s" % (batch.name, p, number, run, detail))
    return problems
