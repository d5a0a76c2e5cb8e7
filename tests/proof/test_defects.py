"""The real defects Eva found on the C runtime (docs/proof.md, "Real defects") that no other test
catches, each shown on the C code itself: a host build of the runtime run on the inputs that reach
the defect, under UBSan where there is undefined behaviour to see.

The loader's and the stream's defects have their tests beside the code they concern
(tests/learning/test_c_policy.py, the stream's tests); the ones here are arguments of the API, not
bytes of an image or a stream, so no fuzzer reaches them either."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from swarmvm.compiler.pipeline import compile_inputs

ROOT = Path(__file__).resolve().parents[2]
RUNTIME = ROOT / "runtime_c"
FORAGER = ROOT / "examples" / "learning" / "supervisor.yaml"

# svl_policy_init with each baseline shift, then 40 steps with rewards: the shift's answer, and
# (UBSan) any undefined shift the accepted ones reach in floor_shift.
PROBE = r"""
#include <stdio.h>
#include "swarmvm.h"
#include "swarmvm_learn.h"
static const uint8_t image[] = {%(image)s};
static const uint8_t shifts[] = {%(shifts)s};
static uint8_t check(void *data) { (void)data; return 1; }
int main(void)
{
    static int32_t theta[1024];
    unsigned k;
    for (k = 0; k < sizeof shifts; k++) {
        svm_vm_t vm;
        svl_policy_t policy;
        uint8_t e;
        int step, result;
        static svm_binding_t table[SVM_MAX_EVENTS];
        svm_init(&vm);
        if (svm_load(&vm, image, sizeof image) != SVM_OK) {
            return 1;
        }
        svm_set_bindings(&vm, table, SVM_MAX_EVENTS);
        for (e = 0; e < svm_num_events(&vm); e++) {
            (void)svm_bind(&vm, e, 0, svm_is_controllable(&vm, e) ? 0 : check, 0);
        }
        result = svl_policy_init(&policy, &vm, theta, 1024, 256, 6554, shifts[k]);
        printf("%%u %%d\n", shifts[k], result);
        if (result != 0) {
            continue;
        }
        svm_set_chooser(&vm, svl_policy_choose, &policy);
        svm_set_options(&vm, SVM_POLICY_LEARNED, 7u);
        svm_reset(&vm);
        for (step = 0; step < 40; step++) {
            (void)svm_step(&vm);
            (void)svl_policy_reward(&policy, step & 1 ? -(1L << 20) : 1L << 20);
        }
    }
    return 0;
}
"""


def test_a_baseline_shift_of_32_or_more_is_refused_by_svl_policy_init(tmp_path):
    """svl_policy_init took any baseline shift (0..255); svl_policy_reward then shifts by it in
    floor_shift, undefined from 32 on (UBSan: 'shift exponent 40 is too large for 32-bit type').
    Eva reported it in the `learn` configuration, whose harness passes an unknown shift. Now a
    shift of 32 or more is refused (-1), as svl_policy_load refuses it in a saved array; 0..31
    are taken and step without undefined behaviour."""
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.fail("no C compiler on the PATH (make setup)")
    shifts = [0, 4, 31, 32, 40, 255]
    raw = compile_inputs([str(FORAGER)]).image
    (tmp_path / "probe.c").write_text(PROBE % {"image": ", ".join(map(str, raw)),
                                               "shifts": ", ".join(map(str, shifts))})
    exe = tmp_path / "probe"
    subprocess.run([cc, "-std=c99", "-O1", "-fsanitize=undefined", "-fno-sanitize-recover=undefined",
                    "-I", str(RUNTIME), str(tmp_path / "probe.c"), str(RUNTIME / "swarmvm.c"),
                    str(RUNTIME / "swarmvm_learn.c"), "-o", str(exe), "-lm"], check=True)
    run = subprocess.run([str(exe)], capture_output=True, text=True)
    assert run.returncode == 0 and "runtime error" not in run.stderr, run.stderr
    answers = dict(line.split() for line in run.stdout.splitlines())
    assert answers == {"0": "0", "4": "0", "31": "0", "32": "-1", "40": "-1", "255": "-1"}


def test_the_store_reads_a_record_length_without_a_signed_shift_where_int_has_16_bits(tmp_path):
    """swarmvm_store.c's read16 shifted a medium byte promoted to int by 8 before the cast to
    uint16_t: on AVR's 16-bit int, a high byte of 0x80 or more overflowed (C99 6.5.7p4), for any
    slot whose length or sequence field has such a byte (a record of 32 KB or more, a sequence
    number past 2^15, or any corrupted slot the load reads). The host's 32-bit int hides it, and
    no sanitizer runs on AVR, so this asks Eva, as `make prove` does: its `store` configuration
    (x86_16) reported `(int)tmp_0 << 8 <= 32767` in read16 before the cast moved before the shift."""
    from proof import prove

    if prove.frama_c() is None and os.environ.get("CI") != "true":
        pytest.skip("frama-c not found: scripts/setup.sh installs frama-c-base (apt-get install frama-c-base)")
    run = prove.analyse(prove.BY_NAME["store"], tmp_path)
    assert not run.error, run.error
    assert [a for a in run.alarms if a[2] == "read16"] == []
