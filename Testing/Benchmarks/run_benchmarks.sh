#!/usr/bin/env bash
# Runs every Refracta benchmark program on one OpenCL device, keeps each program's log and CSV
# under DIR and writes DIR/summary.md: one table, one row per headline quantity (issue #17).
# Needs bash, awk and coreutils' timeout only (no Python), so it also runs on a lent GPU machine.
#
# Usage: run_benchmarks.sh [--quick] [--device SEL] [--out DIR] [--bin DIR] [--only a,b,...]
#                          [--accuracy] [--timeout S] [--launcher CMD]
#   --quick     the ctest smoke sizes (seconds); without it each program's own default sizes.
#   --device    OpenCL device selection, exported as REFRACTA_OPENCL_DEVICE (what
#               vtkOpenCLContext reads): 'gpu', 'cpu', 'P:D' or part of a device name.
#   --out       directory for logs, CSVs and summary.md (default ./benchmark-results).
#   --bin       directory holding the benchmark executables (default: this build's bin).
#   --only      comma-separated subset of the program keys listed in PROGRAMS below.
#   --accuracy  also run the long accuracy programs (glass optics, accuracy/time, reference,
#               the photon-mapped reference's convergence).
#   --timeout   seconds each program may run (default 60 with --quick, 3600 without).
#   --launcher  command each program is run through, e.g. /tmp/b/gpu-env.sh on a lent GPU
#               machine (shared/tools/gpu/README.md); its device choice applies unless --device.
# The header's commit is $REFRACTA_COMMIT when set (a copy's git may be stale or absent: the lent
# GPU machine's is), else `git rev-parse` of this checkout.
# A program that fails or times out gets a FAILED row in the table; the script goes on.
set -u

quick=0 accuracy=0 device="" out="benchmark-results" bin="" only="" limit="" launcher=""
while [ $# -gt 0 ]; do
  case "$1" in
    --device | --out | --bin | --only | --timeout | --launcher)
      [ $# -ge 2 ] || { echo "run_benchmarks.sh: $1 needs a value" >&2; exit 2; } ;;
  esac
  case "$1" in
    --quick) quick=1 ;;
    --accuracy) accuracy=1 ;;
    --device) device="$2"; shift ;;
    --out) out="$2"; shift ;;
    --bin) bin="$2"; shift ;;
    --only) only="$2"; shift ;;
    --timeout) limit="$2"; shift ;;
    --launcher) launcher="$2"; shift ;;
    *) echo "run_benchmarks.sh: unknown option '$1' (valid: --quick --device SEL --out DIR" \
         "--bin DIR --only a,b --accuracy --timeout S --launcher CMD)" >&2; exit 2 ;;
  esac
  shift
done
[ -z "$limit" ] && { [ "$quick" = 1 ] && limit=60 || limit=3600; }
if [ -z "$bin" ]; then
  bin="$(cd "$(dirname "$0")/../../build/bin" 2>/dev/null && pwd)"
fi
if [ -z "$bin" ] || [ ! -d "$bin" ]; then
  echo "run_benchmarks.sh: no benchmark directory; pass --bin DIR (the build's bin/)" >&2
  exit 2
fi
bin="$(cd "$bin" && pwd)" # absolute: a launcher such as gpu-env.sh changes directory
[ -n "$device" ] && export REFRACTA_OPENCL_DEVICE="$device"
mkdir -p "$out" || exit 2
out="$(cd "$out" && pwd)"
rows="$out/rows.md"
: > "$rows"

# key | executable | quick arguments | full arguments ; @CSV@ becomes DIR/<key>.csv, @DIR@ DIR.
PROGRAMS="photon|BenchmarkPhotonTracer|--quick @CSV@|@CSV@
lattice|BenchmarkLatticeBoltzmann|--sizes 8 --repeats 1 --max-steps 64 --csv @CSV@|--csv @CSV@
table1|BenchmarkLatticeBoltzmann|--table1 8 --repeats 1 --csv @CSV@|--table1 64 --csv @CSV@
viewpass|BenchmarkViewPass|--sizes 32 --medium 24 --runs 1 --photons 4096 --compare-size 32 --csv @CSV@|--csv @CSV@
interactive|BenchmarkInteractive|--size 16 --photons 4096 --width 32 --height 24 --runs 1 --csv @CSV@|--runs 3 --csv @CSV@
surfaces|BenchmarkSurfaces|--quick --csv @CSV@|--csv @CSV@
singlescattering|BenchmarkSingleScattering|--sizes 24 --lights 1,8 --repeats 1 --max-photons 16384 --csv @CSV@|--csv @CSV@
voxelize|BenchmarkVoxelize|--sizes 16 --runs 1 --theta 24 --phi 12 --csv @CSV@|--csv @CSV@
illumination|BenchmarkIlluminationNetwork|--sizes 256 --directions 16 --frames 2 --csv @CSV@|--csv @CSV@
effectplan|BenchmarkEffectPlan|--size 12 --image 16 --photons 2048 --runs 1 --csv @CSV@|--csv @CSV@"
ACCURACY="glassoptics|BenchmarkGlassOptics|--quick|
glassshaft|BenchmarkGlassOptics|--quick --shaft|--shaft
glassedges|BenchmarkGlassEdges|--quick --samples 1,3 --reference 2 --runs 1|
accuracytime|BenchmarkAccuracyTime|--smoke --scenes glass-sphere-in-fog,grin-lens --out @DIR@/accuracytime|--out @DIR@/accuracytime
reference|RefractaReferenceBenchmark|--smoke --csv @CSV@|--csv @CSV@
referencepm|BenchmarkReferencePhotonMapper|--smoke --scenes glass-sphere-in-fog --csv @CSV@|--scenes glass-sphere-in-fog --csv @CSV@"
[ "$accuracy" = 1 ] && PROGRAMS="$PROGRAMS
$ACCURACY"

for key in ${only//,/ }; do
  printf '%s\n' "$PROGRAMS" | grep -q "^$key|" || {
    echo "run_benchmarks.sh: --only: unknown program '$key' (valid:" \
      $(printf '%s\n' "$PROGRAMS" | cut -d'|' -f1) ")" >&2
    exit 2
  }
done

row() { printf '| %s | %s | %s | %s |\n' "$1" "$2" "$3" "$4" >> "$rows"; }

# csvget FILE FILTER-COLUMN FILTER-VALUE COLUMN: COLUMN of the first row whose FILTER-COLUMN
# equals FILTER-VALUE (FILTER-COLUMN "" takes the first data row); empty when absent.
csvget() {
  awk -F, -v fc="$2" -v fv="$3" -v c="$4" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    (fc == "" || $(col[fc]) == fv) && (c in col) { print $(col[c]); exit }' "$1" 2>/dev/null
}

# Every row's value of column $2 (named in the header) of CSV $1.
csvcolumn() {
  awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    (c in col) { print $(col[c]) }' "$1" 2>/dev/null
}

# Each program's headline rows, read from its CSV (columns named in its header).
summarise() {
  local key="$1" csv="$2" v
  case "$key" in
    photon)
      v=$(awk -F, 'NR > 1 && $2 == "adaptive" { r = $4 / $8 } END { if (r) printf "%.4g", r }' "$csv")
      row BenchmarkPhotonTracer "marching voxel pieces/s (adaptive, largest photon count)" "${v:-n/a}" "pieces/s"
      v=$(awk -F, 'NR > 1 && $2 == "adaptive" { a = $4 / $8 } NR > 1 && $2 == "adaptive-lattice-order" { l = $4 / $8 } END { if (a && l) printf "%.3g", a / l }' "$csv")
      row BenchmarkPhotonTracer "coherent photon order: pieces/s over the lattice order (largest count)" "${v:-n/a}" "x" ;;
    lattice)
      v=$(csvcolumn "$csv" mlups | sort -g | awk '{ a[NR] = $1 } END { if (NR) print a[int((NR + 1) / 2)] }')
      row BenchmarkLatticeBoltzmann "lattice updates/s (median over rows)" "${v:-n/a}" "M updates/s"
      v=$(csvcolumn "$csv" ratio | sort -g | awk '{ a[NR] = $1 } END { if (NR) print a[int((NR + 1) / 2)] }')
      row BenchmarkLatticeBoltzmann "fraction of copy bandwidth (median over rows)" "${v:-n/a}" "-" ;;
    table1)
      v=$(csvget "$csv" schedule sequential total_s)
      row "BenchmarkLatticeBoltzmann --table1" "Table I sequential total" "${v:-n/a}" s
      c=$(csvget "$csv" schedule "sequential cold start" total_s)
      r=$(awk -v a="$c" -v b="$v" 'BEGIN { if (a > 0 && b > 0) print a / b }')
      row "BenchmarkLatticeBoltzmann --table1" "Table I sequential: cold start / coarse start time" "${r:-n/a}" x
      v=$(awk -F, 'NR > 1 && $2 == "interleaved" && (m == "" || $4 < m) { m = $4 } END { print m }' "$csv")
      row "BenchmarkLatticeBoltzmann --table1" "Table I best interleaved total" "${v:-n/a}" s ;;
    viewpass)
      # The device's default kernel: the eight lanes where they ran (CPU devices), else the
      # general kernel; and the lanes' gain over the general kernel in the same run.
      v=$(awk -F, '$1 == "view pass" && $2 ~ /^curved/ && $4 == "off" { m[$2] = m[$2] ? m[$2] : $6 }
        END { print m["curved; 8 lanes"] ? m["curved; 8 lanes"] : m["curved; general kernel"] }' "$csv")
      row BenchmarkViewPass "curved view pass median (first image size)" "${v:-n/a}" ms
      v=$(awk -F, '$1 == "view pass" && $2 ~ /^curved/ && $4 == "off" { m[$2] = m[$2] ? m[$2] : $6 }
        END { if (m["curved; 8 lanes"] && m["curved; general kernel"])
                printf "%.3g", m["curved; general kernel"] / m["curved; 8 lanes"] }' "$csv")
      row BenchmarkViewPass "curved view pass: 8 lanes over the general kernel (first image size)" \
        "${v:-n/a (no lanes on this device)}" "x"
      v=$(awk -F, '$2 ~ /^refracta straight/ && $NF != "-" && $NF != "" { r = $NF } END { print r }' "$csv")
      row BenchmarkViewPass "vtkFixedPointVolumeRayCastMapper time / view pass time" \
        "${v:-n/a (no render window)}" "x" ;;
    interactive)
      v=$(csvget "$csv" interaction "camera move" persistent_s)
      row BenchmarkInteractive "camera-move frame (persistent pipeline)" "${v:-n/a}" s
      v=$(csvget "$csv" interaction "light move" persistent_s)
      row BenchmarkInteractive "relight frame (persistent pipeline)" "${v:-n/a}" s ;;
    surfaces)
      v=$(csvget "$csv" "" "" device_Mrays_s)
      row BenchmarkSurfaces "BVH rays on the device" "${v:-n/a}" "M rays/s" ;;
    singlescattering)
      v=$(csvget "$csv" lights 8 speedup)
      row BenchmarkSingleScattering "interpolated vs light rays speed-up (8 lights)" "${v:-n/a}" "x" ;;
    voxelize)
      v=$(awk -F, 'NR > 1 && $2 == "near-surface" { t = $10 } END { print t }' "$csv")
      row BenchmarkVoxelize "voxelize total (largest grid, near-surface)" "${v:-n/a}" s ;;
    illumination)
      v=$(awk -F, 'NR > 1 { f = $5 } END { print f }' "$csv")
      row BenchmarkIlluminationNetwork "frames/s (last N, D)" "${v:-n/a}" "frames/s" ;;
    referencepm)
      v=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
        { e = $(col["efficiency vs first collision"]) }
        e != "-" && e + 0 > best { best = e + 0 } END { if (best) print best }' "$csv")
      row BenchmarkReferencePhotonMapper "photon-mapped truth: efficiency of gathering along the ray vs one gather (best spacing)" "${v:-n/a}" "x" ;;
    effectplan)
      v=$(csvget "$csv" scene glass-sphere-in-fog "planned s")
      row BenchmarkEffectPlan "default scene (glass-sphere-in-fog) planned render" "${v:-n/a}" s ;;
    *) row "$3" "completed" "yes" "-" ;;
  esac
}

started=$(date -u '+%Y-%m-%d %H:%M UTC')
while IFS='|' read -r key exe qargs fargs; do
  [ -z "$key" ] && continue
  if [ -n "$only" ] && ! printf ',%s,' "$only" | grep -q ",$key,"; then continue; fi
  args="$fargs"; [ "$quick" = 1 ] && args="$qargs"
  csv="$out/$key.csv"
  args="${args//@CSV@/$csv}"; args="${args//@DIR@/$out}"
  log="$out/$key.log"
  rm -f "$csv"
  echo "== $key: $exe $args"
  t0=$(date +%s.%N)
  # shellcheck disable=SC2086 # the argument lists above are word lists on purpose
  timeout "$limit" $launcher "$bin/$exe" $args > "$log" 2>&1
  rc=$?
  t1=$(date +%s.%N)
  wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
  if [ "$rc" -ne 0 ]; then
    why="exit $rc"; [ "$rc" -eq 124 ] && why="timed out after ${limit} s"
    [ "$rc" -eq 127 ] && why="not found in $bin"
    row "$exe" "FAILED ($why), see $key.log" "-" "-"
    echo "   FAILED ($why)"
  elif [ -f "$csv" ] || [ "$key" = glassoptics ] || [ "$key" = glassshaft ] || [ "$key" = glassedges ] ||
    [ "$key" = accuracytime ]; then
    summarise "$key" "$csv" "$exe"
  else
    row "$exe" "FAILED (no CSV written), see $key.log" "-" "-"
  fi
  echo "   $wall s"
done <<< "$PROGRAMS"

devname=$(grep -h -m1 -i '^device: ' "$out/lattice.log" "$out"/*.log 2>/dev/null | head -n1 | sed 's/^[Dd]evice: //')
commit="${REFRACTA_COMMIT:-$(git -C "$(dirname "$0")" rev-parse --short HEAD 2>/dev/null || echo unknown)}"
selection="${REFRACTA_OPENCL_DEVICE:-default}"
[ -z "${REFRACTA_OPENCL_DEVICE:-}" ] && [ -n "$launcher" ] && selection="the launcher's ($launcher)"
sizes="program defaults"; [ "$quick" = 1 ] && sizes="--quick (smoke sizes, not a speed claim)"
{
  echo "# Refracta benchmarks"
  echo
  echo "- device: ${devname:-unknown} (selection: $selection)"
  echo "- date: $started; commit: $commit; sizes: $sizes"
  echo
  echo "| program | quantity | value | unit |"
  echo "|---|---|---|---|"
  cat "$rows"
} > "$out/summary.md"
rm -f "$rows"
cat "$out/summary.md"
