"""How fast a 600-s energy-replenishment trial runs in real ARGoS (10 steps per second, 6,000
steps), against the same trial with every robot running an empty controller (same robots,
sensors, physics and loop functions): the difference is what the generated VM and the study's
application layer (virtual-force motion, protocol) cost.

CPU seconds are the argos3 process's (``RUSAGE_CHILDREN``: what one core spends, whatever else
the shared machine runs); wall seconds are shown too. The median of ``repeats`` runs of each.
``python benchmarks/energy_study.py [repeats] [--json FILE]``."""

import argparse
import resource
import statistics
import time

from swarmvm.studies.energy_replenishment import plugin, trial
from swarmvm.studies.energy_replenishment.params import Params
from figures import add_json_option, write_figures

CASES = (("fixed, 6 workers", Params()),
         ("mobile, 6 workers + 6 chargers", Params(strategy="mobile", chargers=6)),
         ("mobile, 6 workers + 12 chargers", Params(strategy="mobile", chargers=12)))


def timed(params, library, baseline):
    """(CPU s, wall s) of one trial."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    trial.run(params, library, baseline=baseline)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("repeats", nargs="?", type=int, default=5)
    add_json_option(parser)
    args = parser.parse_args()
    library = plugin.build()
    rows = []
    print("| trial (600 s, 6,000 steps) | generated controllers: CPU s | wall s | empty controllers: CPU s | wall s "
          "| ratio (CPU) | VM + application, CPU s |")
    print("|---|---|---|---|---|---|---|")
    for name, params in CASES:
        study = [timed(params, library, False) for _ in range(args.repeats)]
        empty = [timed(params, library, True) for _ in range(args.repeats)]
        row = dict(case=name, cpu_s=statistics.median(c for c, _ in study), wall_s=statistics.median(w for _, w in study),
                   empty_cpu_s=statistics.median(c for c, _ in empty), empty_wall_s=statistics.median(w for _, w in empty))
        row["ratio"] = row["cpu_s"] / row["empty_cpu_s"]
        rows.append(row)
        print("| %s | %.3f | %.3f | %.3f | %.3f | %.2f | %.3f |" % (name, row["cpu_s"], row["wall_s"], row["empty_cpu_s"],
                                                                  row["empty_wall_s"], row["ratio"],
                                                                  row["cpu_s"] - row["empty_cpu_s"]))
    write_figures(args.json, rows)


if __name__ == "__main__":
    main()
