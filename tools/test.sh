#!/usr/bin/env bash
# Install, build (warnings as errors), check formatting, run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh -DWRC_WERROR=ON
tools/check-format.sh
cd build && ctest --output-on-failure -j "$(nproc)" --timeout 600
