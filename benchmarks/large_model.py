"""A generated large supervisor for the speed benchmarks: SUPERVISORS local supervisors over
EVENTS events (a third controllable), each with an alphabet of a quarter of the events and
STATES states, transitions drawn from a fixed seed, written as a Nadzoru 2 ``supervisor.yaml``.
The corpus holds no model this wide; issue 13 asks for 30+ events and 10 supervisors."""

import random
from pathlib import Path

EVENTS = 36
SUPERVISORS = 10
STATES = 6
SEED = 13


def large_model_yaml(events: int = EVENTS, supervisors: int = SUPERVISORS, states: int = STATES,
                     seed: int = SEED) -> str:
    """The model's text: the same for the same arguments (one seeded generator)."""
    rng = random.Random(seed)
    names = ["EV_%s%d" % ("c" if e % 3 == 0 else "u", e) for e in range(events)]
    alphabets = [sorted(rng.sample(range(events), max(2, events // 4))) for _ in range(supervisors)]
    data, positions = [], []
    for alphabet in alphabets:
        positions.append(len(data))
        for _ in range(states):
            # A supervisor disables controllable events only: uncontrollable ones stay defined.
            defined = [e for e in alphabet if e % 3 or rng.random() < 0.5]
            data.append(str(len(defined)))
            for e in defined:
                target = rng.randrange(states)
                data += [names[e], str(target >> 8), str(target & 0xFF)]
    flags = [[1 if e in alphabet else 0 for e in range(events)] for alphabet in alphabets]
    return ("num_events: %d\nnum_supervisors: %d\nevents: [ %s ]\nev_controllable: [ %s ]\n"
            "ev_public: [ %s ]\nsup_events: [ %s ]\nsup_init_state: [ %s ]\nsup_current_state: [ %s ]\n"
            "sup_data_pos: [ %s ]\nsup_data: [ %s ]\n"
            % (events, supervisors, ", ".join(names), ", ".join("1" if e % 3 == 0 else "0" for e in range(events)),
               ", ".join("1" if e % 5 == 0 else "0" for e in range(events)),
               ", ".join("[%s]" % ", ".join(map(str, f)) for f in flags), ", ".join(["0"] * supervisors),
               ", ".join(["0"] * supervisors), ", ".join(map(str, positions)), ", ".join(data)))


def write_large_model(folder: Path) -> Path:
    """The model written as ``folder/large_10x36.yaml`` (its name says its size)."""
    path = folder / ("large_%dx%d.yaml" % (SUPERVISORS, EVENTS))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(large_model_yaml())
    return path
