#!/usr/bin/env bash
# Builds the libFuzzer targets of the input parsers (tests/fuzz/, clang with ASan + UBSan) into
# build-fuzz/ (or build-fuzz-plain/) and runs them; see docs/robustness.md.
#
#   tools/fuzz.sh [SECONDS] [libFuzzer flags...]  each target for SECONDS (default 60). New
#       interesting inputs accumulate in BUILD/corpus/<target>/, so a later run goes on from
#       there; crash reproducers land in BUILD/artifacts/<target>/.
#   tools/fuzz.sh --smoke   the short, fixed-seed runs registered with ctest (label "fuzz").
#
# WRC_FUZZ_TARGETS="fuzz_profile ..." picks targets, WRC_JOBS the build parallelism (default 2).
# WRC_FUZZ_SANITIZERS= (empty) builds plain libFuzzer targets into build-fuzz-plain/, where the C
# library's allocator, and so MALLOC_PERTURB_, serves the code under test (ASan's ignores it).
# Exits 1 when any target found a crash, a hang, a leak or a sanitizer report.
set -euo pipefail
cd "$(dirname "$0")/.."

read -r -a targets <<<"${WRC_FUZZ_TARGETS:-fuzz_profile fuzz_case fuzz_scene fuzz_table fuzz_flat_table}"
jobs="${WRC_JOBS:-2}"
sanitizers="${WRC_FUZZ_SANITIZERS-address,undefined}"
build=build-fuzz
[ -n "$sanitizers" ] || build=build-fuzz-plain

cmake -S . -B "$build" -DWRC_FUZZ=ON -DWRC_FUZZ_SANITIZERS="$sanitizers" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWRC_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target "${targets[@]}"

if [ "${1:-}" = "--smoke" ]; then
  tests=$(printf '%s_smoke|' "${targets[@]}")
  exec ctest --test-dir "$build" -L fuzz -R "^(${tests%|})\$" --output-on-failure -j "$jobs"
fi

seconds="${1:-60}"
shift || true
declare -A dictionary=([fuzz_profile]=profile.dict [fuzz_case]=toml.dict [fuzz_scene]=toml.dict
  [fuzz_table]=hdf5.dict [fuzz_flat_table]=flat.dict)
declare -A max_len=([fuzz_profile]=4096 [fuzz_case]=4096 [fuzz_scene]=4096 [fuzz_table]=32768 [fuzz_flat_table]=16384)
# An impossible allocation fails with NULL as in a normal build (HDF5 then reports an error),
# instead of ASan's default abort.
export ASAN_OPTIONS="allocator_may_return_null=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
failed=()
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  artifacts="$build/artifacts/$target"
  mkdir -p "$corpus" "$artifacts"
  echo "fuzz: $target for ${seconds} s" >&2
  # The first directory receives new inputs; the seeds in tests/fuzz/corpus stay untouched.
  if ! "$build/tests/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="${max_len[$target]}" -dict="tests/fuzz/${dictionary[$target]}" -artifact_prefix="$artifacts/" \
    -print_final_stats=1 "$@" "$corpus" "tests/fuzz/corpus/$target"; then
    failed+=("$target")
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: findings in ${failed[*]}; reproducers in $build/artifacts/" >&2
  exit 1
fi
echo "fuzz: no findings in ${targets[*]}" >&2
