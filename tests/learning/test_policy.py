"""The learned policy's fixed-point pieces (docs/learning.md, section 3) on their own."""

import math

import pytest

from swarmvm.compiler.pipeline import compile_inputs
from swarmvm_learn import LearnedPolicy, exp_neg_q15, q16
from swarmvm_vm import VM, Image

from test_c_policy import FORAGER


@pytest.fixture
def forager():
    return Image.parse(compile_inputs([str(FORAGER)]).image)


def test_fixed_point_exponential_tracks_exp():
    for tenth in range(0, 161):
        x = q16(tenth / 10.0)
        assert abs(exp_neg_q15(x) - 32768 * math.exp(-tenth / 10.0)) <= 8 + 0.001 * 32768 * math.exp(-tenth / 10.0)
    assert exp_neg_q15(0) == 32768 and exp_neg_q15(q16(16.0)) == 0


def test_lower_temperature_sharpens_the_choice(forager):
    def weights(beta):
        policy = LearnedPolicy(forager, inv_temp_q8=beta)
        far = forager.event_index("far")
        policy.theta[policy.rank[far]] = q16(1.0)           # state 0 of the task supervisor
        enabled = VM(forager).enabled()
        return dict(zip((forager.names[e] for e in enabled), policy.weights([0, 0], enabled)))
    hot, cold = weights(64), weights(1024)                   # temperature 4 and 1/4
    assert hot["far"] == cold["far"] == 32768
    assert hot["near"] == pytest.approx(32768 * math.exp(-0.25), rel=0.01)
    assert cold["near"] == pytest.approx(32768 * math.exp(-4.0), rel=0.01)


def test_single_choice_draws_nothing_and_rewards_are_q16(forager):
    uav = Image.parse(compile_inputs([str(FORAGER.parents[2] / "tests" / "corpus" / "openswarm" / "uav.yaml")]).image)
    vm = VM(uav, policy="learned", learner=LearnedPolicy(uav), seed=9)
    vm.states = [vm.moves[0][0][uav.event_index("capableTask")]]   # bid is the only enabled event
    state = vm.rng.state
    assert [uav.names[e] for e in vm.step()] == ["bid"]
    assert vm.rng.state == state
    assert vm.learner.reward(q16(1.0)) is False                      # nothing to credit
    policy = LearnedPolicy(forager)
    vm = VM(forager, policy="learned", learner=policy, seed=9)
    vm.step()
    with pytest.raises(TypeError):
        policy.reward(1.5)
    assert policy.reward(q16(1.5)) is True and policy.updates == 1


def test_reward_moves_preferences_towards_the_rewarded_event(forager):
    policy = LearnedPolicy(forager, rate_q16=q16(0.5))
    vm = VM(forager, policy="learned", learner=policy, seed=2)
    chosen = vm.step()[-1]
    policy.reward(q16(3.0))
    rank = policy.rank[chosen]
    assert policy.theta[rank] > 0                                  # task state 0 row
    others = [policy.theta[policy.rank[e]] for e in (forager.event_index(n) for n in ("near", "far", "wait"))
              if e != chosen]
    assert all(value < 0 for value in others)
