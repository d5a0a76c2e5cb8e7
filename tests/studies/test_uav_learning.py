"""The learning of the study: the initial fit gives the published weights, each attempt is one
partial_fit with the take-off SoC and label 1 (delivered) or 0 (aborted), and the NumPy mirror
of the fleet decides exactly as the classifiers do."""

import numpy as np

from swarmvm.studies.drone_delivery.controller import linear_classifier_class
from swarmvm.studies.drone_delivery.features import MEAN, SCALE
from swarmvm.studies.drone_delivery.fleet import Fleet
from swarmvm.studies.drone_delivery.params import Params


def test_initial_fit_gives_the_published_weights_and_both_intercept_signs():
    fleet = Fleet(Params(drones=12), np.random.default_rng(5))
    assert np.allclose(fleet.weights, [-7.7631, -7.7633, 7.7624], atol=1e-3)
    assert np.allclose(np.abs(fleet.intercept), 6.3246, atol=1e-4)
    assert (fleet.intercept > 0).any() and (fleet.intercept < 0).any()


def test_each_attempt_is_one_update_with_the_takeoff_features():
    fleet = Fleet(Params(drones=2), np.random.default_rng(5))
    twin = linear_classifier_class().from_dict(fleet.policies[1].to_dict())
    for features, delivered in [((3000.0, 2.0, 70.3), True), ((5500.0, 4.5, 40.0), False)]:
        fleet.learn(1, features, delivered)
        twin.partial_fit(features, int(delivered))
    assert fleet.policies[1].to_dict() == twin.to_dict()
    assert list(fleet.weights[1]) == twin.weights and fleet.intercept[1] == twin.intercept
    assert fleet.policies[0].t == 15.0 and fleet.policies[1].t == 17.0


def test_fleet_arrays_decide_exactly_as_the_classifiers():
    fleet = Fleet(Params(drones=6), np.random.default_rng(2))
    rng = np.random.default_rng(9)
    for drone in range(6):                       # make the policies differ
        for _ in range(20):
            fleet.learn(drone, (rng.uniform(1000, 6000), rng.uniform(0.5, 5), round(rng.uniform(0, 100), 1)), rng.random() < 0.6)
    d, m, s = rng.uniform(1000, 6000, 2000), rng.uniform(0.5, 5, 2000), np.round(rng.uniform(0, 100, 2000), 1)
    scores = fleet.scores(np.arange(6)[:, None], d, m, s)
    for drone in range(6):
        policy = fleet.policies[drone]
        assert [policy.decision_function(x) for x in zip(d, m, s)] == list(scores[drone])
        assert [policy.bid_value(x) for x in zip(d, m, s)] == list(fleet.bid_values(np.full(2000, drone), scores[drone], s))


def test_bid_window_is_the_first_tick_the_decision_turns_yes():
    params = Params(drones=3)
    fleet = Fleet(params, np.random.default_rng(4))
    from swarmvm.studies.drone_delivery.energy import NEVER, charged, measure
    start, stop = fleet.bid_window(params, np.arange(3)[:, None], 100, 20.0, np.array([[2000.0, 5000.0]]), 3.0)
    for drone in range(3):
        for order, distance in enumerate((2000.0, 5000.0)):
            t = start[drone, order]

            def yes(tick, drone=drone, distance=distance):
                return fleet.scores(drone, distance, 3.0, measure(charged(params, 20.0, tick - 100))) >= 0

            if t == NEVER:
                assert not yes(10 ** 9)                    # not even when full
            else:
                assert yes(t) and (t == 100 or not yes(t - 1))
            assert stop[drone, order] == NEVER             # rising drones never stop bidding
    assert (start < NEVER).sum() >= 2
    assert MEAN == (3500.0, 2.75, 50.0) and SCALE == (1443.38, 1.299, 28.87)


def test_the_study_runs_the_published_uav_controller():
    from pathlib import Path

    from swarmvm.studies.drone_delivery.controller import SUPERVISOR, DroneLogic
    corpus = Path(__file__).resolve().parents[1] / "corpus" / "openswarm" / "uav.yaml"
    assert SUPERVISOR.read_bytes() == corpus.read_bytes()          # package copy of the corpus file
    fleet = Fleet(Params(drones=1), np.random.default_rng(0))
    logic = fleet.logic[0]
    assert isinstance(logic, DroneLogic) and type(logic.vm.controller).__module__ == "uav_controller"
    assert logic.offer((1000.0, 0.5, 100.0)) and logic.state == 2            # capableTask, bid
    logic.auction_result(True)
    assert logic.state == 4                                                   # wonBid, deliver
    logic.turn()
    assert logic.state == 0 and logic.vm.violations == 0                      # condReturn, return
    assert not logic.offer((6000.0, 5.0, 0.0)) and logic.state == 0           # notCapableTask
