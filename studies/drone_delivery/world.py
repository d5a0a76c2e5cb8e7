"""The state of one trial and what happens in one tick, shared by both engines.

A tick t runs three steps (design/STUDIES.md, the 2-tick auction timeline):

1. orders arriving at t join the queue;
2. drones in flight move: the abort check (measured SoC <= xi SoC_takeoff), a move of 10 m and
   its energy; a drone delivers within 80 m of the destination and lands within 800 m of the
   centre, where it learns from the attempt; a drone with no energy left away from the centre
   is lost;
3. the auction: reserved drones able to go take off (forecast); an auction advertised at t-2
   is resolved (the winner takes off, drawing the take-off tick's energy); the drones that heard
   an advertisement at t-1 bid; and, every ``advert_period_s`` ticks while orders are pending
   and a drone is idle at the centre, an order is advertised.

The *tick* engine (``exhaustive=True``) moves flights tick by tick and lets every drone that
heard an advertisement answer it through its VM. The *event* engine plans each flight at take-off
and asks NumPy which drones bid, stepping only the bidders' VMs (a drone that does not bid
fires notCapableTask, a self-loop of the supervisor's wait state)."""

from __future__ import annotations

import dataclasses
from typing import List, Optional

import numpy as np

from .auction import lowest, winner
from .energy import (
    NEVER,
    aborts_before_move,
    charged,
    first_true,
    lost_before_move,
    measure,
    outbound_end,
    outbound_ticks,
    return_ticks,
)
from .fleet import LEVELS, Fleet
from .orders import Orders
from .params import Params

IDLE, OUT, BACK, LOST, RESERVED = range(5)


@dataclasses.dataclass
class Flight:
    """One delivery attempt. Times are ticks; SoCs are percentages."""

    order: int
    takeoff: int
    soc0: float                 # SoC at take-off
    features: tuple             # (distance, mass, measured take-off SoC): what the drone learns from
    limit: float                # abort at measured SoC <= limit
    drain: float                # per tick with the parcel
    drain_empty: float          # per tick without it
    moves: int                  # outbound moves to the destination
    turn: int = NEVER           # tick of delivery or abort (the drone turns back)
    delivered: bool = False
    position: float = 0.0       # distance from the centre when turning
    soc_turn: float = 0.0
    drain_back: float = 0.0
    moves_back: int = 0
    end: int = NEVER            # landing (or loss) tick
    lost: bool = False


@dataclasses.dataclass
class Auction:
    tick: int
    order: int
    heard: np.ndarray                      # idle drones at the centre when advertised
    bid_done: bool = False
    bidders: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    values: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))
    reservers: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    reservation_values: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))


class World:
    """Fleet, orders, queue and counters of one trial; ``step(t)`` runs one tick."""

    def __init__(self, params: Params, fleet: Fleet, orders: Orders, auction_rng: np.random.Generator,
                 exhaustive: bool) -> None:
        self.params, self.fleet, self.orders = params, fleet, orders
        self.rng = auction_rng
        self.exhaustive = exhaustive
        size = fleet.size
        self.phase = np.full(size, IDLE, dtype=np.int8)
        self.land_tick = np.zeros(size, dtype=np.int64)
        self.land_soc = np.full(size, 100.0)
        self.flights: List[Optional[Flight]] = [None] * size
        self.next_event = np.full(size, NEVER, dtype=np.int64)    # event engine: next flight event
        self.reserved = np.full(size, -1, dtype=np.int64)         # order a reserved drone waits for
        self.reserve_tick = np.full(size, NEVER, dtype=np.int64)
        self.pending = np.zeros(0, dtype=np.int64)                # arrived, unallocated, undelivered (sorted)
        self.arrived = 0
        self.after: Optional[int] = None                          # last advertised order (None: oldest next)
        self.last_ad = -params.advert_period_s
        self.auction: Optional[Auction] = None
        self.delivered_tick = np.full(len(orders), -1, dtype=np.int64)
        self.adverts = self.takeoffs = self.aborts = self.losses = self.reservations = 0
        # Event engine, per order: the earliest tick an idle drone whose decision rises with its charge would bid.
        self.earliest = np.full(len(orders), NEVER, dtype=np.int64) if not exhaustive else None
        # Event engine: the ticks [start, stop) in which each idle drone would bid on each pending order.
        self.bid_start = np.full((size, len(orders)), NEVER, dtype=np.int64) if not exhaustive else None
        self.bid_stop = np.full((size, len(orders)), NEVER, dtype=np.int64) if not exhaustive else None

    # -- helpers ------------------------------------------------------------------------------------
    def soc(self, drones, t):
        """SoC of drones charging at the centre at tick t."""
        return charged(self.params, self.land_soc[drones], t - self.land_tick[drones])

    def idle(self) -> np.ndarray:
        return np.flatnonzero(self.phase == IDLE)

    def _pend(self, order: int) -> None:
        self.pending = np.insert(self.pending, np.searchsorted(self.pending, order), order)
        if self.bid_start is not None:
            self.earliest[order] = NEVER
            self._bid_windows(self.idle(), np.array([order]))

    def _unpend(self, order: int) -> None:
        self.pending = np.delete(self.pending, np.searchsorted(self.pending, order))

    def _leave_pool(self, drone: int, phase: int) -> None:
        """An idle drone takes off or reserves: forget it in the per-order earliest bids."""
        self.phase[drone] = phase
        if self.earliest is not None and len(self.pending) and self.fleet.rising(drone):
            orders = self.pending[self.bid_start[drone, self.pending] == self.earliest[self.pending]]
            idle = self.idle()
            idle = idle[self.fleet.rising(idle)]
            self.earliest[orders] = self.bid_start[np.ix_(idle, orders)].min(axis=0) if len(idle) else NEVER

    def _bid_windows(self, drones: np.ndarray, orders: np.ndarray) -> None:
        """Event engine: cache when each idle drone would bid on each order."""
        if len(drones) and len(orders):
            rows, columns = drones[:, None], orders[None, :]
            start, stop = self.fleet.bid_window(self.params, rows, self.land_tick[rows], self.land_soc[rows],
                                                self.orders.distance[columns], self.orders.mass[columns])
            self.bid_start[rows, columns], self.bid_stop[rows, columns] = start, stop
            rising = self.fleet.rising(drones)
            if rising.any():
                self.earliest[orders] = np.minimum(self.earliest[orders], start[rising].min(axis=0))

    # -- one tick -----------------------------------------------------------------------------------
    def step(self, t: int) -> None:
        self.arrivals(t)
        self.flying(t)
        self.auctions(t)

    def arrivals(self, t: int) -> None:
        while self.arrived < len(self.orders) and self.orders.tick[self.arrived] <= t:
            self._pend(self.arrived)
            self.arrived += 1

    def flying(self, t: int) -> None:
        if self.exhaustive:
            for drone in np.flatnonzero((self.phase == OUT) | (self.phase == BACK)):
                self._tick_flight(int(drone), t)
        else:
            for drone in np.flatnonzero(self.next_event == t):
                flight = self.flights[drone]
                if t == flight.turn:
                    self._turn(int(drone), flight)
                if t == flight.end:
                    self._end(int(drone), flight, t)

    # -- flights: tick by tick ------------------------------------------------------------------------
    def _tick_flight(self, drone: int, t: int) -> None:
        flight = self.flights[drone]
        if self.phase[drone] == OUT:
            j = t - flight.takeoff
            if lost_before_move(flight.soc0, flight.drain, j):
                flight.lost = True
                self._end(drone, flight, t)
            elif aborts_before_move(flight.soc0, flight.drain, flight.limit, j):
                self._set_turn(flight, t, False, (j - 1) * self.params.speed_ms, flight.soc0 - j * flight.drain)
                self._turn(drone, flight)
            elif j == flight.moves:
                self._set_turn(flight, t, True, j * self.params.speed_ms, flight.soc0 - (j + 1) * flight.drain)
                self._turn(drone, flight)
        else:
            i = t - flight.turn
            if flight.soc_turn - (i - 1) * flight.drain_back <= 0.0:
                flight.lost = True
                self._end(drone, flight, t)
            elif flight.position - i * self.params.speed_ms < self.params.home_radius_m or i == flight.moves_back:
                self._end(drone, flight, t)

    # -- flights: planned at take-off -----------------------------------------------------------------
    def _plan(self, drone: int, flight: Flight) -> None:
        j = int(outbound_end(flight.soc0, flight.drain, flight.limit, flight.moves))
        if j <= flight.moves and lost_before_move(flight.soc0, flight.drain, j):
            flight.lost, flight.end = True, flight.takeoff + j
            self.next_event[drone] = flight.end
            return
        if j <= flight.moves:
            self._set_turn(flight, flight.takeoff + j, False, (j - 1) * self.params.speed_ms, flight.soc0 - j * flight.drain)
        else:
            j = flight.moves
            self._set_turn(flight, flight.takeoff + j, True, j * self.params.speed_ms, flight.soc0 - (j + 1) * flight.drain)
        i = int(first_true(lambda i: flight.soc_turn - (i - 1) * flight.drain_back <= 0.0, 1, flight.moves_back))
        flight.lost = i <= flight.moves_back
        flight.end = flight.turn + (i if flight.lost else flight.moves_back)
        self.next_event[drone] = flight.turn

    def _set_turn(self, flight: Flight, t: int, delivered: bool, position: float, soc: float) -> None:
        flight.turn, flight.delivered, flight.position, flight.soc_turn = t, delivered, position, soc
        flight.drain_back = flight.drain_empty if delivered else flight.drain
        flight.moves_back = int(return_ticks(self.params, position))

    def _turn(self, drone: int, flight: Flight) -> None:
        """Delivered or aborted: condReturn, and back."""
        if flight.delivered:
            self.delivered_tick[flight.order] = flight.turn
        else:
            self.aborts += 1
        self.phase[drone] = BACK
        self.fleet.logic[drone].turn()
        self.next_event[drone] = flight.end

    def _end(self, drone: int, flight: Flight, t: int) -> None:
        """Landing (learn from the attempt, charge) or loss."""
        self.next_event[drone] = NEVER
        self.flights[drone] = None
        if flight.lost:
            self.phase[drone] = LOST
            self.losses += 1
            if not flight.delivered:
                self._pend(flight.order)
            return
        self.phase[drone] = IDLE
        self.land_tick[drone] = t
        self.land_soc[drone] = max(0.0, flight.soc_turn - (t - flight.turn) * flight.drain_back)
        self.fleet.learn(drone, flight.features, flight.delivered)
        if not flight.delivered:
            self._pend(flight.order)
        if self.bid_start is not None:
            self._bid_windows(np.array([drone]), self.pending)

    def _take_off(self, drone: int, order: int, t: int) -> None:
        p = self.params
        soc0 = float(self.soc(drone, t))
        reading = float(measure(soc0))
        distance, mass = float(self.orders.distance[order]), float(self.orders.mass[order])
        soh = self.fleet.soh[drone]
        flight = Flight(order, t, soc0, (distance, mass, reading), p.xi * reading,
                        p.drain_per_tick(mass, soh), p.drain_per_tick(0.0, soh), int(outbound_ticks(p, distance)))
        self.flights[drone] = flight
        self._leave_pool(drone, OUT)
        self.takeoffs += 1
        if not self.exhaustive:
            self._plan(drone, flight)

    # -- the auction ----------------------------------------------------------------------------------
    def auctions(self, t: int) -> None:
        if self.params.forecast:
            self._reserved_take_offs(t)
        auction = self.auction
        if auction is not None and t == auction.tick + 2:
            self._resolve(auction, t)
        elif auction is not None and t == auction.tick + 1:
            self._bid(auction, t)
        if self.auction is None and t >= self.last_ad + self.params.advert_period_s and len(self.pending):
            heard = self.idle()
            if len(heard):
                self._advertise(heard, t)

    def next_order(self) -> int:
        if self.after is None:
            return int(self.pending[0])
        index = int(np.searchsorted(self.pending, self.after, side="right"))
        return int(self.pending[index % len(self.pending)])

    def _advertise(self, heard: np.ndarray, t: int) -> None:
        self.auction = Auction(t, self.next_order(), heard)
        self.last_ad = t
        self.adverts += 1

    def _features(self, auction: Auction, t: int):
        order = auction.order
        return self.orders.distance[order], self.orders.mass[order], measure(self.soc(auction.heard, t))

    def _bid(self, auction: Auction, t: int) -> None:
        distance, mass, readings = self._features(auction, t)
        fleet, heard = self.fleet, auction.heard
        scores = fleet.scores(heard, distance, mass, readings)
        if self.exhaustive:
            yes = np.array([fleet.logic[d].offer((float(distance), float(mass), float(r)))
                            for d, r in zip(heard, readings)], dtype=bool)
        else:
            yes = scores >= 0.0
            for d, r in zip(heard[yes], readings[yes]):
                if not fleet.logic[d].offer((float(distance), float(mass), float(r))):
                    raise AssertionError("drone %d: the VM's learned check disagrees with the fleet arrays" % d)
        auction.bidders = heard[yes]
        if self.params.rule == "random":
            auction.values = self.rng.random(len(auction.bidders)) if len(auction.bidders) else np.zeros(0)
        else:
            auction.values = fleet.bid_values(auction.bidders, scores[yes], readings[yes])
        if self.params.forecast and not yes.any():
            self._reservation_bids(auction, distance, mass, readings, t)
        auction.bid_done = True

    def _reservation_bids(self, auction: Auction, distance, mass, readings, t: int) -> None:
        """Forecast: drones that could bid once charged offer the time they need."""
        fleet, heard = self.fleet, auction.heard
        can = fleet.rising(heard)
        can[can] = fleet.crossing_level(heard[can], distance, mass) <= LEVELS
        auction.reservers = heard[can]
        auction.reservation_values = fleet.reservation_values(heard[can], distance, mass, readings[can])

    def _resolve(self, auction: Auction, t: int) -> None:
        self.auction = None
        won = winner(auction.bidders, auction.values, self.params.rule)
        if won >= 0:
            for drone in auction.bidders:
                self.fleet.logic[drone].auction_result(drone == won)
            self._unpend(auction.order)
            self.after = None
            self._take_off(won, auction.order, t)
            return
        reserver = lowest(auction.reservers, auction.reservation_values)
        if reserver >= 0:
            self._unpend(auction.order)
            self.after = None
            self._leave_pool(reserver, RESERVED)
            self.reserved[reserver] = auction.order
            self.reservations += 1
            if not self.exhaustive:
                self.reserve_tick[reserver] = self.bid_start[reserver, auction.order]
            return
        self.after = auction.order

    def _reserved_take_offs(self, t: int) -> None:
        for drone in np.flatnonzero(self.phase == RESERVED):
            order = int(self.reserved[drone])
            features = (float(self.orders.distance[order]), float(self.orders.mass[order]), float(measure(self.soc(drone, t))))
            ready = self.fleet.policies[drone].decide(features) if self.exhaustive else self.reserve_tick[drone] <= t
            if ready:
                logic = self.fleet.logic[drone]
                if not logic.offer(features):
                    raise AssertionError("drone %d: reserved take-off refused by its VM" % drone)
                logic.auction_result(True)
                self.reserved[drone], self.reserve_tick[drone] = -1, NEVER
                self._take_off(int(drone), order, t)
