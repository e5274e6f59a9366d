# Installs the wrc module where ${python} finds modules of ${CMAKE_INSTALL_PREFIX} (run by
# `cmake --install`, with python, override, module and finder set by python/CMakeLists.txt).
if(override)
  set(dir "${CMAKE_INSTALL_PREFIX}/${override}")
  set(on_path "unknown")
else()
  execute_process(COMMAND "${python}" "${finder}" "${CMAKE_INSTALL_PREFIX}"
                  OUTPUT_VARIABLE answer RESULT_VARIABLE code OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "wrc: ${python} could not say where its modules go (exit ${code})")
  endif()
  string(REPLACE "\n" ";" answer "${answer}")
  list(GET answer 0 dir)
  list(GET answer 1 on_path)
endif()
file(INSTALL DESTINATION "${dir}" TYPE MODULE FILES "${module}")
if(on_path STREQUAL "yes")
  message(STATUS "wrc Python module for ${python}: ${dir} (on its sys.path)")
else()
  message(STATUS "wrc Python module for ${python}: ${dir}; that folder is not on its sys.path: "
                 "PYTHONPATH=${dir} ${python} -c 'import wrc'")
endif()
