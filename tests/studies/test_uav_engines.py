"""The event-driven engine against the plain tick-by-tick engine: identical trials (every
delivery tick, counter, weekly accuracy, final classifier and VM state) for every rule, the
threshold baseline and the forecasting variant."""

import numpy as np
import pytest

from swarmvm.studies.drone_delivery.engine import run


def same(a, b):
    sa, sb = a.summary(), b.summary()
    for timing in ("seconds", "cpu_seconds"):
        sa.pop(timing), sb.pop(timing)
    assert sa == sb
    assert np.array_equal(a.delivered_tick, b.delivered_tick)
    assert np.array_equal(a.weights, b.weights) and np.array_equal(a.intercept, b.intercept)
    assert a.vm_states == b.vm_states


CASES = [dict(rule="least-confident"), dict(rule="most-confident"), dict(rule="random"),
         dict(rule="threshold", threshold=0.6), dict(rule="least-confident", forecast=True),
         dict(rule="threshold", threshold=0.9, forecast=True)]


@pytest.mark.parametrize("case", CASES[:2])
def test_event_engine_equals_tick_engine(short, case):
    params = short.replace(**case)
    event, tick = run(params, "event"), run(params, "tick")
    same(event, tick)
    summary = event.summary()
    assert summary["delivered"] > 5 and summary["aborted"] > 0       # the run exercised both outcomes
    assert event.adverts > 10 * event.takeoffs                        # and skipped many dead adverts


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES[2:])
def test_event_engine_equals_tick_engine_other_rules(short, case):
    params = short.replace(**case, weeks=3)
    event, tick = run(params, "event"), run(params, "tick")
    same(event, tick)
    assert event.takeoffs > 5
    if case.get("forecast"):
        assert event.reservations > 0


def test_pretraining_then_forecast_is_identical_in_both_engines(short):
    params = short.replace(pretrain_weeks=1, forecast=True, weeks=1)
    same(run(params, "event"), run(params, "tick"))


def test_a_trial_is_reproducible_from_its_seed(short):
    a, b = run(short), run(short)
    same(a, b)
    assert run(short.replace(seed=12)).summary()["orders"] != a.summary()["orders"] or \
        not np.array_equal(run(short.replace(seed=12)).soh, a.soh)
