#!/usr/bin/env bash
# The unit and GL integration tests (ctest labels unit and gl, not slow),
# built with AddressSanitizer + UndefinedBehaviorSanitizer in a tree of
# their own ($SANITIZE_BUILD, kept between runs so a second run rebuilds
# only what changed): a Debug tree, so assert() stays in, compiled at -O1
# (DM_SANITIZE in the top-level CMakeLists.txt).  Any sanitizer report
# fails the test that triggered it, and so the ctest test that ran it.
#
#   sanitize.sh build          configure the tree and build only the test
#                              binaries the sanitizer run needs (and what
#                              they depend on), not every target
#   sanitize.sh run CTEST...   run a share of them there, one at a time:
#                              CTEST selects it (e.g. -L '^unit$'); the
#                              shares of tests/sanitize.cmake cover every
#                              selected test exactly once
set -euo pipefail
SRC=${DMBENCH_SOURCE_DIR:?}
BUILD=${SANITIZE_BUILD:?}
SELECT=(-L '^(unit|gl)$' -LE '^slow$')
case ${1:-} in
build)
  launcher=()
  [ -n "${SANITIZE_LAUNCHER:-}" ] &&
    launcher=(-DCMAKE_C_COMPILER_LAUNCHER="$SANITIZE_LAUNCHER" -DCMAKE_CXX_COMPILER_LAUNCHER="$SANITIZE_LAUNCHER")
  # Ninja when it is installed: make's per-target dependency steps cost
  # about 13 s of CPU more for this tree (docs/testing.md).  A tree kept
  # from a run with the other generator is removed (CMake cannot switch a
  # tree's generator).
  gen="Unix Makefiles"
  command -v ninja > /dev/null && gen=Ninja
  if [ -f "$BUILD/CMakeCache.txt" ] && ! grep -qx "CMAKE_GENERATOR:INTERNAL=$gen" "$BUILD/CMakeCache.txt"; then
    echo "removing $BUILD: configured with another generator than $gen"
    rm -rf "$BUILD"
  fi
  cmake -S "$SRC" -B "$BUILD" -G "$gen" -DDM_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug "${launcher[@]}" \
    > "$BUILD.cmake.log" 2>&1 || { cat "$BUILD.cmake.log"; exit 1; }
  # Each unit or GL test is the executable of the same name (tests/CMakeLists.txt).
  mapfile -t targets < <(cd "$BUILD" && ctest -N "${SELECT[@]}" | sed -n 's/^ *Test *#[0-9]*: //p')
  [ "${#targets[@]}" -ge 40 ] || { echo "only ${#targets[@]} unit and GL tests found in $BUILD"; exit 1; }
  echo "building ${#targets[@]} test binaries with ASan + UBSan in $BUILD"
  # One goal, dm_sanitize_tests (tests/CMakeLists.txt), so make builds them
  # side by side; its list must be the tests ctest selects.
  diff <(sort "$BUILD/sanitize-tests.txt") <(printf '%s\n' "${targets[@]}" | sort) ||
    { echo "dm_sanitize_tests ($BUILD/sanitize-tests.txt, <) differs from ctest's selection (>)"; exit 1; }
  cmake --build "$BUILD" -j "$(nproc)" --target dm_sanitize_tests > "$BUILD.build.log" 2>&1 \
    || { tail -40 "$BUILD.build.log"; exit 1; }
  ;;
run)
  shift
  cd "$BUILD"
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  ctest "${SELECT[@]}" "$@" --no-tests=error --output-on-failure
  ;;
*) echo "usage: sanitize.sh build | run CTEST_ARGS..."; exit 2 ;;
esac
