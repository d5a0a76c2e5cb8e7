"""The learned selection policy: the C VM with svl_policy as its chooser makes the same choices
and ends with the same parameters as the Python VM with LearnedPolicy, for the same seeds and
rewards (integer fixed point, so bit for bit), on the host and on the ATmega328P (simavr).
Every run also saves the parameters half way and reloads them into a fresh policy. On the AVR
the runs' images are in flash, RAM and EEPROM (the policy reads them through the VM's accessors)."""

import pytest

import learnbuild
from swarmvm.compiler.pipeline import compile_inputs
from swarmvm_format import crc16
from swarmvm_learn import LearnedPolicy, PolicyError, q16
from swarmvm_vm import VM, Image

SOURCES = [learnbuild.RUNTIME_C / "swarmvm.c", learnbuild.RUNTIME_C / "swarmvm_learn.c",
           learnbuild.PROBES / "policy_probe.c"]
FORAGER = learnbuild.ROOT / "examples" / "learning" / "supervisor.yaml"
CORPUS = learnbuild.ROOT / "tests" / "corpus" / "openswarm"
# Operator reward of each forager event: value of the task minus the energy it costs.
FORAGER_REWARDS = {"charge": -0.5, "far": 4.0, "near": 1.5, "run": -2.0, "wait": -0.1, "walk": -1.0}


class ProbeInputs:
    """The probe's uncontrollable events: xorshift32 from seed ^ 0x5A5A5A5A, true below 40/256."""

    def __init__(self, seed):
        self.state = (seed ^ 0x5A5A5A5A) & 0xFFFFFFFF

    def __call__(self, _data):
        x = self.state
        x ^= (x << 13) & 0xFFFFFFFF
        x ^= x >> 17
        x ^= (x << 5) & 0xFFFFFFFF
        self.state = x
        return (x >> 24) < 40


def rewards_for(image):
    """Q16 reward per event: the forager's table, or a fixed spread for corpus supervisors."""
    if image.names and set(image.names) == set(FORAGER_REWARDS):
        return [q16(FORAGER_REWARDS[name]) for name in image.names]
    return [q16(((7 * e) % 11 - 5) / 2.0) for e in range(image.num_events)]


def python_run(image, seed, beta, rate, shift, steps):
    rewards = rewards_for(image)
    policy = LearnedPolicy(image, beta, rate, shift)
    vm = VM(image, policy="learned", learner=policy, seed=seed)
    inputs = ProbeInputs(seed)
    for event in vm.input_order:
        vm.bind(event, check=inputs)
    chosen = []
    for step in range(steps):
        fired = vm.step()
        pick = fired[-1] if fired and image.controllable >> fired[-1] & 1 else 0xFF
        chosen.append(pick)
        if pick != 0xFF:
            policy.reward(rewards[pick])
        if step == steps // 2:
            fresh = LearnedPolicy(image, 1, 0, 0)
            fresh.from_words(policy.to_words())
            vm.learner = policy = fresh
    return chosen, policy.to_words()


# (supervisor, seed, 1/temperature Q8.8, rate Q16, baseline shift, steps)
HOST_RUNS = [(FORAGER, 1, 256, q16(0.1), 4, 1500), (FORAGER, 77, 1024, q16(0.5), 2, 1500),
             (FORAGER, 0, 64, q16(0.02), 0, 800), (CORPUS / "network_worker.yaml", 5, 512, q16(0.2), 3, 1500),
             (CORPUS / "hitl_leader.yaml", 9, 256, q16(0.3), 4, 1500)]
# On the AVR, run k loads its image from flash, RAM, EEPROM (k % 3).
AVR_RUNS = [(FORAGER, 3, 512, q16(0.2), 4, 600), (FORAGER, 8, 256, q16(0.3), 3, 600),
            (CORPUS / "hitl_leader.yaml", 12, 256, q16(0.3), 4, 1200)]


def write_policy_header(path, runs):
    index = {}
    for run in runs:
        index.setdefault(run[0], len(index))
    images = [compile_inputs([str(p)]).image for p in sorted(index, key=index.get)]
    parsed = [Image.parse(raw) for raw in images]
    max_events = max(image.num_events for image in parsed)
    cap = max(len(LearnedPolicy(image).theta) for image in parsed)
    lines = ["#define POLICY_RUNS %d" % len(runs), "#define POLICY_MAX_EVENTS %d" % max_events,
             "#define POLICY_THETA_CAP %d" % cap, "#define POLICY_MAX_IMAGE %d" % max(map(len, images)),
             "struct policy_run { uint8_t image; uint16_t image_length; uint32_t seed;",
             "                    uint16_t inv_temp_q8; uint16_t rate_q16; uint8_t shift; uint16_t steps; };"]
    for number, raw in enumerate(images):
        lines.append("static const uint8_t policy_image_%d[%d] PROBE_CONST = {" % (number, len(raw)))
        lines += ["    " + ", ".join("0x%02x" % b for b in raw[i:i + 16]) + "," for i in range(0, len(raw), 16)]
        lines.append("};")
    lines.append("static const uint8_t *const policy_images[%d] = {%s};" % (
        len(images), ", ".join("policy_image_%d" % n for n in range(len(images)))))
    lines.append("static const struct policy_run policy_runs[%d] PROBE_CONST = {" % len(runs))
    for sup, seed, beta, rate, shift, steps in runs:
        raw = images[index[sup]]
        lines.append("    {%d, %d, %dUL, %d, %d, %d, %d}," % (index[sup], len(raw), seed, beta, rate, shift, steps))
    lines.append("};")
    lines.append("static const int32_t policy_rewards[%d][POLICY_MAX_EVENTS] PROBE_CONST = {" % len(runs))
    for sup, *_ in runs:
        values = rewards_for(parsed[index[sup]])
        lines.append("    {%s}," % ", ".join("%dL" % v for v in values + [0] * (max_events - len(values))))
    lines.append("};")
    path.write_text("\n".join(lines) + "\n")
    return {sup: parsed[index[sup]] for sup in index}


def check_identity(text, runs, images):
    tags = ["%s%02x" % (letter, k) for letter in "CP" for k in range(len(runs))]
    lines = learnbuild.parse_lines(text, tags)
    assert set(lines) == set(tags), text[-300:]
    choices_made = 0
    for k, (sup, seed, beta, rate, shift, steps) in enumerate(runs):
        chosen, words = python_run(images[sup], seed, beta, rate, shift, steps)
        c_chosen = [int(h, 16) for h in lines["C%02x" % k].split()]
        assert len(c_chosen) == len(chosen) == steps
        differ = [i for i, (a, b) in enumerate(zip(c_chosen, chosen)) if a != b]
        assert not differ, "run %d: first difference at step %d" % (k, differ[0] + 1)
        assert [int(h, 16) for h in lines["P%02x" % k].split()] == words
        assert words[7] > 20, "run %d: the policy must actually learn (updates %d)" % (k, words[7])
        assert any(words[8:-1]), "run %d: preferences still all zero" % k
        choices_made += sum(1 for c in chosen if c != 0xFF)
    return choices_made


def test_host_c_policy_is_bit_identical_to_python(tmp_path):
    images = write_policy_header(tmp_path / "policy_data.h", HOST_RUNS)
    exe = learnbuild.build_host(tmp_path / "policy", SOURCES, includes=[tmp_path])
    assert check_identity(learnbuild.run_host(exe), HOST_RUNS, images) > 3000


def test_atmega328p_policy_is_bit_identical_to_python(tmp_path):
    images = write_policy_header(tmp_path / "policy_data.h", AVR_RUNS)
    exe = learnbuild.build_avr(tmp_path / "policy.elf", SOURCES, includes=[tmp_path],
                               defines=["SVM_MAX_EVENTS=32", "SVM_MAX_SUPERVISORS=8", "POLICY_ALL_SOURCES",
                                        "SVM_IMAGE_SOURCES=SVM_ANY_SOURCE"])
    assert check_identity(learnbuild.run_simavr(exe), AVR_RUNS, images) > 500


def test_saved_parameters_refuse_another_supervisor_and_corruption(tmp_path):
    forager = Image.parse(compile_inputs([str(FORAGER)]).image)
    other = Image.parse(compile_inputs([str(CORPUS / "energy_worker.yaml")]).image)
    policy = LearnedPolicy(forager)
    vm = VM(forager, policy="learned", learner=policy, seed=4)
    for _ in range(50):
        vm.step()
        policy.reward(q16(1.0))
    policy.save(tmp_path / "policy.json")
    copy = LearnedPolicy(forager)
    copy.load(tmp_path / "policy.json")
    assert copy.to_words() == policy.to_words()
    with pytest.raises(PolicyError):
        LearnedPolicy(other).from_words(policy.to_words())
    words = policy.to_words()
    words[9] ^= 1
    with pytest.raises(PolicyError):
        copy.from_words(words)


def _resealed(words):
    """``words`` with its checksum made right again: what another writer, or a corruption that
    keeps the checksum, hands the loader."""
    words = list(words)
    words[-1] = crc16(b"".join((w & 0xFFFFFFFF).to_bytes(4, "little") for w in words[:-1]))
    return words


def _edited(words, index, value):
    words = list(words)
    words[index] = value & 0xFFFFFFFF
    return _resealed(words)


def test_saved_values_the_policy_never_holds_are_refused_by_both_loaders(tmp_path):
    """A checksum that matches does not make an array the policy's: a baseline shift of 32 or
    more (an undefined shift in the step), a baseline or a preference past its clamp (a signed
    overflow), rates wider than their 16 bits are refused by svl_policy_load and
    LearnedPolicy.from_words alike; the policy's own save is accepted (docs/proof.md)."""
    image = Image.parse(compile_inputs([str(FORAGER)]).image)
    policy = LearnedPolicy(image)
    saved = policy.to_words()
    limit, reward = 32 << 16, 1 << 24
    cases = {"own": (saved, True), "shift 31": (_edited(saved, 5, 31), True),
             "shift 32": (_edited(saved, 5, 32), False), "shift 40": (_edited(saved, 5, 40), False),
             "baseline at its clamp": (_edited(saved, 6, -reward), True),
             "baseline past it": (_edited(saved, 6, reward + 1), False),
             "baseline INT32_MIN": (_edited(saved, 6, -(1 << 31)), False),
             "preference at its clamp": (_edited(saved, 8, limit), True),
             "preference past it": (_edited(saved, 8, limit + 1), False),
             "last preference INT32_MAX": (_edited(saved, len(saved) - 2, (1 << 31) - 1), False),
             "rate of 17 bits": (_edited(saved, 4, 1 << 16), False)}
    for name, (words, accepted) in cases.items():
        try:
            LearnedPolicy(image).from_words(words)
            python = True
        except PolicyError:
            python = False
        assert python == accepted, name
    raw = compile_inputs([str(FORAGER)]).image
    lines = ["#define LOAD_CASES %d" % len(cases), "#define LOAD_WORDS %d" % len(saved),
             "#define LOAD_THETA %d" % len(policy.theta),
             "static const uint8_t load_image[%d] = {%s};" % (len(raw), ", ".join(map(str, raw))),
             "static const uint32_t load_words[LOAD_CASES][LOAD_WORDS] = {"]
    lines += ["    {%s}," % ", ".join("%dUL" % w for w in words) for words, _ in cases.values()]
    (tmp_path / "policy_load_data.h").write_text("\n".join(lines + ["};", ""]))
    exe = learnbuild.build_host(tmp_path / "policy_load", [learnbuild.RUNTIME_C / "swarmvm.c",
                                learnbuild.RUNTIME_C / "swarmvm_learn.c", learnbuild.PROBES / "policy_load_probe.c"],
                                includes=[tmp_path])
    answers = learnbuild.parse_lines(learnbuild.run_host(exe), ["L%02x" % k for k in range(len(cases))])
    for k, (name, (_, accepted)) in enumerate(cases.items()):
        assert answers["L%02x" % k] == ("00" if accepted else "ff"), name
