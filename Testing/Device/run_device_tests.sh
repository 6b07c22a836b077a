#!/usr/bin/env bash
# On the device, under gpu-env.sh (its OpenCL environment exported): runs every test of LIST
# (name<TAB>command, from list_device_tests.py), the refracta-render scenes first and in order
# (later tests read their outputs), the rest PARALLEL at a time, each bounded by timeout and with
# its own kernel cache. One log per test in LOGDIR; one line per test on stdout: name rc=N secs.
# usage: run_device_tests.sh LIST BIN LOGDIR [PARALLEL]
list="$1" bin="$2" logs="$3" parallel="${4:-6}"
mkdir -p "$logs" /tmp/refracta-test-kernels
sed "s#@BIN@#$bin#g" "$list" > "$logs/.list"
export logs
one() {
  local line name command start rc
  line=$(sed -n "${1}p" "$logs/.list")
  name=${line%%$'\t'*} command=${line#*$'\t'}
  start=$(date +%s.%N)
  REFRACTA_KERNEL_CACHE_DIR=/tmp/refracta-test-kernels/$name timeout 150 bash -c "$command" \
    > "$logs/$name.log" 2>&1
  rc=$?
  echo "$name rc=$rc $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s"
}
export -f one
total=$(wc -l < "$logs/.list")
fixtures=$(grep -c $'\t.*refracta-render' "$logs/.list")
for i in $(seq 1 "$fixtures"); do one "$i"; done
seq $((fixtures + 1)) "$total" | xargs -P "$parallel" -I{} bash -c 'one {}'
