"""Each drone's logic: uav.yaml (the published controller) generated for swarmvm's Python target
with its capability check learned (``swarmvm gen uav.yaml --target python --learned-check
capableTask/notCapableTask``), imported once per process from a private build directory.

The supervisor's cycle is capableTask -> bid -> wonBid -> deliver -> condReturn -> return; the
world answers wonBid/lostBid (the auction) and condReturn (delivered or abort point)."""

from __future__ import annotations

import importlib
import shutil
import sys
import tempfile
from functools import lru_cache
from pathlib import Path
from types import ModuleType

from swarmvm import api

SUPERVISOR = Path(__file__).with_name("uav.yaml")
LEARNED_CHECK = "capableTask/notCapableTask"


@lru_cache(maxsize=None)
def generated_app() -> ModuleType:
    """The generated ``uav_app`` module (``make_vm``; it imports uav_controller, uav_learned and
    uav_tables, and the copy of the Python runtime generated beside them)."""
    outdir = tempfile.mkdtemp(prefix="swarmvm-uav-")
    api.generate_target([str(SUPERVISOR)], "python", outdir, name="uav", learned=[LEARNED_CHECK])
    sys.path.insert(0, outdir)
    try:
        return importlib.import_module("uav_app")     # imports its siblings too
    finally:
        sys.path.remove(outdir)
        shutil.rmtree(outdir)


def linear_classifier_class():
    """swarmvm_learn.LinearClassifier as the generated code imported it."""
    generated_app()
    return importlib.import_module("uav_learned").LinearClassifier


class DroneLogic:
    """One drone's VM and the world's answers to its uncontrollable events."""

    def __init__(self, policy, seed: int) -> None:
        self.vm = generated_app().make_vm(seed=seed, classifiers={"capableTask": policy})
        self.won = self.lost = self.turned = False
        self.vm.bind("wonBid", check=lambda _data: self.won)
        self.vm.bind("lostBid", check=lambda _data: self.lost)
        self.vm.bind("condReturn", check=lambda _data: self.turned)
        self.vm.bind("notCondReturn", check=lambda _data: False)
        names = self.vm.image.names
        self.capable, self.bid = names.index("capableTask"), names.index("bid")

    def offer(self, features) -> bool:
        """A task announcement: one VM step; True iff the drone bids (capableTask, bid)."""
        self.vm.controller.offer("capableTask", features)
        fired = self.vm.step()
        return self.bid in fired

    def auction_result(self, won: bool) -> None:
        """wonBid (and deliver: take-off) or lostBid."""
        self.won, self.lost = won, not won
        self.vm.step()
        self.won = self.lost = False

    def turn(self) -> None:
        """condReturn (delivered, or abort point) and return."""
        self.turned = True
        self.vm.step()
        self.turned = False

    def learn(self, features, delivered: bool) -> None:
        """One online update from an attempt (features with the take-off SoC)."""
        self.vm.controller.report_outcome("capableTask", delivered, features=features)

    @property
    def state(self) -> int:
        return self.vm.states[0]
