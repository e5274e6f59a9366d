#!/usr/bin/env bash
# Changes each byte of a table in turn and reads every damaged copy with the C runtime and the
# Python module (each in one process, so the heap carries what earlier reads left) and with
# `wrc info` (a process per copy), all under MALLOC_PERTURB_ (glibc fills allocated and freed
# memory with a pattern, so reading memory that is not initialised or already freed shows);
# see docs/robustness.md. Run from the repository root after a build in build/:
#
#   tools/flip_scan/flip_scan.sh TABLE.h5 [STRIDE]   every STRIDE-th byte (default 1)
#
# Prints the counts of each reader; exits 1 when any damaged copy crashed a reader or was read
# with numbers other than the intact table's.
set -uo pipefail
cd "$(dirname "$0")/../.."
table="$1"
stride="${2:-1}"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
export MALLOC_PERTURB_="${MALLOC_PERTURB_:-165}"
status=0
# A copy of the binaries, so that the scan can go on while build/ is rebuilt (the front end finds
# wrc-tables beside itself).
bin="$scratch/bin"
mkdir -p "$bin"
cp build/wrc build/wrc-tables build/tools/flip_scan/wrc_flip_scan "$bin/"
echo "flip_scan: $table, $(stat -c %s "$table") bytes, every ${stride}th, MALLOC_PERTURB_=$MALLOC_PERTURB_"
printf 'C runtime:   '
"$bin/wrc_flip_scan" "$table" "$scratch/c.h5" "$stride" || status=1
printf 'Python:      '
build/python/python3 tools/flip_scan/flip_scan.py python "$table" "$scratch/p.h5" \
  "$stride" || status=1
printf 'wrc info:    '
build/python/python3 tools/flip_scan/flip_scan.py info "$bin/wrc" "$table" "$scratch/i.h5" "$stride" || status=1
exit $status
