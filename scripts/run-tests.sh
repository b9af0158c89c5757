#!/usr/bin/env bash
# README command 2, also what CI runs (.ci/run). Runs every test stage of VoxelBRep:
#
#   deps  scripts/install-deps.sh (skips what is installed; no network needed then)
#   A     primary build against ParaView 5.11's VTK 9.2 in `build` (module, Python package,
#         ParaView plugin, tests): xvfb-run -a ctest
#   B     one sanitizer build (AddressSanitizer + UndefinedBehaviorSanitizer) in `build-asan`
#         against ParaView's VTK (Debug, -O1): the VTK-free core's unit tests, the module's C++
#         filter tests, and the hostile-input corpus (Testing/Python) through its Python package
#   C     build against Debian's stock VTK 9.1 in `build-vtk91` (plugin, Python wrapping and
#         the core's unit tests off: the core uses no VTK, stages A and B run them):
#         xvfb-run -a ctest
#
# Stage C needs libvtk9-dev, which conflicts with python3-paraview: the stage swaps the two
# packages, configures and builds, swaps them back at once (the VTK 9.1 runtime libraries,
# package libvtk9.1, stay installed, so the built tests still run) and then runs the tests.
# The restore also runs from an EXIT trap, whatever fails, and is verified afterwards
# (dpkg state, `import paraview`, `pvpython --version`). While the packages are swapped,
# ParaView builds and pvpython/pvbatch on this machine do not work.
#
# A failing stage makes the script exit non-zero; the later stages still run. A summary of
# the stages with their durations is printed at the end.
#
# Environment:
#   VOXELBREP_JOBS=N          build and ctest parallelism (default 2)
#   VOXELBREP_STAGES="deps A B C"  the stages to run (default: all; the others are skipped)
#   VOXELBREP_SKIP_VTK91=1    skip stage C (e.g. while others build against ParaView here)
#   VOXELBREP_REQUIRE_VTK91=1 fail (instead of skip) when the VTK 9.1 packages cannot be
#                             downloaded
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
ROOT=$PWD
JOBS=${VOXELBREP_JOBS:-2}
LOGDIR=$(mktemp -d "${TMPDIR:-/tmp}/voxelbrep-tests.XXXXXX")
VTK91_DIR=/usr/lib/x86_64-linux-gnu/cmake/vtk-9.1
PV_VTK_DIR=/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11/vtk
# -noreset: by default Xvfb resets when its last client disconnects, and a test that
# connects during the reset fails with "bad X server connection" (seen in CI).
XVFB=(xvfb-run -a -s "-noreset -screen 0 1280x1024x24")
SAN_FLAGS="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"

export DEBIAN_FRONTEND=noninteractive
SUDO=()
if [ "$(id -u)" -ne 0 ]; then SUDO=(sudo); fi
apt_get() {
  "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get -q -o DPkg::Lock::Timeout=600 "$@"
}
is_installed() {
  [ "$(dpkg-query -W -f='${db:Status-Abbrev}' "$1" 2>/dev/null)" = "ii " ]
}
run() {
  echo "+ $*"
  "$@"
}
fmt_time() { printf '%dm%02ds' $(($1 / 60)) $(($1 % 60)); }

# ---- ctest with counting ----------------------------------------------------------------
TESTS_PASSED=0
TESTS_FAILED=0
# run_ctest DIR LABEL [WRAPPER...] [-- CTEST_ARGS...]: runs ctest in DIR, adds its counts to
# the totals.
run_ctest() {
  local dir=$1 label=$2
  shift 2
  local wrapper=() args=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do
    wrapper+=("$1")
    shift
  done
  [ $# -gt 0 ] && shift
  args=("$@")
  local log="$LOGDIR/ctest-$label.log" rc line failed total
  echo "+ (cd $dir && ${wrapper[*]} ctest --output-on-failure -j$JOBS ${args[*]})"
  (cd "$dir" && "${wrapper[@]}" ctest --output-on-failure -j"$JOBS" "${args[@]}") 2>&1 | tee "$log"
  rc=${PIPESTATUS[0]}
  line=$(grep -E '^[0-9]+% tests passed, [0-9]+ tests? failed out of [0-9]+' "$log" | tail -n 1)
  if [ -n "$line" ]; then
    failed=$(sed -E 's/.* ([0-9]+) tests? failed out of.*/\1/' <<<"$line")
    total=$(sed -E 's/.*failed out of ([0-9]+).*/\1/' <<<"$line")
    TESTS_PASSED=$((TESTS_PASSED + total - failed))
    TESTS_FAILED=$((TESTS_FAILED + failed))
  elif grep -q 'No tests were found' "$log"; then
    echo "note: no tests in $dir"
  fi
  return "$rc"
}

# ---- stages -----------------------------------------------------------------------------
stage_deps() {
  run bash scripts/install-deps.sh
}

stage_paraview() {
  run cmake -S . -B build -DPython3_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release \
    -DBUILD_TESTING=ON -DVOXELBREP_BUILD_PARAVIEW_PLUGIN=ON || return 1
  run cmake --build build -j"$JOBS" || return 1
  # The top-level CMakeLists.txt silently drops the plugin when ParaView is not found: the
  # primary build must have it.
  if [ ! -f build/lib/paraview-5.11/plugins/VoxelBRep/VoxelBRep.so ]; then
    echo "error: the ParaView plugin was not built (is paraview-dev installed?)" >&2
    return 1
  fi
  run_ctest build paraview "${XVFB[@]}"
}

stage_asan() {
  local ok=0
  # One build serves both: the core (with its unit tests) and the VTK module are compiled once,
  # against ParaView's VTK. -O1: CGAL's exact arithmetic at -O0 under the sanitizers takes
  # minutes per test. Line tables only (-g1, enough for the reports' stacks); the core tests'
  # sources that build exact references on CGAL and Qhull are compiled plain: instrumented
  # with full debug information, they took most of the stage's 12-minute build. CGAL_NDEBUG:
  # CGAL 5.5's own assertions off (ours stay on). With them on, corefine_and_compute_difference
  # never returns on some valid closed operands (a 16-vertex H and a 6-vertex prism of a thin
  # torus's handle cut loop in append_patches_to_triangle_mesh) where the same call built with
  # them off returns false at once, as in every Release build.
  run cmake -S . -B build-asan -DVTK_DIR="$PV_VTK_DIR" \
    -DPython3_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 \
    "-DVOXELBREP_REFERENCE_COMPILE_OPTIONS=-fno-sanitize=all;-g0" -DBUILD_TESTING=ON \
    -DVOXELBREP_CORE_ONLY=OFF -DVOXELBREP_BUILD_CORE_TESTS=ON \
    -DVOXELBREP_BUILD_PARAVIEW_PLUGIN=OFF -DVOXELBREP_WRAP_PYTHON=ON \
    -DVOXELBREP_BUILD_BENCHMARKS=OFF "-DCMAKE_CXX_FLAGS=-O1 -DCGAL_NDEBUG $SAN_FLAGS" || return 1
  # The test programs and the Python package; not the example programs (never run here).
  run cmake --build build-asan -j"$JOBS" --target VoxelBRepCoreTests VoxelBRepFiltersCxxTests \
    VoxelBRepFiltersPython || return 1
  # The core's unit tests, with leak detection (they use no VTK). The largest exact-geometry
  # tests (a self-intersection search on porous blobs, the hull modifier's 72 hollow balls
  # with off-centre tunnels and its larger real objects (over 5 minutes each here), its
  # noise cubes and the full aneurism's independent check (34 s in stage A, over 10 minutes
  # and 7 GB here), the face octree's
  # closed-surface checks of every label of random label maps and its CSG solids and porous
  # blobs at 64^3: a minute or more each here) are left out; stage A runs them. The hull
  # modifier's handle cuts, joins, components apart, random volumes, blobs and real objects
  # run here (5 to 50 s each).
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1} \
    UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    run_ctest build-asan asan-core -- -R "^Core[.]" -E "NetDoesNotSelfIntersect|HollowBallsWithOffCentreTunnels|LargerRealObjectsSeparate|CubesAndCSGAt64|FaceOctreeBoundary.PorousBlobs|RandomNoiseCubesSeparate|FullAneurismSeparates|EachLabelsNetIsClosedManifold|EachLabelsBoundaryIsClosedManifold" || ok=1
  # The module's C++ filter tests. Leak detection is off (VTK's and Mesa's singletons live
  # until exit) and the image tests are left out (Mesa's llvmpipe raises SIGFPE under the
  # sanitizers' floating-point settings, in its own code).
  ASAN_OPTIONS=detect_leaks=0:strict_string_checks=1 \
    UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    run_ctest build-asan asan-filters "${XVFB[@]}" -- -E "^Core[.]|Render|^Python[.]|^Example" ||
    ok=1
  # The hostile-input corpus through the sanitized Python package: the sanitizer runtimes
  # preloaded into /usr/bin/python3 (the memory-limit cases cannot run there: the sanitizers
  # reserve far more address space than any ulimit -v leaves).
  run_sanitized_corpus || ok=1
  return $ok
}

run_sanitized_corpus() {
  local log="$LOGDIR/asan-corpus.log" rc
  echo "+ (sanitized) Testing/Python/TestHostileInputs.py"
  LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
    ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    PYTHONPATH="$ROOT/build-asan/lib/python3/dist-packages" \
    /usr/bin/python3 Testing/Python/TestHostileInputs.py 2>&1 | tee "$log"
  rc=${PIPESTATUS[0]}
  if [ "$rc" = 0 ]; then
    TESTS_PASSED=$((TESTS_PASSED + 1))
  else
    TESTS_FAILED=$((TESTS_FAILED + 1))
  fi
  return "$rc"
}

PV_DEB_DIR="$LOGDIR/debs"
SWAPPED=0
RESTORE_STATUS="not needed"
# Puts python3-paraview back and removes libvtk9-dev/python3-vtk9. Idempotent; called from
# stage C right after its build and from the EXIT trap.
restore_paraview() {
  [ "$SWAPPED" = 1 ] || return 0
  # Not to be interrupted half-way (apt and dpkg inherit the ignored signals too).
  trap '' INT TERM HUP
  echo "======== restoring python3-paraview ========"
  local good=1 deb
  if ! apt_get install -y python3-paraview libvtk9-dev- python3-vtk9-; then
    # Without network: the .deb saved before the swap.
    deb=$(ls "$PV_DEB_DIR"/python3-paraview_*.deb 2>/dev/null | head -n 1)
    if [ -n "$deb" ]; then
      apt_get install -y "$deb" libvtk9-dev- python3-vtk9- || good=0
    else
      good=0
    fi
  fi
  is_installed python3-paraview || good=0
  is_installed libvtk9-dev && good=0
  is_installed python3-vtk9 && good=0
  /usr/bin/python3 -c "import paraview" || good=0
  pvpython --version || good=0
  if [ "$good" = 1 ]; then
    SWAPPED=0
    RESTORE_STATUS=PASS
    echo "restore: python3-paraview installed, libvtk9-dev removed, 'import paraview' works"
  else
    RESTORE_STATUS=FAIL
    echo "RESTORE FAILED: run 'apt-get install -y python3-paraview libvtk9-dev- python3-vtk9-'" >&2
  fi
  trap 'exit 130' INT TERM HUP
}

stage_vtk91() {
  if [ "${VOXELBREP_SKIP_VTK91:-0}" = 1 ]; then
    echo "skipped: VOXELBREP_SKIP_VTK91=1"
    return 77
  fi
  # Download everything both swaps need before removing anything.
  if ! apt_get install -y --download-only libvtk9-dev python3-paraview-; then
    apt_get update
    if ! apt_get install -y --download-only libvtk9-dev python3-paraview-; then
      echo "stock VTK 9.1 packages (libvtk9-dev) cannot be downloaded" >&2
      [ "${VOXELBREP_REQUIRE_VTK91:-0}" = 1 ] && return 1
      return 77
    fi
  fi
  mkdir -p "$PV_DEB_DIR"
  if is_installed python3-paraview; then
    local version arch
    version=$(dpkg-query -W -f='${Version}' python3-paraview)
    arch=$(dpkg-query -W -f='${Architecture}' python3-paraview)
    apt_get install -y --reinstall --download-only python3-paraview ||
      echo "warning: cannot download python3-paraview; relying on apt's cache" >&2
    cp "/var/cache/apt/archives/python3-paraview_${version//:/%3a}_${arch}.deb" \
      "$PV_DEB_DIR/" 2>/dev/null ||
      echo "warning: no python3-paraview .deb saved; the restore needs apt" >&2
  fi

  SWAPPED=1
  if ! run apt_get install -y libvtk9-dev python3-paraview-; then
    restore_paraview
    return 1
  fi
  local ok=1
  run cmake -S . -B build-vtk91 -DVTK_DIR="$VTK91_DIR" -DPython3_EXECUTABLE=/usr/bin/python3 \
    -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON -DVOXELBREP_BUILD_PARAVIEW_PLUGIN=OFF \
    -DVOXELBREP_WRAP_PYTHON=OFF -DVOXELBREP_BUILD_CORE_TESTS=OFF 2>&1 |
    tee "$LOGDIR/configure-vtk91.log"
  [ "${PIPESTATUS[0]}" = 0 ] || ok=0
  if [ "$ok" = 1 ] && ! grep -q 'building against VTK 9\.1' "$LOGDIR/configure-vtk91.log"; then
    echo "error: build-vtk91 is not configured against VTK 9.1" >&2
    ok=0
  fi
  if [ "$ok" = 1 ]; then
    run cmake --build build-vtk91 -j"$JOBS" 2>&1 | tee "$LOGDIR/build-vtk91.log"
    [ "${PIPESTATUS[0]}" = 0 ] || ok=0
  fi
  # Swap back before testing: the tests only need the VTK 9.1 runtime libraries.
  restore_paraview
  [ "$ok" = 1 ] || return 1
  run_ctest build-vtk91 vtk91 "${XVFB[@]}"
}

# ---- driver -----------------------------------------------------------------------------
trap restore_paraview EXIT
trap 'exit 130' INT TERM HUP

STAGE_IDS=()
STAGE_DESCS=()
STAGE_RESULTS=()
STAGE_TIMES=()
FAILED=0
run_stage() {
  local id=$1 desc=$2 fn=$3 start=$SECONDS rc result
  echo
  echo "======== stage $id: $desc ========"
  if [[ " ${VOXELBREP_STAGES:-deps A B C} " == *" $id "* ]]; then
    "$fn"
    rc=$?
  else
    echo "skipped: not in VOXELBREP_STAGES"
    rc=77
  fi
  case $rc in
  0) result=PASS ;;
  77) result=SKIP ;;
  *) result=FAIL FAILED=1 ;;
  esac
  echo "======== stage $id: $result ($(fmt_time $((SECONDS - start)))) ========"
  STAGE_IDS+=("$id")
  STAGE_DESCS+=("$desc")
  STAGE_RESULTS+=("$result")
  STAGE_TIMES+=($((SECONDS - start)))
}

TOTAL_START=$SECONDS
run_stage deps "install Debian packages" stage_deps
run_stage A "ParaView 5.11 / VTK 9.2 build + tests (build)" stage_paraview
run_stage B "core and module with ASan+UBSan (build-asan)" stage_asan
run_stage C "stock Debian VTK 9.1 build + tests (build-vtk91)" stage_vtk91
restore_paraview
[ "$RESTORE_STATUS" = FAIL ] && FAILED=1

echo
echo "======================== VoxelBRep test summary ========================"
for i in "${!STAGE_IDS[@]}"; do
  printf '  %-5s %-52s %-5s %8s\n' "${STAGE_IDS[$i]}" "${STAGE_DESCS[$i]}" \
    "${STAGE_RESULTS[$i]}" "$(fmt_time "${STAGE_TIMES[$i]}")"
done
printf '  %-5s %-52s %-5s\n' "" "restore python3-paraview after stage C" "$RESTORE_STATUS"
printf '  %-5s %-52s %-5s %8s\n' "" "total" "$([ $FAILED = 0 ] && echo PASS || echo FAIL)" \
  "$(fmt_time $((SECONDS - TOTAL_START)))"
echo "  logs: $LOGDIR"
echo "tests: $TESTS_PASSED passed, $TESTS_FAILED failed"
exit "$FAILED"
