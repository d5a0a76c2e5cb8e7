"""How fast the drone-delivery study runs: seconds per simulated week and the 8-week, 25-drone
reference trial (least confident, tau 20 min, seed 1445), event-driven, on one core; and the
plain tick-by-tick engine over the first simulated day for comparison. The published time-stepped
simulator takes 6,102 s for that trial on this machine (design/STUDIES.md).

CPU time (``time.process_time``) is what one core spends; wall time is shown too (the machine
may be shared). ``python benchmarks/drone_delivery.py [weeks]``."""

import sys
import time

from swarmvm.studies.drone_delivery.engine import run
from swarmvm.studies.drone_delivery.params import Params

PUBLISHED_TRIAL_S = 6102.0          # the published simulator, 8 weeks, same machine
PUBLISHED_WEEK_S = 870.0            # one week with learning


def timed(params, mode):
    wall, cpu = time.perf_counter(), time.process_time()
    result = run(params, mode)
    return result, time.process_time() - cpu, time.perf_counter() - wall


def main(weeks=8):
    run(Params(weeks=0))                                      # generate the VM once (not timed)
    params = Params(weeks=weeks)
    result, cpu, wall = timed(params, "event")
    summary = result.summary()
    print("drone delivery, %d drones, %d week(s), %s, tau %g min, seed %d: %d of %d delivered"
          % (params.drones, weeks, params.rule, params.tau_min, params.seed, summary["delivered"], summary["orders"]))
    print("| engine | simulated | CPU s | wall s | CPU s per simulated week | vs published |")
    print("|---|---|---|---|---|---|")
    print("| event-driven | %d weeks | %.2f | %.2f | %.2f | %.0fx |"
          % (weeks, cpu, wall, cpu / weeks, PUBLISHED_WEEK_S * weeks / cpu if weeks else 0))
    day = params.replace(weeks=1, week_s=86400)
    _, tick_cpu, tick_wall = timed(day, "tick")
    print("| tick by tick | 1 day | %.2f | %.2f | %.1f | %.1fx |"
          % (tick_cpu, tick_wall, tick_cpu * 7, PUBLISHED_WEEK_S / (tick_cpu * 7)))
    if weeks == 8:
        print("8-week trial: %.2f s CPU (target < 10 s; published simulator %.0f s: %.0fx)"
              % (cpu, PUBLISHED_TRIAL_S, PUBLISHED_TRIAL_S / cpu))


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:2]))
