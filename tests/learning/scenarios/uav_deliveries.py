"""Drive a generated uav controller (``swarmvm gen uav.yaml --target python --learned-check
capableTask/notCapableTask``) through task announcements, auctions and deliveries.

Run inside the generation directory with the learning tests' folder on sys.path; prints one
JSON object: the learned check's decision per task, the events each step fired, the number of
outcomes reported and the classifier's final parameters."""

import json
import sys

import uav_app
from drone import MEAN, SCALE, SEED_LABELS, SEED_POINTS, delivery_stream
from swarmvm_learn import LinearClassifier


def main(tasks):
    classifier = LinearClassifier(MEAN, SCALE, alpha=0.01)
    classifier.fit(SEED_POINTS, SEED_LABELS)
    vm = uav_app.make_vm(classifiers={"capableTask": classifier})
    world = {"won": False, "back": False}
    vm.bind("wonBid", check=lambda _d: world["won"])
    vm.bind("condReturn", check=lambda _d: world["back"])
    names = vm.image.event_name
    decisions, steps, outcomes = [], [], 0
    for features, delivered in delivery_stream(tasks, seed=21):
        vm.controller.offer("capableTask", features)
        fired = [names(e)[3:] for e in vm.step()]
        steps.append(fired)
        decisions.append("capableTask" in fired)
        if "capableTask" not in fired:
            continue
        world["won"] = True                     # the auction: this drone wins, takes off
        steps.append([names(e)[3:] for e in vm.step()])
        world["won"], world["back"] = False, True
        steps.append([names(e)[3:] for e in vm.step()])
        world["back"] = False
        vm.controller.report_outcome("capableTask", bool(delivered))
        outcomes += 1
    print(json.dumps(dict(decisions=decisions, steps=steps, outcomes=outcomes, states=vm.states,
                          violations=vm.violations, classifier=classifier.to_dict())))


if __name__ == "__main__":
    main(int(sys.argv[1]))
