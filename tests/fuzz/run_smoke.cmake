# Runs one fuzz target for a fixed number of inputs from its seed corpus (ctest "fuzz" label).
# The seeds stay untouched: libFuzzer writes new inputs to the first corpus directory, a fresh
# WORK_DIR, and crash reproducers into WORK_DIR/artifacts.
foreach(variable FUZZER SEEDS DICT WORK_DIR RUNS MAX_LEN)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "run_smoke.cmake: -D${variable}=... missing")
  endif()
endforeach()
# An impossible allocation (HDF5 reading a size from a damaged header) fails as malloc does in a
# normal build, with NULL, which HDF5 reports as an error the runtime passes on; by default ASan
# would abort instead.
set(ENV{ASAN_OPTIONS} "allocator_may_return_null=1:$ENV{ASAN_OPTIONS}")
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/corpus ${WORK_DIR}/artifacts)
execute_process(
  COMMAND ${FUZZER} -runs=${RUNS} -seed=1 -max_len=${MAX_LEN} -timeout=10 -rss_limit_mb=2048
          -dict=${DICT} -artifact_prefix=${WORK_DIR}/artifacts/ -print_final_stats=1
          ${WORK_DIR}/corpus ${SEEDS}
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (${result}); reproducers in ${WORK_DIR}/artifacts")
endif()
