"""The .argos experiment file of one trial, written from its :class:`Params`: the walled
1.6 m x 1.6 m arena, the workers (and mobile chargers) placed at random in the charging strip,
their controllers from the study plugin and the loop functions that account for energy."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from .params import TICKS_PER_SECOND, Params

RAB_RANGE_M = 0.533       # the seed's neighbourhood
RAB_DATA_SIZE = 6         # the VM's message code (2 bytes) and the protocol's payload (energy_robot.h)
WALL = 0.05
# The seed's thresholds (high: a fraction of capacity; low: the return energy plus a margin) and
# virtual-force motion.
MOTION = dict(high="0.99", margin="10", alpha="1", beta="100", gamma="1", sigma="0.1", **{"lambda": "24"})
CHARGING_STRIP = (-0.78, -0.52)   # where robots start: inside the strip (x from -0.8 to -0.5)


def _fmt(value: float) -> str:
    """The shortest text ARGoS reads back as the same double ("600", "0.005"): a rounded one could
    differ from the trial's parameters, or pass the largest double and fail to parse."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _controller(parent: ET.Element, kind: str, library: str, p: Params, capacity: float, baseline: bool,
                vm_traces: bool) -> None:
    element = ET.SubElement(parent, "energy_idle_controller" if baseline else kind + "_controller", id=kind,
                            library=library)
    actuators = ET.SubElement(element, "actuators")
    ET.SubElement(actuators, "differential_steering", implementation="default")
    ET.SubElement(actuators, "range_and_bearing", implementation="default")
    sensors = ET.SubElement(element, "sensors")
    ET.SubElement(sensors, "range_and_bearing", implementation="medium", medium="rab", show_rays="false")
    ET.SubElement(sensors, "positioning", implementation="default")
    ET.SubElement(sensors, "epuck_proximity", implementation="default", show_rays="false")
    params = ET.SubElement(element, "params")
    ET.SubElement(params, "options", inputs="level", control="after-inputs", policy="uniform")
    ET.SubElement(params, "report", trace="true" if vm_traces else "false", summary="false")
    ET.SubElement(params, "energy", dict(capacity=_fmt(capacity), move=_fmt(p.per_step(p.move_rate)),
                                         core=_fmt(p.per_step(p.core_rate)), speed=_fmt(p.speed_cms),
                                         noise=_fmt(p.steering_noise), inset=_fmt(p.strip_inset_m), **MOTION))


def _robots(arena: ET.Element, prefix: str, kind: str, count: int) -> None:
    distribute = ET.SubElement(arena, "distribute")
    ET.SubElement(distribute, "position", method="uniform", min="%s, -0.75, 0" % CHARGING_STRIP[0],
                  max="%s, 0.75, 0" % CHARGING_STRIP[1])
    ET.SubElement(distribute, "orientation", method="uniform", min="0, 0, 0", max="360, 0, 0")
    entity = ET.SubElement(distribute, "entity", quantity=str(count), max_trials="1000")
    epuck = ET.SubElement(entity, "e-puck", id=prefix, rab_range=_fmt(RAB_RANGE_M), rab_data_size=str(RAB_DATA_SIZE))
    ET.SubElement(epuck, "controller", config=kind)


def robot_kinds(p: Params) -> dict[str, str]:
    """{robot id prefix: its controller, named after the supervisor it runs}: workers ``w0``,
    ``w1``...; with the mobile strategy, chargers ``c0``..."""
    worker = "energy_worker" if p.strategy == "fixed" else "energy_worker_mc"
    return {"w": worker, "c": "energy_charger"} if p.strategy == "mobile" else {"w": worker}


def experiment(p: Params, library: Path, result: Path, trace: Path | None = None, baseline: bool = False,
               vm_traces: bool = False) -> str:
    """The experiment file's text. ``library``: the study plugin (without its suffix, as ARGoS
    takes it); ``result``: where the loop functions write the JSON result; ``trace``: an
    optional per-step CSV; ``baseline``: every robot runs the empty controller (benchmarks);
    ``vm_traces``: every robot logs its VM's canonical trace line each step (``trace ID: LINE``)."""
    root = ET.Element("argos-configuration")
    framework = ET.SubElement(root, "framework")
    ET.SubElement(framework, "system", threads="0")
    ET.SubElement(framework, "experiment", length=_fmt(p.duration_s), ticks_per_second=str(TICKS_PER_SECOND),
                  random_seed=str(p.seed))
    controllers = ET.SubElement(root, "controllers")
    worker = "energy_worker" if p.strategy == "fixed" else "energy_worker_mc"
    _controller(controllers, worker, str(library), p, p.capacity, baseline, vm_traces)
    if p.strategy == "mobile":
        _controller(controllers, "energy_charger", str(library), p, p.charger_capacity, baseline, vm_traces)
    loop = ET.SubElement(root, "loop_functions", library=str(library), label="energy_loop_functions")
    ET.SubElement(loop, "energy", move=_fmt(p.per_step(p.move_rate)), work=_fmt(p.per_step(p.work_rate)),
                  core=_fmt(p.per_step(p.core_rate)), charge=_fmt(p.per_step(p.charge_rate)),
                  transfer=_fmt(p.per_step(p.transfer_rate)), loss=_fmt(p.transfer_loss))
    ET.SubElement(loop, "output", path=str(result), trace=str(trace) if trace else "")
    side = 1.6
    # the arena's outer side and the walls' centres, to the millimetre as they are meant (1.7, not
    # the sum's 1.7000000000000002)
    outer, centre = _fmt(round(side + 2 * WALL, 6)), round((side + WALL) / 2, 6)
    arena = ET.SubElement(root, "arena", size="%s, %s, 1" % (outer, outer), center="0, 0, 0.5")
    for name, position, size in (("north", "0, %s, 0" % _fmt(centre), "%s, %s, 0.1" % (outer, _fmt(WALL))),
                                 ("south", "0, %s, 0" % _fmt(-centre), "%s, %s, 0.1" % (outer, _fmt(WALL))),
                                 ("east", "%s, 0, 0" % _fmt(centre), "%s, %s, 0.1" % (_fmt(WALL), _fmt(side))),
                                 ("west", "%s, 0, 0" % _fmt(-centre), "%s, %s, 0.1" % (_fmt(WALL), _fmt(side)))):
        box = ET.SubElement(arena, "box", id="wall_" + name, size=size, movable="false")
        ET.SubElement(box, "body", position=position, orientation="0, 0, 0")
    for prefix, kind in robot_kinds(p).items():
        _robots(arena, prefix, kind, p.workers if prefix == "w" else p.chargers)
    engines = ET.SubElement(root, "physics_engines")
    ET.SubElement(engines, "dynamics2d", id="dyn2d")
    media = ET.SubElement(root, "media")
    ET.SubElement(media, "range_and_bearing", id="rab", check_occlusions="false")
    ET.SubElement(root, "visualization")
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"
