#!/usr/bin/env bash
# Configures and builds the libFuzzer targets in BUILD_DIR (default build-fuzz): clang, ASan +
# UBSan and coverage on the parsers, -O1 with line tables (fast to build, readable stacks).
set -euo pipefail
build=${1:-build-fuzz}
cd "$(dirname "$0")/.."
cmake -S . -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DUWGRASP_BUILD_FUZZ=ON -DUWGRASP_BUILD_TESTS=OFF -DUWGRASP_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build "$build" -j2 --target fuzz
