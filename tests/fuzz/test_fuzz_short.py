"""The short fuzzing run of ``make test`` (CI): every fuzzer for a few seconds from its seed
corpus, about a minute in all; ``make fuzz`` is the long run (docs/fuzzing.md).

A fuzzer passes when it found nothing (no input raised anything but the project's own error,
none hung or ran out of memory, no sanitizer report) and really ran: at least its seeds and,
for the fast ones, a number of mutated inputs too, counted from libFuzzer's own report."""

import pytest

from fuzz import campaign

pytestmark = pytest.mark.slow

SECONDS = {campaign.CODEGEN: 10, campaign.C_RUNTIME: 5, campaign.C_RUNTIME_EXACT: 3}
READER_SECONDS = 3
# Inputs each must at least have run (libFuzzer's count includes the seeds): its seeds and some
# mutated inputs: far fewer than even a loaded machine runs in the time given.
MIN_MUTATIONS = {campaign.CODEGEN: 1, campaign.C_RUNTIME: 500, campaign.C_RUNTIME_EXACT: 500}
READER_MIN_MUTATIONS = 20


@pytest.mark.parametrize("fuzzer", campaign.FUZZERS)
def test_fuzzer_runs_and_finds_nothing(fuzzer, tmp_path):
    result = campaign.run(fuzzer, SECONDS.get(fuzzer, READER_SECONDS), tmp_path)
    tail = result.log.read_text(errors="replace")[-4000:]
    assert not result.findings and result.status == 0, "%s\n%s" % (result.summary(), tail)
    wanted = len(campaign.seeds(fuzzer)) + MIN_MUTATIONS.get(fuzzer, READER_MIN_MUTATIONS)
    assert result.runs >= wanted, "%s: fewer than %d runs\n%s" % (result.summary(), wanted, tail)
