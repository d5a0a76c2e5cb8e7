#!/usr/bin/env bash
# The installed product, as a new user gets it: build the wheel from this checkout, install it
# into a fresh venv outside the checkout, run every verb from an unrelated directory with the
# wheel's CLI and with the editable install's, and require identical output; then run the CLI
# tests that need only the package (CLI, inputs, golden files, Python targets) against the
# wheel's install. Usage: scripts/check_wheel.sh [EDITABLE_VENV]
# (`make wheel-check`; footprint needs build/*/energy_worker.elf: `make firmware` first).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
editable="$(cd "${1:-$root/.venv}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$editable/bin/python" -m build --wheel --outdir "$work/dist" "$root" >"$work/build.log" 2>&1 \
  || { cat "$work/build.log"; exit 1; }
# The metadata builds without a warning (setuptools' deprecations, data folders it would ignore).
if grep -E "WARNING|[Dd]eprecat" "$work/build.log"; then echo "wheel-check: the wheel build warns (above)"; exit 1; fi
python3 -m venv "$work/venv"
"$work/venv/bin/python" -m pip install -q --disable-pip-version-check "$work"/dist/swarmvm-*.whl pytest hypothesis
echo "wheel-check: installed $(basename "$work"/dist/swarmvm-*.whl) into a fresh venv"

example="$root/examples/energy_worker/supervisor.yaml"
elfs=("$root/build/kilobot/energy_worker.elf" "$root/build/capbot/energy_worker.elf")
# One run of every verb, in the current directory, with the CLI given as $1.
verbs() {
  local cli="$1"
  "$cli" --version
  "$cli" check "$example" "$root"/tests/corpus/openswarm/*.yaml
  "$cli" pack "$example" -o logic.svm && "$cli" check logic.svm
  for target in $("$(dirname "$cli")/python" -c "from swarmvm.targets import TARGETS; print(*sorted(TARGETS))"); do
    "$cli" gen "$example" --target "$target" -o "gen/$target" --name energy_worker
  done
  "$cli" script "$example" --steps 30 --seed 3 > script.txt && cat script.txt
  "$cli" trace "$example" --script script.txt --seed 7
  "$cli" trace logic.svm --script script.txt --seed 7 --policy first
  "$cli" footprint "${elfs[@]}"
  local models="$root/tests/corpus/synthesis/energy_worker"
  "$cli" synth --script "$models/script.txt" "$models"/[GE]?.xml -o synth.yaml
  "$cli" equiv synth.yaml "$example"
  "$cli" check --properties "$example"
  "$cli" export "$example" --format gen -o export && "$cli" export "$example" --format dot -o export
  "$cli" bounds energy && "$cli" bounds energy --strategy mobile --json
  # the energy study's C++ sources and supervisors travel in the wheel: the same plugin, the same trial
  "$cli" sim energy --strategy mobile --chargers 3 --duration 60 --seed 2 | grep -v '^seconds'
}
for install in editable wheel; do
  mkdir -p "$work/run-$install"
  cli="$editable/bin/swarmvm"; [ "$install" = wheel ] && cli="$work/venv/bin/swarmvm"
  (cd "$work/run-$install" && verbs "$cli" > stdout.txt 2>&1) \
    || { echo "wheel-check: the $install install failed:"; tail -n 20 "$work/run-$install/stdout.txt"; exit 1; }
done
diff -r "$work/run-editable" "$work/run-wheel" \
  || { echo "wheel-check: the wheel's output differs from the editable install's"; exit 1; }
echo "wheel-check: every verb gives identical output from the wheel and the editable install" \
  "($(ls "$work/run-wheel/gen" | wc -l) targets generated)"
# The wheel alone has no studies extra: the study verbs say how to get it, in one line.
studies="$(cd "$work" && "$work/venv/bin/swarmvm" sim uav 2>&1)" && status=0 || status=$?
[ "$status" = 2 ] && [ "$studies" = 'swarmvm: error: the studies need numpy, pandas, pyarrow, dask, tqdm, matplotlib: pip install "swarmvm[studies]"' ] \
  || { echo "wheel-check: 'swarmvm sim uav' without the studies extra: status $status, $studies"; exit 1; }
# Of tests/boundary, the input files and the output layer: what the wheel's verbs read and write
# (the escaping and layer checks there read the checkout's sources and runtimes, not the wheel).
boundary=()
for name in budgets hostile_inputs inputs limits messages_bounded output_faults output_over_input outputs \
    readers_generative structured_bounds byte_file_names; do
  boundary+=("$root/tests/boundary/test_$name.py")
done
(cd "$work" && "$work/venv/bin/python" -m pytest -p no:cacheprovider --rootdir "$root" \
  "$root/tests/cli" "${boundary[@]}" "$root/tests/golden" "$root/tests/targets/pipuck" "$root/tests/python" \
  "$root/tests/docs" \
  "$root/tests/footprint/test_footprint_ci.py" "$root/tests/targets/capbot/test_capbot_qemu.py")
# every command README.md and docs/ show, run with the wheel's swarmvm; the CI recipes, --cycles
# building the board it ships, and the generated CapBot project's bare-metal build from the wheel alone
