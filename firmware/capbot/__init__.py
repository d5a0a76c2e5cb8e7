"""Package data (swarmvm.capbot_qemu, pyproject.toml's package-dir): the bare-metal QEMU
mps2-an386 build of a generated CapBot application (start-up code, linker script, compiler flags,
CapBot API stand-ins, the bare-metal main), which ``swarmvm gen --target capbot`` copies into the
project's qemu/ folder (swarmvm.targets.capbot) and mk/capbot.mk links from here. Nothing here is
imported as code."""
