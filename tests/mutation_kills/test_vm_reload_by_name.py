"""load() of an image whose events are numbered otherwise keeps each callback on its event's name
(swarmvm_vm.Bindings._rebind): deleting the line that moves the actions survived every other test,
whose images kept the events' indices (issue 29)."""

from conformance.cases import compiled_image, supervisor_yaml

# One supervisor, one state: controllable "go" and uncontrollable "hit", self-loops. The second
# image adds "aaa" (uncontrollable, never occurring), first in name order: go and hit move up one.
FIRST = supervisor_yaml(["go", "hit"], [1, 0], [{"go", "hit"}], [[[("go", 0), ("hit", 0)]]])
SECOND = supervisor_yaml(["go", "hit", "aaa"], [1, 0, 0], [{"go", "hit", "aaa"}],
                         [[[("go", 0), ("hit", 0), ("aaa", 0)]]])


def test_a_reload_with_other_event_indices_keeps_actions_and_checks_by_name(vm, tmp_path):
    first, second = compiled_image(tmp_path, FIRST, "first.yaml"), compiled_image(tmp_path, SECOND, "second.yaml")
    machine = vm.VM(first)
    calls = []
    machine.bind("go", action=lambda data: calls.append(("go", data)), data="g")
    machine.bind("hit", check=lambda data: calls.append(("hit?", data)) or True, action=lambda data: calls.append(
        ("hit", data)), data="h")
    assert machine.step() == [1, 0] and calls == [("hit?", "h"), ("hit", "h"), ("go", "g")]
    assert machine.load(second) == ["EV_aaa"]       # its one uncontrollable event without a check
    calls.clear()
    assert machine.step() == [2, 1]                 # hit, then go, at their new indices
    assert calls == [("hit?", "h"), ("hit", "h"), ("go", "g")]
    assert sorted(machine.actions) == [1, 2] and sorted(machine.checks) == [2] and machine.data == {1: "g", 2: "h"}
