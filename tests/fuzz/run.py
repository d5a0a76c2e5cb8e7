"""Run one atheris (coverage-guided, libFuzzer) fuzz target: ``python tests/fuzz/run.py TARGET
[libFuzzer options] [CORPUS_DIR...]``. TARGET is a reader of tests/fuzz/readers.py or
``codegen`` (tests/fuzz/gen_target.py). A finding leaves its input as ``crash-*``,
``timeout-*`` or ``oom-*`` (in the folder -artifact_prefix names) and a non-zero exit status.
tests/fuzz/campaign.py (``make fuzz``, and the short run in ``make test``) calls this with
each target's seed corpus (docs/fuzzing.md)."""

import sys
from pathlib import Path

import atheris

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

# Coverage is traced through swarmvm, the runtime's reader and VM and defusedxml; not through
# PyYAML's pure-Python parser, which traced ran some 30 times slower (the YAML fuzzer then ran
# a few inputs a second).
with atheris.instrument_imports(include=["swarmvm", "swarmvm_format", "swarmvm_vm", "defusedxml", "fuzz"]):
    from fuzz import gen_target, readers
    from swarmvm.compiler.runtime_files import python_vm
    python_vm()

TARGETS = dict(readers.READERS, codegen=gen_target.one_input)


def main(argv: list) -> None:
    if len(argv) < 2 or argv[1] not in TARGETS:
        sys.exit("usage: run.py {%s} [libFuzzer options] [corpus folder...]" % ",".join(TARGETS))
    atheris.Setup([argv[0], *argv[2:]], TARGETS[argv[1]])
    try:
        atheris.Fuzz()
    finally:
        readers.cleanup()


if __name__ == "__main__":
    main(sys.argv)
