#!/usr/bin/env bash
# ctest smoke test of run_benchmarks.sh: a --quick run writes summary.md with a row for every
# program that ran, and a failing program becomes a FAILED row instead of aborting the run.
# Usage: TestRunBenchmarks.sh SCRIPT BINDIR TMPDIR [run_benchmarks.sh options, e.g. --only LIST]
set -u
script="$1" bin="$2" tmp="$3"
shift 3
fail() { echo "TestRunBenchmarks: $*" >&2; exit 1; }
rm -rf "$tmp" && mkdir -p "$tmp" || fail "cannot create $tmp"

# 1. The real programs at smoke sizes: every '== key: Exe' the script announces has a row.
bash "$script" --quick --bin "$bin" --out "$tmp/run" "$@" > "$tmp/run.log" 2>&1 ||
  fail "run_benchmarks.sh exited $? (log: $tmp/run.log)"
summary="$tmp/run/summary.md"
[ -s "$summary" ] || fail "no summary.md"
grep -q '^- device: ' "$summary" || fail "summary.md names no device"
grep -q 'commit: ' "$summary" || fail "summary.md names no commit"
ran=$(grep -c '^== ' "$tmp/run.log")
[ "$ran" -gt 0 ] || fail "no program ran"
for exe in $(sed -n 's/^== [a-z0-9]*: \([A-Za-z]*\) .*/\1/p' "$tmp/run.log" | sort -u); do
  grep -q "^| $exe " "$summary" || fail "summary.md has no row for $exe"
done
if grep -q 'FAILED' "$summary"; then fail "a benchmark failed: $(grep FAILED "$summary")"; fi
# Every headline is a number (or n/a where the program's setting has no such row).
bad=$(awk -F'|' 'NR > 7 && $4 !~ /^ *(n\/a.*|[-+0-9.eE]+) *$/' "$summary")
[ -z "$bad" ] || fail "non-numeric headline: $bad"

# 2. A program that fails: a stand-in BenchmarkPhotonTracer that exits 3, before a real program.
mkdir -p "$tmp/bin"
ln -sf "$bin/BenchmarkVoxelize" "$tmp/bin/BenchmarkVoxelize"
printf '#!/bin/sh\necho "deliberate failure" >&2\nexit 3\n' > "$tmp/bin/BenchmarkPhotonTracer"
chmod +x "$tmp/bin/BenchmarkPhotonTracer"
bash "$script" --quick --bin "$tmp/bin" --out "$tmp/fail" --only photon,voxelize \
  > "$tmp/fail.log" 2>&1 || fail "run_benchmarks.sh aborted on a failing program"
grep -q '^| BenchmarkPhotonTracer | FAILED (exit 3)' "$tmp/fail/summary.md" ||
  fail "the failing program has no FAILED row"
grep -q '^| BenchmarkVoxelize | voxelize total' "$tmp/fail/summary.md" ||
  fail "the program after the failure did not run"
echo "TestRunBenchmarks: $ran programs summarised; failure reported in the table"
