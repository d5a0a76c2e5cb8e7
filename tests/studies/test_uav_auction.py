"""Order processing rules (i)-(iv) of the seed and the winner rules (ties to the highest id)."""

import numpy as np
import pytest

from swarmvm.studies.drone_delivery.auction import lowest, winner, winners
from swarmvm.studies.drone_delivery.fleet import Fleet
from swarmvm.studies.drone_delivery.orders import Orders
from swarmvm.studies.drone_delivery.params import Params
from swarmvm.studies.drone_delivery.world import IDLE, LOST, World


def test_least_and_most_confident_and_ties_to_the_highest_id():
    ids, values = [2, 5, 7, 9], [0.4, 0.1, 0.9, 0.1]
    assert winner(ids, values, "least-confident") == 9          # 0.1 twice: the higher id
    assert winner(ids, values, "most-confident") == 7
    assert winner([1, 3], [0.5, 0.5], "most-confident") == 3
    assert winner([1, 3, 4], [0.2, 0.8, 0.3], "random") == 3      # random: drawn values, highest wins
    assert winner([1, 3, 4], [100.0, 80.0, 100.0], "threshold") == 4   # baseline: highest SoC
    assert winner([], [], "least-confident") == -1


def test_winners_per_column_with_missing_bids():
    values = np.array([[0.3, 0.0], [0.2, 0.5], [0.2, 0.1]])
    bidding = np.array([[True, False], [True, False], [True, False]])
    assert list(winners(values, bidding, "least-confident")) == [2, -1]


def test_reservations_lowest_wait_wins_ties_to_highest_id():
    assert lowest([1, 4, 6], [30.0, 10.0, 10.0]) == 6
    assert lowest([], []) == -1


def world(drones=3, orders=3, threshold=0.9):
    params = Params(rule="threshold", threshold=threshold, drones=drones, weeks=1, accuracy_samples=10)
    fleet = Fleet(params, np.random.default_rng(0))
    batch = Orders(np.arange(orders, dtype=np.int64), np.full(orders, 2000.0), np.full(orders, 1.0))
    return World(params, fleet, batch, np.random.default_rng(1), exhaustive=True)


def advertised(w, ticks):
    """The order advertised at each tick of ``ticks`` (None when there was none)."""
    seen = []
    for t in ticks:
        before = w.adverts
        w.step(t)
        seen.append(w.auction.order if w.adverts > before else None)
    return seen


def test_no_bid_moves_to_the_next_order_and_wraps_round():        # rule (ii)
    w = world()
    w.land_soc[:] = 50.0                                          # below the 90 % threshold: nobody bids
    assert advertised(w, range(9)) == [0, None, 1, None, 2, None, 0, None, 1]
    assert w.takeoffs == 0


def test_no_advertisement_while_no_drone_is_at_the_centre():      # rule (i)
    w = world()
    w.phase[:] = LOST                                             # away (no flight needed for this check)
    assert advertised(w, range(6)) == [None] * 6
    w.phase[:] = IDLE
    w.land_soc[:] = 50.0
    assert advertised(w, range(6, 9)) == [0, None, 1]


def test_allocation_returns_to_the_front_of_the_queue():          # rule (iii)
    w = world(drones=2, orders=4)
    w.land_soc[:] = 50.0
    assert advertised(w, range(5)) == [0, None, 1, None, 2]       # order 2 advertised at tick 4
    w.land_soc[1], w.land_tick[1] = 100.0, 5                      # drone 1 now full: it bids at tick 5
    assert advertised(w, range(5, 9)) == [None, 0, None, 1]       # 2 allocated at 6; next: oldest (0)
    assert w.takeoffs == 1 and w.flights[1].order == 2 and list(w.pending) == [0, 1, 3]


def test_an_aborted_order_returns_to_its_own_slot():              # rule (iv)
    w = world(drones=1, orders=3, threshold=0.0)
    w.fleet.soh[:] = 0.5
    w.orders.distance[:] = 6000.0
    w.orders.mass[:] = 5.0
    w.land_soc[:] = 30.0                                          # too little charge: it must abort
    t = 0
    while w.aborts == 0:
        w.step(t)
        t += 1
    assert list(w.pending) == [1, 2]                                   # order 0 is away with the drone
    while w.phase[0] != IDLE:
        w.step(t)
        t += 1
    assert list(w.pending) == [0, 1, 2] and w.delivered_tick[0] == -1


def test_a_drone_out_of_energy_is_lost_and_its_order_returns():
    w = world(drones=1, orders=1, threshold=0.0)
    w.fleet.soh[:] = 0.5
    w.orders.distance[:] = 6000.0
    w.orders.mass[:] = 5.0
    w.land_soc[:] = 0.04                                          # reads 0.0: abort limit 0, energy gone first
    for t in range(20):
        w.step(t)
    assert w.losses == 1 and w.phase[0] == LOST and list(w.pending) == [0]
    assert advertised(w, range(20, 24)) == [None] * 4             # no drone left to advertise to


@pytest.mark.parametrize("rule", ["least-confident", "most-confident"])
def test_the_rule_picks_the_least_or_most_confident_bidder(rule):
    params = Params(rule=rule, drones=4, weeks=1, accuracy_samples=10)
    fleet = Fleet(params, np.random.default_rng(3))
    batch = Orders(np.zeros(1, dtype=np.int64), np.array([1500.0]), np.array([1.0]))
    w = World(params, fleet, batch, np.random.default_rng(1), exhaustive=True)
    w.land_soc[:] = [100.0, 90.0, 95.0, 85.0]
    for t in range(3):
        w.step(t)
    readings = np.array([100.0, 90.0, 95.0, 85.0])
    values = fleet.bid_values(np.arange(4), fleet.scores(np.arange(4), 1500.0, 1.0, readings), readings)
    expected = int(np.argmin(values)) if rule == "least-confident" else int(np.argmax(values))
    assert w.flights[expected] is not None and w.takeoffs == 1
