"""An independent reading of a supervisor.yaml, the oracle the conformance and property tests
check the VMs against: PyYAML's safe loader and its own walk of Nadzoru's flat ``sup_data``,
sharing no code with the compiler's loader, canonical form or tables."""

import yaml


class FileOracle:
    """Local supervisors straight from the file: states as numbered there, events by name."""

    def __init__(self, path):
        with open(path) as handle:
            doc = yaml.safe_load(handle)
        self.events = [str(e) for e in doc["events"]]
        self.controllable = {e for e, c in zip(self.events, doc["ev_controllable"]) if c}
        flags = doc.get("ev_public", doc.get("ev_shared", [0] * len(self.events)))
        self.public = {e for e, p in zip(self.events, flags) if p}
        self.alphabets, self.delta = [], []
        data = doc["sup_data"]
        positions = doc["sup_data_pos"] + [len(data)]
        for s in range(doc["num_supervisors"]):
            self.alphabets.append({e for e, x in zip(self.events, doc["sup_events"][s]) if x})
            table, pos = [], positions[s]
            while pos < positions[s + 1]:
                n = data[pos]
                table.append({str(data[pos + 1 + 3 * k]): data[pos + 2 + 3 * k] * 256 + data[pos + 3 + 3 * k]
                              for k in range(n)})
                pos += 1 + 3 * n
            self.delta.append(table)
        self.initial = list(doc["sup_init_state"])
        uncontrollable = sorted(e for e in self.events if e not in self.controllable)
        self.input_order = [e for e in uncontrollable if e in self.public] + \
                           [e for e in uncontrollable if e not in self.public]

    def enabled(self, cur):
        return {c for c in self.controllable
                if all(c not in self.alphabets[s] or c in self.delta[s][cur[s]] for s in range(len(cur)))}

    def apply(self, cur, event):
        """Move every supervisor that can; return how many could not (violations)."""
        missed = 0
        for s in range(len(cur)):
            if event in self.alphabets[s]:
                if event in self.delta[s][cur[s]]:
                    cur[s] = self.delta[s][cur[s]][event]
                else:
                    missed += 1
        return missed
