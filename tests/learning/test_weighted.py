"""Policy `weighted` (docs/semantics.md): the frequencies of the VM's choices follow the Q15
products of the transition probabilities, and two bugs of the published probabilistic VMs are
absent: probabilities parsed as integers (every weight 0, so every choice uniform: 50/50) and
an 8-bit random number divided by RAND_MAX (always 0, so always the first event: 100/0)."""

from pathlib import Path

import pytest

from swarmvm.compiler.pipeline import compile_inputs
from swarmvm_vm import VM, Image

HERE = Path(__file__).resolve().parent
PROBABILISTIC = HERE.parent / "corpus" / "nadzoru2" / "probabilistic_example.yaml"
TWO_DICE = HERE / "data" / "two_dice.yaml"
CHI2_P001 = {1: 10.83, 2: 13.82}     # chi-square critical values at p = 0.001


def frequencies(vm, steps):
    counts = {}
    for _ in range(steps):
        for event in vm.step():
            if vm.image.controllable >> event & 1:
                name = vm.image.names[event]
                counts[name] = counts.get(name, 0) + 1
    return counts


def chi_square(counts, expected_share):
    total = sum(counts.values())
    return sum((counts.get(name, 0) - total * share) ** 2 / (total * share)
               for name, share in expected_share.items())


def probabilistic_vm(seed):
    image = Image.parse(compile_inputs([str(PROBABILISTIC)]).image)
    vm = VM(image, policy="weighted", seed=seed)
    # u brings the supervisor back after `a`: it occurs exactly when the VM is in a's target,
    # so every step ends with one weighted choice between a (0.3) and b (0.7).
    back = vm.moves[0][0][image.event_index("a")]
    vm.bind("u", check=lambda _data: vm.states[0] == back)
    return vm


@pytest.mark.parametrize("seed", [1, 2, 0xC0FFEE])
def test_probabilistic_example_is_70_30(seed):
    vm = probabilistic_vm(seed)
    weights = {vm.image.names[e]: vm._weight(e) for e in vm.enabled()}
    assert weights == {"a": 9830, "b": 22938}           # 0.3 and 0.7 in Q15
    counts = frequencies(vm, 20_000)
    total = counts["a"] + counts["b"]
    assert total == 20_000 and vm.violations == 0
    assert chi_square(counts, {"a": 9830 / 32768, "b": 22938 / 32768}) < CHI2_P001[1]
    share_b = counts["b"] / total
    assert abs(share_b - 0.7) < 0.015
    assert abs(share_b - 0.5) > 0.15 and share_b < 0.9      # not all-zero weights, not always-first


def test_two_supervisors_multiply_their_probabilities():
    image = Image.parse(compile_inputs([str(TWO_DICE)]).image)
    vm = VM(image, policy="weighted", seed=7)
    weights = {image.names[e]: vm._weight(e) for e in vm.enabled()}
    # a: 0.5 x 0.2, b: 0.3 x 0.8, c: 0.2 (the second supervisor does not know c)
    assert weights["a"] == pytest.approx(0.1 * 32768, abs=2)
    assert weights["b"] == pytest.approx(0.24 * 32768, abs=2)
    assert weights["c"] == pytest.approx(0.2 * 32768, abs=2)
    total = sum(weights.values())
    counts = frequencies(vm, 30_000)
    assert sum(counts.values()) == 30_000
    assert chi_square(counts, {n: w / total for n, w in weights.items()}) < CHI2_P001[2]
    shares = {n: counts[n] / 30_000 for n in counts}
    assert shares["a"] == pytest.approx(0.1 / 0.54, abs=0.015)
    assert shares["b"] == pytest.approx(0.24 / 0.54, abs=0.015)
    assert shares["c"] == pytest.approx(0.2 / 0.54, abs=0.015)


def test_uniform_policy_ignores_probabilities():
    """The contrast that makes the weighted test meaningful: uniform on the same model is 50/50."""
    vm = probabilistic_vm(1)
    vm.policy = "uniform"
    counts = frequencies(vm, 20_000)
    assert abs(counts["b"] / 20_000 - 0.5) < 0.015
