"""Fast version of benchmarks/learning.py: on the forager, a few hundred steps of policy
`learned` already earn clearly more than `uniform`, on every seed, and approach the best."""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def bench():
    spec = importlib.util.spec_from_file_location("learning_benchmark", ROOT / "benchmarks" / "learning.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_best_achievable_is_far_then_walk(bench):
    assert bench.best_average(bench.forager_image()) == pytest.approx((4.0 - 1.0) / 2)


def test_learned_beats_uniform_within_a_few_hundred_steps(bench):
    """All preferences start at 0, so the learned policy starts as uniform: any gap is learnt."""
    image = bench.forager_image()
    best = bench.best_average(image)
    for seed in (1, 2, 3):
        learned = bench.run(image, "learned", seed, 800)
        uniform = bench.run(image, "uniform", seed, 800)
        late_learned, late_uniform = bench.tail_mean(learned), bench.tail_mean(uniform)
        assert late_learned > late_uniform + 0.8, (seed, late_learned, late_uniform)
        assert late_learned > 0.8 * best, (seed, late_learned, best)
