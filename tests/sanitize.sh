#!/usr/bin/env bash
# The unit and GL integration tests, built with AddressSanitizer +
# UndefinedBehaviorSanitizer in a tree of their own.  Any
# sanitizer report fails the test that triggered it, and so this one.
set -euo pipefail
SRC=${DMBENCH_SOURCE_DIR:?}
BUILD=${SANITIZE_BUILD:?}
cmake -S "$SRC" -B "$BUILD" -DDM_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug > "$BUILD.cmake.log" 2>&1 \
  || { cat "$BUILD.cmake.log"; exit 1; }
cmake --build "$BUILD" -j "$(nproc)" > "$BUILD.build.log" 2>&1 || { tail -40 "$BUILD.build.log"; exit 1; }
cd "$BUILD"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest -L "^(unit|gl)$" -LE "^slow$" -j "$(nproc)" --output-on-failure
