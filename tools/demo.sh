#!/usr/bin/env bash
# The main job on the shipped default scene: install, build, solve. Only the JSON result goes to
# stdout (the build's output goes to stderr), so `bash tools/demo.sh > result.json` works.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh >&2
./build/wrc solve tables/hertz_demo.toml --json
