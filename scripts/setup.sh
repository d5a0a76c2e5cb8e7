#!/usr/bin/env bash
# Install what swarmvm needs on a fresh Debian machine (idempotent): the cross toolchains,
# emulators and build tools from Debian's packages (with what building ARGoS from source needs:
# xz-utils, Lua 5.3, FreeImage; scripts/argos.sh builds it; and clang's libFuzzer and sanitizer
# runtimes, libclang-rt-14-dev, for the C fuzzer: tests/fuzz; Chromium and its driver for the
# inspector page's browser tests: tests/inspector; Frama-C with Eva and WP, frama-c-base, and the
# provers WP calls through Why3, why3 cvc4 z3, for `make prove`:
# proof/), then a virtual environment of the
# project's own (.venv/, or $VENV) holding swarmvm (editable) and its test dependencies.
# Debian's system Python refuses `pip install` (PEP 668), hence the venv; every make target
# uses it, and `.venv/bin/swarmvm` (or `source .venv/bin/activate`) is the installed CLI.
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${VENV:-.venv}"
python="${SETUP_PYTHON:-python3}"

packages="gcc-avr avr-libc binutils-avr simavr gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm libsimavr-dev make
  g++ clang cmake pkg-config cppcheck python3-venv graphviz
  xz-utils liblua5.3-dev libfreeimage-dev libfreeimageplus-dev libyaml-cpp-dev
  libclang-rt-14-dev chromium chromium-driver frama-c-base why3 cvc4 z3"
missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  sudo_cmd=""; [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  echo "setup: installing Debian packages:$missing"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq $missing >/dev/null
fi

"$python" -c 'import sys; sys.exit(sys.version_info < (3, 11))' \
  || { echo "setup: swarmvm needs Python 3.11 or newer; $python is $("$python" --version 2>&1)" >&2; exit 1; }
[ -x "$venv/bin/python" ] || "$python" -m venv "$venv"
# Reinstall only when the project's metadata changed since the last install.
stamp="$venv/.swarmvm-installed"
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
  "$venv/bin/python" -m pip install -q --disable-pip-version-check -e ".[test]"
  touch "$stamp"
fi
