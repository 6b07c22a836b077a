#!/usr/bin/env bash
# Refracta's set-up, build, render and test entry point (idempotent).
#
#   ./refracta.sh render [refracta-render args...]   install what is missing, build, render
#   ./refracta.sh test                               install what is missing, build, run ctest
#   ./refracta.sh build                              install what is missing, build
#   ./refracta.sh sanitize                           build in build-asan with AddressSanitizer and
#                                                    UndefinedBehaviorSanitizer, run the C++ tests
#   ./refracta.sh fuzz [TARGET...]                   build the libFuzzer targets in build-fuzz (clang,
#                                                    ASan, UBSan) and run each RUNS times (default 1e6,
#                                                    at most FUZZ_SECONDS, default 7200, per target)
#
# Environment: BUILD_DIR (default ./build), JOBS (default: number of cores),
# CTEST_ARGS (extra arguments for ctest, e.g. "-L long" or "-LE long").
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build_dir="${BUILD_DIR:-$here/build}"
jobs="${JOBS:-$(nproc)}"

# Debian bookworm packages the project needs to build and test.
packages=(
  build-essential cmake pkg-config
  # ParaView 5.11's VTK 9.2 (python3-paraview conflicts with Debian's libvtk9-dev/python3-vtk9);
  # its CMake configuration needs the Qt 5 development files and the proxy-documentation tools.
  paraview-dev python3-paraview python3-numpy
  qtbase5-dev qttools5-dev libqt5svg5-dev libqt5opengl5-dev qtxmlpatterns5-dev-tools
  # Third-party libraries ParaView's VTK CMake package links its modules against.
  libopenmpi-dev libutfcpp-dev libglew-dev liblz4-dev libdouble-conversion-dev libtiff-dev
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers clinfo
  libcgal-dev libgmp-dev libmpfr-dev libglm-dev
  libosmesa6-dev libx11-dev xvfb xauth
  libgtest-dev libbenchmark-dev
  nlohmann-json3-dev
  # Fuzzing (./refracta.sh fuzz): clang's libFuzzer.
  clang
)

install_missing_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "refracta: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

build() {
  install_missing_packages
  if [ ! -f "$build_dir/CMakeCache.txt" ]; then
    cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@"
  fi
  cmake --build "$build_dir" -j "$jobs"
}

# Kernel caches inside the build tree: results and timings never depend on a warm home directory.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$build_dir/pocl-cache}"

command="${1:-}"
[ $# -gt 0 ] && shift
case "$command" in
  build)
    build
    ;;
  render)
    build
    "$build_dir/bin/refracta-render" "$@"
    ;;
  test)
    build
    # Render-window tests need an X server: Debian's VTK is an X11 build, so run the suite under
    # a virtual framebuffer (Mesa's software rasterizer) when no display is present.
    runner=()
    if [ -z "${DISPLAY:-}" ]; then
      runner=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")
    fi
    cd "$build_dir"
    # shellcheck disable=SC2086
    "${runner[@]}" ctest --output-on-failure -j "$jobs" ${CTEST_ARGS:--LE long}
    ;;
  sanitize)
    # Host code instrumented; kernels run inside PoCL's own (uninstrumented) code. Leak checking is
    # off because the OpenCL ICD loader and PoCL keep allocations alive until exit by design.
    # Python tests are excluded: Debian's interpreter is not built with the sanitizers.
    build_dir="${BUILD_DIR:-$here/build-asan}"
    build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DREFRACTA_SANITIZE=address,undefined \
      -DREFRACTA_WRAP_PYTHON=OFF
    export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:${ASAN_OPTIONS:-}"
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
    runner=()
    if [ -z "${DISPLAY:-}" ]; then
      runner=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")
    fi
    cd "$build_dir"
    # shellcheck disable=SC2086
    "${runner[@]}" ctest --output-on-failure -j "$jobs" ${CTEST_ARGS:--LE long}
    ;;
  fuzz)
    # Documentation/Developing.md, "Fuzzing": every Refracta library instrumented for libFuzzer's
    # coverage, ASan and UBSan; the runs, their corpora and any crash input go to
    # build-fuzz/Testing/fuzz-runs/<target>/.
    install_missing_packages
    build_dir="${BUILD_DIR:-$here/build-fuzz}"
    if [ ! -f "$build_dir/CMakeCache.txt" ]; then
      cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
        -DCMAKE_CXX_COMPILER=clang++ -DREFRACTA_FUZZ=ON -DREFRACTA_WRAP_PYTHON=OFF \
        -DREFRACTA_BUILD_BENCHMARKS=OFF
    fi
    cmake --build "$build_dir" -j "$jobs" --target refracta-fuzzers
    "$here/Testing/Fuzz/run_fuzzers.sh" "$build_dir/bin" "$build_dir/Testing/fuzz-runs" \
      "${RUNS:-1000000}" "${FUZZ_SECONDS:-7200}" "$@"
    ;;
  *)
    echo "usage: $0 {render|test|build|sanitize|fuzz} [args...]" >&2
    exit 2
    ;;
esac
