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
  foreach(file include/wrc/runtime.h include/wrc/runtime.hpp)
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
else()
  message(FATAL_ERROR "MODE must be install, consumer, example, pkgconfig or python, not '${MODE}'")
endif()
