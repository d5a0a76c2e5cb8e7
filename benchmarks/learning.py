"""Does policy `learned` learn? The forager of examples/learning against `uniform` and the best
achievable average reward.

The forager (examples/learning/supervisor.yaml) has several controllable events enabled in most
states. After each choice the operator pays a noisy reward: the task's value minus the energy
spent (far +4, near +1.5, wait -0.1, walk -1, run -2, charge -0.5, plus Gaussian noise of
deviation 0.5). The best achievable average reward is found exactly by enumerating every
deterministic stationary policy over the product of the supervisors' states (the transitions are
deterministic, so each such policy ends in a cycle whose mean reward is exact).

Prints, per seed and on average, the mean reward of the last quarter of the run for learned and
uniform, the best achievable, and the learned policy's share of it; saves the reward curves to
build/learning.png (matplotlib, Agg); then, when avr-gcc and simavr are installed, the cycles the
learning code costs on the Kilobot's ATmega328P. ``python benchmarks/learning.py [steps] [seeds]``."""

import itertools
import random
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "runtime_py"))
sys.path.insert(0, str(ROOT / "tests" / "learning"))

from swarmvm.compiler.pipeline import compile_inputs  # noqa: E402
from swarmvm_learn import LearnedPolicy, q16  # noqa: E402
from swarmvm_vm import VM, Image  # noqa: E402
import learnbuild  # noqa: E402

FORAGER = ROOT / "examples" / "learning" / "supervisor.yaml"
REWARDS = {"charge": -0.5, "far": 4.0, "near": 1.5, "run": -2.0, "wait": -0.1, "walk": -1.0}
NOISE = 0.5
WINDOW = 100                      # steps of the plot's rolling mean
# The learned policy's options: temperature 1, rate 0.1, baseline averaging 1/16.
OPTIONS = dict(inv_temp_q8=256, rate_q16=q16(0.1), baseline_shift=4)


def forager_image():
    return Image.parse(compile_inputs([str(FORAGER)]).image)


def run(image, policy, seed, steps):
    """Per-step operator rewards of one run; ``policy`` is "uniform" or "learned"."""
    learner = LearnedPolicy(image, **OPTIONS) if policy == "learned" else None
    vm = VM(image, policy=policy, learner=learner, seed=seed)
    noise = random.Random(seed * 7919 + 1)
    rewards = []
    for _ in range(steps):
        fired = vm.step()
        reward = REWARDS[image.names[fired[-1]]] + noise.gauss(0.0, NOISE) if fired else 0.0
        if learner is not None:
            learner.reward(q16(reward))
        rewards.append(reward)
    return rewards


def best_average(image):
    """The best mean reward per step of any deterministic stationary policy (exact)."""
    vm = VM(image, policy="first")
    states, frontier, enabled = [], [tuple(vm.states)], {}
    while frontier:                                   # reachable product states
        state = frontier.pop()
        if state in enabled:
            continue
        vm.states = list(state)
        enabled[state] = vm.enabled()
        states.append(state)
        for event in enabled[state]:
            vm.states = list(state)
            vm._apply(event)
            frontier.append(tuple(vm.states))
    best = float("-inf")
    for choice in itertools.product(*(enabled[s] for s in states)):
        policy = dict(zip(states, choice))
        vm.reset()
        seen, trail = {}, []
        state = tuple(vm.states)
        while state not in seen:                      # follow the deterministic orbit to its cycle
            seen[state] = len(trail)
            event = policy[state]
            trail.append(REWARDS[image.names[event]])
            vm._apply(event)
            state = tuple(vm.states)
        cycle = trail[seen[state]:]
        best = max(best, sum(cycle) / len(cycle))
    return best


def tail_mean(rewards):
    tail = rewards[len(rewards) * 3 // 4:]
    return sum(tail) / len(tail)


def rolling(rewards, width):
    out, total = [], 0.0
    for i, value in enumerate(rewards):
        total += value - (rewards[i - width] if i >= width else 0.0)
        out.append(total / min(i + 1, width))
    return out


def plot(curves, best, seeds, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(figsize=(7, 4))
    for label, series in curves.items():
        axes.plot(range(WINDOW, len(series) + 1), series[WINDOW - 1:], label=label)
    axes.axhline(best, color="black", linestyle="--", label="best achievable (%.2f)" % best)
    axes.set_xlabel("step")
    axes.set_ylabel("reward per step")
    axes.set_title("Forager: rolling mean of %d steps, mean of %d seeds" % (WINDOW, seeds))
    axes.legend(loc="center right")
    figure.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(str(path), dpi=100, metadata={"Software": None})
    plt.close(figure)


def main(steps=6000, seeds=5):
    image = forager_image()
    best = best_average(image)
    print("forager: best achievable mean reward per step %.3f" % best)
    print("| seed | learned (last quarter) | uniform (last quarter) | learned / best |")
    print("|---|---|---|---|")
    results = {"learned": [], "uniform": []}
    for seed in range(1, seeds + 1):
        learned, uniform = run(image, "learned", seed, steps), run(image, "uniform", seed, steps)
        results["learned"].append(learned)
        results["uniform"].append(uniform)
        print("| %d | %.3f | %.3f | %.1f %% |" % (seed, tail_mean(learned), tail_mean(uniform),
                                                100 * tail_mean(learned) / best))
    means = {k: sum(tail_mean(r) for r in v) / seeds for k, v in results.items()}
    print("| mean | %.3f | %.3f | %.1f %% |" % (means["learned"], means["uniform"], 100 * means["learned"] / best))
    curves = {}
    for label, runs in results.items():
        smoothed = [rolling(r, WINDOW) for r in runs]
        curves[label] = [sum(values) / seeds for values in zip(*smoothed)]
    path = ROOT / "build" / "learning.png"
    plot(curves, best, seeds, path)
    print("plot: %s" % path.relative_to(ROOT))
    return means, best


def avr_cycles():
    """{measurement: cycles} from tests/learning/c/cycles_probe.c in simavr (Kilobot flags)."""
    image = compile_inputs([str(FORAGER)]).image
    with tempfile.TemporaryDirectory() as temp:
        header = Path(temp) / "cycles_data.h"
        header.write_text("#define CYCLES_THETA_CAP %d\nstatic const uint8_t cycles_image[%d] PROBE_CONST = {%s};\n" % (
            len(LearnedPolicy(Image.parse(image)).theta), len(image), ", ".join("0x%02x" % b for b in image)))
        sources = [learnbuild.RUNTIME_C / "swarmvm.c", learnbuild.RUNTIME_C / "swarmvm_learn.c",
                   learnbuild.PROBES / "cycles_probe.c"]
        elf = learnbuild.build_avr(Path(temp) / "cycles.elf", sources, includes=[temp],
                                   defines=["SVM_MAX_EVENTS=32", "SVM_MAX_SUPERVISORS=8"], optimise="-O3")
        text = learnbuild.run_simavr(elf)
    return {line.split()[1]: int(line.split()[2], 16) for line in text.splitlines() if line.startswith("K ")}


def print_avr_cycles():
    if not (shutil.which("avr-gcc") and shutil.which("simavr")):
        print("ATmega328P cycles: skipped (avr-gcc or simavr missing)")
        return
    print("| ATmega328P @ 8 MHz (-O3, float) | cycles | ms |")
    print("|---|---|---|")
    for name, cycles in avr_cycles().items():
        print("| %s | %d | %.2f |" % (name, cycles, cycles / 8000.0))


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
    print_avr_cycles()
