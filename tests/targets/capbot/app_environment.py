"""What firmware/capbot/app_qemu.c (the bare-metal CapBot application's environment in QEMU)
makes happen, as an event script the reference VM can replay."""

from swarmvm.compiler.runtime_files import python_vm

APP_STEPS = 20          # firmware/capbot/app_qemu.c: SVM_APP_STEPS
ENV_SEED = 2024         # firmware/capbot/app_qemu.c: ENV_SEED


def environment_script(image):
    """The events app_qemu.c makes occur: per step, each uncontrollable event in event order
    with probability 1/4 from xorshift32 seeded with ENV_SEED."""
    rng = python_vm().XorShift32(ENV_SEED)
    uncontrollable = [e for e in range(image.num_events) if not image.controllable >> e & 1]
    return [frozenset(e for e in uncontrollable if rng.below(4) == 0) for _ in range(APP_STEPS)]
