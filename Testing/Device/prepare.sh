#!/usr/bin/env bash
# Prepares ONE device call that checks a build on a lent GPU machine (no VTK, no PoCL, no X server
# there; NVIDIA's OpenCL driver): packs the build with the shared tool, lists the default suite's
# tests for it, and copies the scripts, all into .gpu/ of the checkout (ignored by git).
# Then run, with the device tool, from the checkout's root:
#   command: bash .gpu/device_check.sh     carry: [".gpu"]     timeout_s: 570
# and read $OUT's log.txt, bench.tgz and tests.tgz (Documentation/Benchmarks.md, "GPU checks").
#
# usage, from the checkout's root: Testing/Device/prepare.sh [BUILD_DIR] (default ./build)
set -euo pipefail
build="$(cd "${1:-build}" && pwd)"
root="$(git rev-parse --show-toplevel)"
here="$(cd "$(dirname "$0")" && pwd)"
pack="$root/../shared/tools/gpu/pack.sh"
[ -x "$pack" ] || { echo "prepare.sh: $pack not found (the team's GPU tools)" >&2; exit 2; }
"$pack" "$build"
(cd "$build" && ctest -N -V -LE long) | /usr/bin/python3 "$here/list_device_tests.py" "$build/bin" \
  > "$root/.gpu/tests.txt"
printf '%s\n' "$root" > "$root/.gpu/source_dir"
git -C "$root" rev-parse --short HEAD > "$root/.gpu/commit"
cp "$here/device_check.sh" "$here/run_device_tests.sh" "$root/.gpu/"
echo "prepared: $(wc -l < "$root/.gpu/tests.txt") tests, commit $(cat "$root/.gpu/commit"), $(du -sh "$root/.gpu" | cut -f1)"
