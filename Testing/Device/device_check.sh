#!/usr/bin/env bash
# The device side of Testing/Device/prepare.sh: on a lent GPU machine, from the checkout's root,
# with .gpu/ carried. Runs the issue-17 measurements (relight and camera move at 1024^2 with a
# kernel profile and the transfer rates, the light move with the lighting volume handed on
# through the host, without the lattice's coarse start and with its warm start, Table I at 128^3
# fresh and persistent, D3Q18's lattice step, run_benchmarks.sh's table) and then the default
# test suite on
# the GPU. Writes $OUT/log.txt (everything printed), $OUT/bench.tgz and $OUT/tests.tgz. Each step
# is bounded: the limits sum to 560 s, inside the device call's 570 s.
set -u
root=$PWD
gpu="$root/.gpu"
exec > >(tee -a "$OUT/log.txt") 2>&1
mkdir -p /tmp/b /tmp/results /tmp/tests && tar -C /tmp/b -xzf "$gpu/bundle.tar.gz"
# The tests and kernels were built with this checkout's absolute paths.
src=$(cat "$gpu/source_dir")
[ -e "$src" ] || { mkdir -p "$(dirname "$src")" && ln -s "$root" "$src"; }
G=/tmp/b/gpu-env.sh R=/tmp/results
step() { # name seconds command...: runs a program of the bundle, its output in $R/name.txt
  local name="$1" limit="$2"; shift 2
  echo "== $name ($(date -u +%T))"
  timeout "$limit" "$G" "$@" > "$R/$name.txt" 2>&1
  echo "   rc=$?"
}
nvidia-smi -L
step devices 20 bin/refracta-render --list-devices
step interactive1024 80 bin/BenchmarkInteractive --width 1024 --height 1024 --runs 3 --profile \
  --persistent-only --transfers --csv $R/interactive1024.csv
grep -E "transfers|^\| +(camera|light|material|full)" $R/interactive1024.txt
# The light move with the lighting volume handed on through the host (the A/B of session 18's
# device hand-off; the warm start's A/B ran on an H200 in session 14: no change then).
step interactive1024-host-hand-off 40 bin/BenchmarkInteractive --width 1024 --height 1024 \
  --runs 3 --persistent-only --only light --host-hand-off --profile \
  --csv $R/interactive1024-host-hand-off.csv
grep -E "^\| +light|^\| \[(read|write)\]" $R/interactive1024-host-hand-off.txt
# The light move without the lattice's coarse start (the A/B of session 17's default).
step interactive1024-cold-lattice 40 bin/BenchmarkInteractive --width 1024 --height 1024 \
  --runs 3 --persistent-only --only light --cold-lattice --csv $R/interactive1024-cold.csv
grep -E "^\| +light" $R/interactive1024-cold-lattice.txt
# The light move with the lattice's warm start and its coarse correction (session 19; off by
# default: on the CPU photon noise kept it from helping at 65536 photons).
step interactive1024-warm 30 bin/BenchmarkInteractive --width 1024 --height 1024 \
  --runs 3 --persistent-only --only light --warm-start --csv $R/interactive1024-warm.csv
grep -E "^\| +light" $R/interactive1024-warm.txt
export REFRACTA_PROFILE_KERNELS=1
step table1-128 50 bin/BenchmarkLatticeBoltzmann --table1 128 --repeats 3 --csv $R/table1-128.csv
step table1-128-persistent 50 bin/BenchmarkLatticeBoltzmann --table1 128 --repeats 3 --persistent \
  --csv $R/table1-128-persistent.csv
unset REFRACTA_PROFILE_KERNELS
grep -hE "^\| (sequential|interleaved)|^Persistent" $R/table1-128.txt $R/table1-128-persistent.txt
# D3Q18's step (the plan's lattice for mean |g| >= 0.6 since session 31, never measured on a GPU;
# its step reads the state twice, which the CPU gained from) beside D3Q6's global update.
step lattice-q18 20 bin/BenchmarkLatticeBoltzmann --sizes 128 --repeats 3 --global-only \
  --lattices 6,18 --max-steps 200 --csv $R/lattice-q18.csv
grep -E "^\| 128" $R/lattice-q18.txt
echo "== run_benchmarks.sh ($(date -u +%T))"
REFRACTA_COMMIT=$(cat "$gpu/commit") timeout 120 bash Testing/Benchmarks/run_benchmarks.sh \
  --launcher $G --bin /tmp/b/bin --out $R/all --timeout 30 > $R/run_benchmarks.txt 2>&1
cat $R/all/summary.md
tar -C /tmp -czf "$OUT/bench.tgz" results
echo "== tests ($(date -u +%T))"
timeout 110 "$G" bash "$gpu/run_device_tests.sh" "$gpu/tests.txt" /tmp/b/bin /tmp/tests 6 \
  > $R/tests.txt 2>&1
echo "$(grep -c ' rc=0 ' $R/tests.txt) of $(wc -l < "$gpu/tests.txt") tests passed"
grep -v ' rc=' $R/tests.txt # what the runner itself printed (e.g. no NVIDIA driver)
for t in $(grep ' rc=' $R/tests.txt | grep -v ' rc=0 ' | awk '{ print $1 }'); do
  echo "---- $t"
  grep -E "Failure|Which is|Expected|FAILED|ERR|rror|drift" /tmp/tests/$t.log | head -12
done
cp $R/tests.txt /tmp/tests/summary.txt
tar -C /tmp -czf "$OUT/tests.tgz" tests
echo "== done ($(date -u +%T))"
