#!/usr/bin/env bash
# Install, build (warnings as errors), check formatting, run the whole test suite, then the
# parser fuzz smoke runs (clang + libFuzzer with ASan/UBSan, about 2 minutes; docs/robustness.md).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh -DWRC_WERROR=ON
tools/check-format.sh
cd build && ctest --output-on-failure -j "$(nproc)" --timeout 600
cd ..
WRC_JOBS="$(nproc)" tools/fuzz.sh --smoke
