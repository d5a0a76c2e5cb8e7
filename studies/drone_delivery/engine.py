"""Run one trial, tick by tick (``mode="tick"``, for validation) or event by event (``"event"``).

The event engine visits only the ticks at which something can change: an order's arrival, a
flight's turn or landing, a reserved drone's departure, the stages of an auction that gets a
bid, a weekly accuracy probe. Advertisements that nobody answers are skipped in bulk: the
queue and the idle drones do not change until the next external event, every idle drone's
earliest bidding tick for every pending order is cached (it depends only on its landing state
and its classifier; World.earliest keeps the minimum over the idle drones per order), so the first advertisement in the round-robin that draws a bid is found
with one array expression; the ones before it are only counted."""

from __future__ import annotations

import time

import numpy as np

from .energy import NEVER
from .fleet import Fleet
from .metrics import AccuracyProbe, Result
from .orders import draw_orders
from .params import Params
from .world import IDLE, Auction, World

MODES = ("event", "tick")


def run(params: Params, mode: str = "event") -> Result:
    """One trial, reproducible from ``params.seed``: numpy Generators for the fleet, the orders,
    the auction draws, the accuracy probe and the pre-training are spawned from it."""
    if mode not in MODES:
        raise ValueError("mode must be one of %s" % (MODES,))
    started, cpu = time.perf_counter(), time.process_time()
    streams = [np.random.default_rng(s) for s in np.random.SeedSequence(params.seed).spawn(5)]
    fleet_rng, orders_rng, auction_rng, probe_rng, pretrain_rng = streams
    fleet = Fleet(params, fleet_rng)
    if params.pretrain_weeks:
        before = params.replace(weeks=params.pretrain_weeks, forecast=False, pretrain_weeks=0)
        simulate(World(before, fleet, draw_orders(before, pretrain_rng, before.horizon), pretrain_rng,
                       exhaustive=mode == "tick"), before.horizon)
        fleet.new_logic()
    probe = AccuracyProbe(params, fleet, probe_rng)
    world = World(params, fleet, draw_orders(params, orders_rng, params.horizon), auction_rng,
                  exhaustive=mode == "tick")
    accuracy = simulate(world, params.horizon, probe)
    return Result.collect(params, world, accuracy, time.perf_counter() - started, time.process_time() - cpu)


def simulate(world: World, horizon: int, probe=None) -> list:
    """Run ``world`` to ``horizon``; the probe's value at every week boundary (week 0 first)."""
    weekly = [probe()] if probe else []
    week = world.params.week_s
    week_end = week
    t = 0
    while t < horizon:
        world.step(t)
        t = t + 1 if world.exhaustive else next_tick(world, t, min(week_end, horizon))
        if t == week_end:
            if probe:
                weekly.append(probe())
            week_end += week
    return weekly


def next_tick(world: World, t: int, bound: int) -> int:
    """The next tick at which anything can happen (event engine), skipping dead advertisements."""
    external = bound
    if world.arrived < len(world.orders):
        external = min(external, int(world.orders.tick[world.arrived]))
    external = min(external, max(t + 1, int(min(world.next_event.min(), world.reserve_tick.min()))))
    auction = world.auction
    if auction is None:
        if len(world.pending) and (world.phase == IDLE).any():
            return min(external, max(t + 1, world.last_ad + world.params.advert_period_s))
        return external
    if auction.bid_done:
        return min(external, auction.tick + 2)
    return skip_dead_adverts(world, auction, external)


def skip_dead_adverts(world: World, auction: Auction, external: int) -> int:
    """``auction`` was just advertised. If it and the next ones draw no bid before the next
    external event, count them and leave the last one open (bids done, none) for resolution."""
    start, heard, period = auction.tick, auction.heard, world.params.advert_period_s
    if external - 2 < start:
        return start + 1
    pending = world.pending
    opens = world.earliest[pending]                         # drones whose decision rises with their charge
    falling = heard[~world.fleet.rising(heard)]             # and the others, which bid only until a tick
    size = len(pending)
    first = int(np.searchsorted(pending, auction.order))
    offset = (np.arange(size) - first) % size               # adverts until each order's turn
    due = _first_advert(opens, NEVER, offset, size, start, period)
    if world.params.forecast:                               # a reservation answers at once
        due = np.where(opens < NEVER, offset, due)
    if len(falling):
        window = np.ix_(falling, pending)
        due = np.minimum(due, _first_advert(world.bid_start[window], world.bid_stop[window], offset, size, start,
                                            period).min(axis=0))
    skipped = min(int(due.min()), (external - 2 - start) // period + 1)
    if skipped < 1:
        return start + 1
    last = start + period * (skipped - 1)
    world.adverts += skipped - 1
    world.last_ad = last
    world.auction = Auction(last, int(pending[(first + skipped - 1) % size]), heard, bid_done=True)
    return last + 2


def _first_advert(opens, closes, offset, size, start, period):
    """The first advert (counted from ``start``) of each order, in the round-robin of ``size``
    pending orders where it comes ``offset``-th, whose bid tick falls in [opens, closes)."""
    wait = np.maximum(0, -((start + 1 - opens) // period))          # ceil((opens - start - 1) / period)
    advert = offset + size * np.maximum(0, -((offset - wait) // size))   # first turn with the window open
    return np.where((opens < NEVER) & (start + period * advert + 1 < closes), advert, NEVER)
