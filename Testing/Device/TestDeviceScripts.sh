#!/usr/bin/env bash
# ctest smoke test of the device-check scripts, on this machine's OpenCL device: the test list
# made from this build's ctest holds the refracta-render scenes first, no render-window, Python or
# long test, and every line is name<TAB>command under @BIN@; run_device_tests.sh runs a few of
# them and reports each with its exit status (a stand-in that exits 3 reads rc=3).
# Usage: TestDeviceScripts.sh BUILD_DIR TMPDIR [PYTHON]
set -u
build="$(cd "$1" && pwd)" tmp="$2" python="${3:-python3}"
here="$(cd "$(dirname "$0")" && pwd)"
fail() { echo "TestDeviceScripts: $*" >&2; exit 1; }
rm -rf "$tmp" && mkdir -p "$tmp" || fail "cannot create $tmp"

(cd "$build" && ctest -N -V -LE long) | "$python" "$here/list_device_tests.py" "$build/bin" \
  > "$tmp/tests.txt" || fail "list_device_tests.py exited $?"
[ "$(wc -l < "$tmp/tests.txt")" -gt 20 ] || fail "only $(wc -l < "$tmp/tests.txt") tests listed"
head -n 1 "$tmp/tests.txt" | grep -q '^RefractaRender.Default'$'\t' ||
  fail "the default scene's render is not first: $(head -n 1 "$tmp/tests.txt" | cut -f1)"
! grep -qE '^[^	]*(RenderingOpenGL|Long|Convergence)' "$tmp/tests.txt" ||
  fail "a render-window or long test is listed"
! grep -q 'python3\|pvpython\|pvbatch' "$tmp/tests.txt" || fail "a Python test is listed"
bad=$(grep -vc $'^[A-Za-z0-9_.]*\tmkdir -p .* && cd .* && env .*@BIN@/' "$tmp/tests.txt")
[ "$bad" -eq 0 ] || fail "$bad line(s) not name<TAB>command under @BIN@"

# Run two real tests and a stand-in that fails.
grep -E '^(RefractaCore\.GridFrame|RefractaOpenCL\.Context)'$'\t' "$tmp/tests.txt" > "$tmp/some.txt"
[ "$(wc -l < "$tmp/some.txt")" -eq 2 ] || fail "RefractaCore.GridFrame or RefractaOpenCL.Context missing"
printf 'Refracta.StandIn\tmkdir -p %s && cd %s && env @BIN@/stand-in\n' "$tmp" "$tmp" >> "$tmp/some.txt"
mkdir -p "$tmp/bin"
ln -sf "$build/bin/RefractaCore.GridFrame" "$build/bin/RefractaOpenCL.Context" "$tmp/bin/"
printf '#!/bin/sh\nexit 3\n' > "$tmp/bin/stand-in" && chmod +x "$tmp/bin/stand-in"
bash "$here/run_device_tests.sh" "$tmp/some.txt" "$tmp/bin" "$tmp/logs" 2 > "$tmp/summary.txt" ||
  fail "run_device_tests.sh exited $?"
grep -q '^RefractaCore.GridFrame rc=0 ' "$tmp/summary.txt" || fail "GridFrame: $(cat "$tmp/summary.txt")"
grep -q '^RefractaOpenCL.Context rc=0 ' "$tmp/summary.txt" || fail "Context: $(cat "$tmp/summary.txt")"
grep -q '^Refracta.StandIn rc=3 ' "$tmp/summary.txt" || fail "stand-in: $(cat "$tmp/summary.txt")"
grep -q 'PASSED' "$tmp/logs/RefractaCore.GridFrame.log" || fail "no GridFrame log"
echo "TestDeviceScripts: $(wc -l < "$tmp/tests.txt") tests listed; run_device_tests.sh reported all three"
