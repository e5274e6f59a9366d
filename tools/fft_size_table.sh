#!/bin/bash
# Regenerates the length-cost table of core/fft/fftw.cpp (kLengthCosts) from instruction
# counts: for every even 13-smooth length n up to 1024, callgrind counts
#   - four Forward + Backward pairs with n as row length (64 x n) and as column length (n x 64),
#     divided by 4·64·n: instructions per point of the padded array;
#   - the making of a PaddedPlan2d of 64 x n and of n x 64, in millions.
# Prints the table rows; takes ~6 minutes. Needs valgrind and build/bench/bench_fft_sizes.
#
#   tools/fft_size_table.sh build/bench/bench_fft_sizes > table.inc
set -euo pipefail
bench=${1:-build/bench/bench_fft_sizes}
count() {  # count FUNCTION MODE N0 N1
  valgrind --tool=callgrind --toggle-collect="$1*" --callgrind-out-file=/dev/null \
    "$bench" "$2" "$3" "$4" 2>&1 >/dev/null | awk '/Collected/ {print $4}'
}
for n in $(seq 16 2 1024); do
  m=$n
  for p in 2 3 5 7 11 13; do while (( m % p == 0 )); do m=$(( m / p )); done; done
  (( m == 1 )) || continue
  row=$(count MeasuredPairs pair 64 "$n")
  col=$(count MeasuredPairs pair "$n" 64)
  row_plan=$(count MeasuredPlan plan 64 "$n")
  col_plan=$(count MeasuredPlan plan "$n" 64)
  awk -v n="$n" -v r="$row" -v c="$col" -v rp="$row_plan" -v cp="$col_plan" 'BEGIN {
    printf "{%d, %.1f, %.1f, %.1f, %.1f},\n", n, r / (4 * 64 * n), c / (4 * 64 * n), rp / 1e6, cp / 1e6 }'
done
