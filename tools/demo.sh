#!/usr/bin/env bash
# The main job on the shipped default scene: install, build, solve.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
./build/wrc solve tables/hertz_demo.toml --json
