#!/usr/bin/env bash
# The main job on the shipped default scene: install, build, generate the demo table, look a few
# points up with the runtime library (through its C example), and solve one case in full.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >&2
rm -f build/demo.h5 build/demo.h5.journal
./build/wrc generate tables/demo.toml -o build/demo.h5 --quiet
./build/wrc info build/demo.h5
for point in "0.0 0.0" "2.5 0.002" "-3.2 -0.004"; do
  # shellcheck disable=SC2086 # the point's coordinates are separate arguments
  ./build/runtime/wrc_lookup_example build/demo.h5 $point | head -8
done
./build/wrc solve tables/hertz_demo.toml
