# Driver of the packaging tests, run by ctest as `cmake -D... -P consumer_test.cmake`.
#
#   MODE=install   installs the runtime component of BUILD_DIR into PREFIX (emptied first) and
#                  checks the shared library's SONAME and that it exports wrc_* symbols only.
#   MODE=consumer  configures, builds and runs the project in consumer/ with SIM_LANGUAGES
#                  (C, CXX or C+CXX) against the package in PACKAGE_DIR (an install prefix,
#                  or the build tree), linking the VARIANT (static or shared) runtime, in WORK_DIR;
#                  each executable reads TABLE and checks a value.
#   MODE=example   builds runtime/examples/wheelset_dynamics.c (EXAMPLE) with the project in
#                  example/ against PACKAGE_DIR in WORK_DIR and runs it on the wheelset TABLE.
#   MODE=pkgconfig compiles consumer/sim.c with the C compiler CC as a plain build would,
#                  `CC sim.c $(pkg-config --cflags --libs wrc-runtime)` with PKG_CONFIG_PATH in
#                  PREFIX, in WORK_DIR, runs it on TABLE and checks that it links the shared runtime.
#   MODE=nohdf5    builds the runtime alone from PROJECT_DIR with WRC_RUNTIME_HDF5=OFF in WORK_DIR,
#                  installs it and checks that neither its library nor its package names HDF5;
#                  exports TABLE flat with WRC; builds digest/ against it (static, no HDF5 on the
#                  link line) and against the HDF5 runtime in PACKAGE_DIR: the digests of 10^6
#                  lookups of the flat table (HDF5-free runtime) and of TABLE (HDF5 runtime) agree.
#   MODE=python    installs the python component into PYTHON_PREFIX (emptied first) and has PYTHON
#                  import the installed module from there and check the same value.
cmake_minimum_required(VERSION 3.22)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    string(REPLACE ";" " " line "${ARGN}")
    message(FATAL_ERROR "failed (${code}): ${line}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

function(check_shared_library library)
  run(${OBJDUMP} -p ${library})
  if(NOT run_output MATCHES "SONAME +libwrc_runtime\\.so\\.${SONAME_VERSION}\n")
    message(FATAL_ERROR "${library}: SONAME is not libwrc_runtime.so.${SONAME_VERSION}:\n${run_output}")
  endif()
  run(${NM} -D --defined-only ${library})
  string(REGEX MATCHALL "[^\n]+" symbols "${run_output}")
  set(foreign "")
  foreach(line IN LISTS symbols)
    if(NOT line MATCHES " (wrc_[A-Za-z0-9_]+)$" AND NOT line MATCHES " A [A-Z0-9_.]+$")
      list(APPEND foreign "${line}")
    endif()
  endforeach()
  if(foreign)
    string(REPLACE ";" "\n" foreign "${foreign}")
    message(FATAL_ERROR "${library} exports symbols besides wrc_*:\n${foreign}")
  endif()
endfunction()

function(install_runtime)
  file(REMOVE_RECURSE ${PREFIX})
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --component runtime --prefix ${PREFIX})
  file(GLOB libdirs ${PREFIX}/lib*)
  foreach(file include/wrc/runtime.h include/wrc/runtime.hpp include/wrc/table_limits.h)
    if(NOT EXISTS ${PREFIX}/${file})
      message(FATAL_ERROR "not installed: ${file}")
    endif()
  endforeach()
  file(GLOB_RECURSE shared ${PREFIX}/libwrc_runtime.so.*.*.*)
  file(GLOB_RECURSE static ${PREFIX}/libwrc_runtime.a)
  file(GLOB_RECURSE config ${PREFIX}/wrcConfig.cmake)
  if(NOT shared OR NOT static OR NOT config)
    message(FATAL_ERROR "installed: shared '${shared}', static '${static}', config '${config}'")
  endif()
  check_shared_library(${shared})
endfunction()

function(build_consumer)
  file(REMOVE_RECURSE ${WORK_DIR})
  if(VARIANT STREQUAL "static")
    set(static ON)
  else()
    set(static OFF)
  endif()
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/consumer -B ${WORK_DIR} -G ${GENERATOR}
      "-DSIM_LANGUAGES=${SIM_LANGUAGES}" -DCMAKE_PREFIX_PATH=${PACKAGE_DIR}
      -DWRC_RUNTIME_STATIC=${static} -DCMAKE_BUILD_TYPE=Release)
  run(${CMAKE_COMMAND} --build ${WORK_DIR})
  file(GLOB executables ${WORK_DIR}/sim_c ${WORK_DIR}/sim_cpp)
  list(LENGTH executables count)
  string(REPLACE "+" ";" language_list "${SIM_LANGUAGES}")
  list(LENGTH language_list languages)
  if(NOT count EQUAL languages)
    message(FATAL_ERROR "built ${count} executables for ${languages} languages: ${executables}")
  endif()
  foreach(executable IN LISTS executables)
    run(${executable} ${TABLE})
    message(STATUS "${run_output}")
    check_linkage(${executable})
  endforeach()
endfunction()

# A static consumer must not need libwrc_runtime.so at run time; a shared one must.
function(check_linkage executable)
  run(${OBJDUMP} -p ${executable})
  if(run_output MATCHES "NEEDED +libwrc_runtime\\.so")
    set(needed shared)
  else()
    set(needed static)
  endif()
  if(NOT needed STREQUAL VARIANT)
    message(FATAL_ERROR "${executable} links the ${needed} runtime, expected ${VARIANT}")
  endif()
endfunction()

function(install_python)
  file(REMOVE_RECURSE ${PYTHON_PREFIX})
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --component python --prefix ${PYTHON_PREFIX})
  file(GLOB_RECURSE module ${PYTHON_PREFIX}/wrc*.so)
  if(NOT module)
    message(FATAL_ERROR "the python component installed no module into ${PYTHON_PREFIX}")
  endif()
  get_filename_component(module_dir ${module} DIRECTORY)
  run(${PYTHON} ${SOURCE_DIR}/../python/check_installed.py ${module_dir} ${TABLE} ${VERSION})
  message(STATUS "${run_output}")
endfunction()

# The example simulates 2 s and reports its cost; on the synthetic table (affine forces, no
# roll) it must run to the end without a clamped state.
function(build_example)
  file(REMOVE_RECURSE ${WORK_DIR})
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/example -B ${WORK_DIR} -G ${GENERATOR}
      -DCMAKE_PREFIX_PATH=${PACKAGE_DIR} -DEXAMPLE=${EXAMPLE} -DCMAKE_BUILD_TYPE=Release)
  run(${CMAKE_COMMAND} --build ${WORK_DIR})
  run(${WORK_DIR}/wheelset_dynamics ${TABLE} 30 10000)
  if(NOT run_output MATCHES "\n2\.000 [-0-9.e]+ [-0-9.e+]+\n" OR
     NOT run_output MATCHES "times real time" OR run_output MATCHES "clamped")
    message(FATAL_ERROR "wheelset_dynamics did not run through 2 s:\n${run_output}")
  endif()
  check_linkage(${WORK_DIR}/wheelset_dynamics)
  message(STATUS "${run_output}")
endfunction()

function(build_with_pkg_config)
  file(REMOVE_RECURSE ${WORK_DIR})
  file(MAKE_DIRECTORY ${WORK_DIR})
  file(GLOB_RECURSE pc_file ${PREFIX}/wrc-runtime.pc)
  if(NOT pc_file)
    message(FATAL_ERROR "no wrc-runtime.pc installed under ${PREFIX}")
  endif()
  get_filename_component(pc_dir ${pc_file} DIRECTORY)
  set(ENV{PKG_CONFIG_PATH} ${pc_dir})
  run(pkg-config --cflags --libs wrc-runtime)
  string(STRIP "${run_output}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  run(${CC} -std=c99 -I${SOURCE_DIR}/consumer ${SOURCE_DIR}/consumer/sim.c ${flags} -lm
      -o ${WORK_DIR}/sim_c)
  run(${WORK_DIR}/sim_c ${TABLE})  # no LD_LIBRARY_PATH: the .pc file's rpath finds the library
  message(STATUS "${run_output}")
  check_linkage(${WORK_DIR}/sim_c)
endfunction()

# The digest line table_digest prints for `table` (built in `dir` against `package`, `variant`).
function(table_digest dir package variant table out_var)
  if(NOT EXISTS ${dir}/table_digest)
    set(static OFF)
    if(variant STREQUAL "static")
      set(static ON)
    endif()
    run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/digest -B ${dir} -G ${GENERATOR}
        -DCMAKE_PREFIX_PATH=${package} -DWRC_RUNTIME_STATIC=${static} -DCMAKE_BUILD_TYPE=Release)
    run(${CMAKE_COMMAND} --build ${dir})
  endif()
  run(${dir}/table_digest ${table})
  string(REGEX MATCH "digest [0-9a-f]+ over [0-9]+ points" digest "${run_output}")
  if(NOT digest)
    message(FATAL_ERROR "table_digest printed no digest: ${run_output}")
  endif()
  set(${out_var} "${digest}" PARENT_SCOPE)
endfunction()

# Nothing installed may name HDF5: not the library's NEEDED entries, not the package files.
function(check_no_hdf5 prefix)
  file(GLOB_RECURSE shared ${prefix}/libwrc_runtime.so.*.*.*)
  run(${OBJDUMP} -p ${shared})
  if(run_output MATCHES "NEEDED +[^\n]*hdf5")
    message(FATAL_ERROR "${shared} needs HDF5:\n${run_output}")
  endif()
  file(GLOB_RECURSE package_files ${prefix}/*.cmake ${prefix}/*.pc)
  foreach(file IN LISTS package_files)
    file(STRINGS ${file} lines REGEX "^[^#]*[Hh][Dd][Ff]5")  # outside comments
    if(lines)
      message(FATAL_ERROR "${file} names HDF5: ${lines}")
    endif()
  endforeach()
endfunction()

function(build_without_hdf5)
  file(REMOVE_RECURSE ${WORK_DIR})
  set(build ${WORK_DIR}/build)
  set(prefix ${WORK_DIR}/prefix)
  run(${CMAKE_COMMAND} -S ${PROJECT_DIR} -B ${build} -G ${GENERATOR} -DWRC_RUNTIME_HDF5=OFF
      -DWRC_WERROR=ON -DCMAKE_BUILD_TYPE=Release)
  run(${CMAKE_COMMAND} --build ${build} --parallel 2)
  run(${CMAKE_COMMAND} --install ${build} --component runtime --prefix ${prefix})
  check_no_hdf5(${prefix})
  set(flat ${WORK_DIR}/table.wrct)
  run(${WRC} export ${TABLE} -o ${flat})
  table_digest(${WORK_DIR}/flat_runtime ${prefix} static ${flat} flat_digest)
  file(GLOB_RECURSE link_lines ${WORK_DIR}/flat_runtime/*link.txt)
  foreach(file IN LISTS link_lines)
    file(READ ${file} text)
    if(text MATCHES "libhdf5|/hdf5/")
      message(FATAL_ERROR "the consumer's link line names HDF5: ${text}")
    endif()
  endforeach()
  table_digest(${WORK_DIR}/hdf5_runtime ${PACKAGE_DIR} shared ${TABLE} hdf5_digest)
  table_digest(${WORK_DIR}/hdf5_runtime ${PACKAGE_DIR} shared ${flat} hdf5_flat_digest)
  if(NOT flat_digest STREQUAL hdf5_digest OR NOT hdf5_flat_digest STREQUAL hdf5_digest)
    message(FATAL_ERROR "lookups differ: HDF5 runtime on the HDF5 table: ${hdf5_digest}; on the "
                        "flat table: ${hdf5_flat_digest}; HDF5-free runtime: ${flat_digest}")
  endif()
  # The HDF5-free runtime refuses an HDF5 table, saying how to convert it.
  execute_process(COMMAND ${WORK_DIR}/flat_runtime/table_digest ${TABLE} 1
                  RESULT_VARIABLE code ERROR_VARIABLE err OUTPUT_QUIET)
  if(code EQUAL 0 OR NOT err MATCHES "wrc export")
    message(FATAL_ERROR "the HDF5-free runtime read ${TABLE} (exit ${code}): ${err}")
  endif()
  message(STATUS "HDF5 runtime and HDF5-free runtime: ${flat_digest}")
endfunction()

if(MODE STREQUAL "install")
  install_runtime()
elseif(MODE STREQUAL "consumer")
  build_consumer()
elseif(MODE STREQUAL "example")
  build_example()
elseif(MODE STREQUAL "pkgconfig")
  build_with_pkg_config()
elseif(MODE STREQUAL "python")
  install_python()
elseif(MODE STREQUAL "nohdf5")
  build_without_hdf5()
else()
  message(FATAL_ERROR
          "MODE must be install, consumer, example, pkgconfig, nohdf5 or python, not '${MODE}'")
endif()
