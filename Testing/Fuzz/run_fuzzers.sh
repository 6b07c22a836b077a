#!/usr/bin/env bash
# Runs Refracta's libFuzzer targets one at a time (a REFRACTA_FUZZ build, see
# Documentation/Developing.md) and reports each target's execution count.
#
#   run_fuzzers.sh BIN_DIR WORK_DIR [RUNS] [MAX_SECONDS] [TARGET...]
#
# BIN_DIR: the build's bin folder; WORK_DIR: where each target's growing corpus, log and crash
# artifacts go (WORK_DIR/<target>/); RUNS: executions per target (default 1000000); MAX_SECONDS:
# the time bound per target (default 7200); TARGETs: default all four. The seed corpus
# (Corpus/<target>/) is read, never written; new inputs libFuzzer keeps go to
# WORK_DIR/<target>/corpus. Exits non-zero when a target crashes, hangs (-timeout), trips ASan
# or UBSan, or stops before RUNS executions.
set -u
here=$(cd "$(dirname "$0")" && pwd)
if [ $# -lt 2 ]; then
  sed -n '2,13p' "$0" >&2
  exit 2
fi
bin=$1
work=$2
runs=${3:-1000000}
seconds=${4:-7200}
shift $(($# < 4 ? $# : 4))
targets=${*:-FuzzSceneFile FuzzMeshVoxelizer FuzzMediumValidator FuzzTransferFunctionMedium}

# A smaller quarantine and shorter allocation stacks than ASan's defaults: VTK's pipeline
# allocates thousands of small objects per execution, and with the defaults every execution
# faults in fresh pages (2x fewer executions per second). Use-after-free is still detected for
# the last 16 MB freed. Caller's ASAN_OPTIONS are appended and win.
export ASAN_OPTIONS="quarantine_size_mb=16:malloc_context_size=8:max_malloc_fill_size=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"

status=0
for target in $targets; do
  dir="$work/$target"
  mkdir -p "$dir/corpus"
  options=(-runs="$runs" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096
    -max_len=4096 -print_final_stats=1 -artifact_prefix="$dir/")
  if [ -f "$here/$target.dict" ]; then
    options+=(-dict="$here/$target.dict")
  fi
  start=$(date +%s)
  "$bin/$target" "${options[@]}" "$dir/corpus" "$here/Corpus/$target" > "$dir/log.txt" 2>&1
  rc=$?
  elapsed=$(($(date +%s) - start))
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log.txt" | tail -1)
  executions=${executions:-0}
  kept=$(find "$dir/corpus" -type f | wc -l)
  printf '%-28s %10s executions in %6d s (%s/s), %d new corpus inputs, exit %d\n' \
    "$target" "$executions" "$elapsed" "$((executions / (elapsed > 0 ? elapsed : 1)))" "$kept" "$rc"
  if [ "$rc" -ne 0 ]; then
    echo "  $target failed; the input is in $dir/ (crash-*, timeout-*, leak-*), the log:" >&2
    grep -E 'ERROR|SUMMARY|runtime error|contract broken' "$dir/log.txt" | head -5 >&2
    status=1
  elif [ "$executions" -lt "$runs" ]; then
    echo "  $target stopped after $executions of $runs executions (time bound $seconds s)" >&2
    status=1
  fi
done
exit $status
