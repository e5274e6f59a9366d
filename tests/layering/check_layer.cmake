# One layer of cmake/WrcLayers.cmake holds: against the include path INCLUDES (a ;-list) a
# source including ALLOWED compiles, and one including each of FORBIDDEN (a ;-list) fails
# because the header is not found. Run as
#   cmake -DCXX=c++ -DINCLUDES=a;b -DALLOWED=x.h -DFORBIDDEN=y.h;z.h -DWORK=dir -P check_layer.cmake
file(MAKE_DIRECTORY ${WORK})
set(flags -std=c++17 -fsyntax-only)
foreach(dir IN LISTS INCLUDES)
  list(APPEND flags -I${dir})
endforeach()

function(compile header result output)
  string(MAKE_C_IDENTIFIER ${header} stem)
  set(source ${WORK}/${stem}.cpp)
  file(WRITE ${source} "#include \"${header}\"\n")
  execute_process(COMMAND ${CXX} ${flags} ${source} RESULT_VARIABLE code OUTPUT_VARIABLE out
                  ERROR_VARIABLE out)
  set(${result} ${code} PARENT_SCOPE)
  set(${output} "${out}" PARENT_SCOPE)
endfunction()

compile(${ALLOWED} code out)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${ALLOWED} should compile against ${INCLUDES}:\n${out}")
endif()
foreach(header IN LISTS FORBIDDEN)
  compile(${header} code out)
  if(code EQUAL 0)
    message(FATAL_ERROR "${header} compiles against ${INCLUDES}: the layer does not hold")
  endif()
  if(NOT out MATCHES "No such file")
    message(FATAL_ERROR "${header} failed for another reason than a missing header:\n${out}")
  endif()
endforeach()
message(STATUS "layer holds: ${ALLOWED} reachable; ${FORBIDDEN} not")
