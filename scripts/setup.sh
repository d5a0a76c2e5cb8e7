#!/usr/bin/env bash
# Install what swarmvm needs on a fresh Debian machine (idempotent): the cross toolchains and
# emulators from Debian's packages, then swarmvm itself with its test dependencies from PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
packages="gcc-avr avr-libc binutils-avr simavr libsimavr-dev make gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm g++ clang"
missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  sudo_cmd=""; [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq $missing >/dev/null
fi
python3 -m pip install -q --disable-pip-version-check -e ".[test]"
