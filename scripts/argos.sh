#!/usr/bin/env bash
# Find the real ARGoS simulator, or build it headless from source into a cache outside the
# checkout, and print its install prefix (the folder holding bin/argos3) on stdout.
#
#   scripts/argos.sh            find ARGoS, else build it from ARGOS_SRC; print the prefix
#   scripts/argos.sh run ARGS   the same, then run `argos3 ARGS` with its libraries and plugins
#                               on LD_LIBRARY_PATH / ARGOS_PLUGIN_PATH (plus any already set)
#
# Search order: ARGOS_PREFIX, the `argos3` program on PATH, ARGoSConfig.cmake in the usual
# prefixes, `pkg-config argos3_simulator`, then the cache. If nothing is found, ARGOS_SRC (a
# source archive; default ../shared/vendor/argos3-421bd763.tar.xz next to the checkout; given
# explicitly, it is built even when an ARGoS is installed) is built once into
# ${XDG_CACHE_HOME:-$HOME/.cache}/swarmvm/<archive name>/. Concurrent callers (make test and a
# test) are serialised by a lock, and the install is renamed into place only when complete, so
# a half-built cache is never taken for a built one.
#
# A build takes about 10 minutes on two cores: stderr says what it does at each stage (unpack,
# configure, compile, install) and the compile's progress (make's per cent, every 5 points);
# the whole build output goes to a log in the cache, whose path the first line names.
#
# Exit status: 0 found or built; 3 no ARGoS and no source archive (callers may skip); 1 other
# errors (a bad ARGOS_PREFIX, a failed build).
set -euo pipefail
checkout="$(cd "$(dirname "$0")/.." && pwd)"
mode="${1:-}"
run_args=("${@:2}")
case "$mode" in ""|run) ;; *) echo "usage: scripts/argos.sh [run ARGOS3_ARGS...]" >&2; exit 1 ;; esac

is_prefix() { [ -x "$1/bin/argos3" ] && [ -d "$1/include/argos3" ]; }
found() {
  if [ "$mode" = run ]; then
    export LD_LIBRARY_PATH="$prefix/lib/argos3${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    export ARGOS_PLUGIN_PATH="$prefix/lib/argos3${ARGOS_PLUGIN_PATH:+:$ARGOS_PLUGIN_PATH}"
    exec "$prefix/bin/argos3" "${run_args[@]}"
  fi
  echo "$prefix"; exit 0
}

if [ -n "${ARGOS_PREFIX:-}" ]; then
  prefix="$ARGOS_PREFIX"
  is_prefix "$prefix" || { echo "argos.sh: ARGOS_PREFIX=$prefix has no bin/argos3 and include/argos3" >&2; exit 1; }
  found
fi
if [ -z "${ARGOS_SRC:-}" ]; then
  if bin="$(command -v argos3)"; then
    prefix="$(cd "$(dirname "$bin")/.." && pwd)"; is_prefix "$prefix" && found
  fi
  for prefix in /usr/local /usr /opt /opt/local; do
    [ -f "$prefix/share/argos3/cmake/ARGoSConfig.cmake" ] && is_prefix "$prefix" && found
  done
  prefix="$(pkg-config --variable=prefix argos3_simulator 2>/dev/null)" && is_prefix "$prefix" && found
fi

src="${ARGOS_SRC:-$checkout/../shared/vendor/argos3-421bd763.tar.xz}"
name="$(basename "$src")"; name="${name%.tar.*}"
cache="${XDG_CACHE_HOME:-$HOME/.cache}/swarmvm"
prefix="$cache/$name"
is_prefix "$prefix" && found
[ -f "$src" ] || { echo "argos.sh: no ARGoS found and no source archive at $src (set ARGOS_PREFIX or ARGOS_SRC)" >&2; exit 3; }

mkdir -p "$cache"
exec 9>"$cache/$name.lock"
flock 9
if is_prefix "$prefix"; then exec 9>&-; found; fi   # built by a concurrent caller meanwhile
work="$(mktemp -d "$cache/.$name.XXXXXX")"
trap 'rm -rf "$work"' EXIT
log="$cache/$name.build.log"
exec 8>&2   # the caller's stderr: the stages and the progress go there, the build's output to $log
say() { echo "argos.sh: $*" >&8; }
# make's output on stdin, copied to $log; its "[ NN%]" lines reported every 5 points.
progress() {
  awk -v out="$log" '{ print >> out; fflush(out) }
    match($0, /^\[ *[0-9]+%\]/) { p = substr($0, 2, RLENGTH - 3) + 0
      if (p >= shown + 5 || (p == 100 && shown < 100)) { shown = p; printf "argos.sh: compiling ARGoS: %d%%\n", p; fflush() } }'
}
say "building ARGoS from $src into $prefix, once (about 10 minutes on two cores); full output: $log"
: >"$log"
{
  say "unpacking the source" && mkdir "$work/src" "$work/build" \
    && tar -xJf "$src" -C "$work/src" --strip-components=1 && cd "$work/build" \
    && say "configuring (cmake)" \
    && cmake -DCMAKE_BUILD_TYPE=Release -DARGOS_BUILD_FOR=simulator -DARGOS_DOCUMENTATION=OFF \
             -DARGOS_FORCE_NO_QTOPENGL=ON -DARGOS_INSTALL_LDSOCONF=OFF \
             -DCMAKE_INSTALL_PREFIX="$prefix" "$work/src/src" \
    && say "compiling (make -j$(nproc))" \
    && { make -j"$(nproc)" 2>&1 | progress >&8; } \
    && say "installing" && make install DESTDIR="$work/dest"
} >>"$log" 2>&1 || { echo "argos.sh: ARGoS build failed; see $log" >&2; exit 1; }
mv "$work/dest$prefix" "$prefix"
say "built; installed in $prefix"
rm -rf "$work"; trap - EXIT
exec 9>&-
found
