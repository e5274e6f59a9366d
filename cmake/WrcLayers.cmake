# Include paths that enforce the layers (docs/design.md). Each part of wrc compiles against a
# directory of its own in the build tree that holds symbolic links to exactly the headers it may
# include: its own sources, and the public headers of the parts below it. An include of another
# part's internals (say "core/..." from the runtime, or "wrc/generator/generator.h" from core)
# then fails to compile instead of silently adding a dependency. Tests and benchmarks, which
# test internals, keep the whole source tree on their path.

# The public headers of each library: include/wrc/runtime.h(pp) and the table limits it includes
# for the runtime (installed with it), include/wrc/core/ for the solver, include/wrc/generator/
# for the generator. Below all of them, header-only: the quantity registry
# (include/wrc/quantities.h) and the table limits (include/wrc/table_limits.h).
set(WRC_RUNTIME_PUBLIC_HEADERS wrc/runtime.h wrc/runtime.hpp wrc/table_limits.h)
set(WRC_QUANTITY_HEADERS wrc/quantities.h wrc/table_limits.h)

# wrc_layer(NAME DIRS dir... HEADERS header...): the directory
# ${PROJECT_BINARY_DIR}/layers/NAME with links to the source directories DIRS (relative to the
# project root, e.g. runtime/hdf5, or to include/ when they start with wrc/, e.g. wrc/core) and
# to the public HEADERS (relative to include/, e.g. wrc/runtime.h, or to the project root when
# they do not start with wrc/, e.g. tools/wrc/gnuplot.h: a single header of another part).
# Sets WRC_LAYER_<NAME> to the directory.
function(wrc_layer name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "DIRS;HEADERS")
  set(root ${PROJECT_BINARY_DIR}/layers/${name})
  file(REMOVE_RECURSE ${root})
  foreach(dir IN LISTS arg_DIRS)
    get_filename_component(parent ${root}/${dir} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    if(dir MATCHES "^wrc/")
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/include/${dir} ${root}/${dir} SYMBOLIC)
    else()
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${dir} ${root}/${dir} SYMBOLIC)
    endif()
  endforeach()
  foreach(header IN LISTS arg_HEADERS)
    get_filename_component(parent ${root}/${header} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    if(header MATCHES "^wrc/")
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/include/${header} ${root}/${header} SYMBOLIC)
    else()
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${header} ${root}/${header} SYMBOLIC)
    endif()
  endforeach()
  set(WRC_LAYER_${name} ${root} PARENT_SCOPE)
endfunction()

# What each part sees. Public layers go to the users of a library (PUBLIC / INTERFACE); the
# private ones add the part's own sources.
wrc_layer(hdf5 DIRS runtime/hdf5)
# The table formats (runtime/format): the readers the runtime loads with and the flat writer of
# `wrc export`. The schema's names come from runtime/hdf5/table_schema.h, in either build.
wrc_layer(format DIRS runtime/format runtime/hdf5 HEADERS ${WRC_RUNTIME_PUBLIC_HEADERS})
wrc_layer(runtime_public HEADERS ${WRC_RUNTIME_PUBLIC_HEADERS})
wrc_layer(runtime DIRS runtime HEADERS ${WRC_RUNTIME_PUBLIC_HEADERS} wrc/quantities.h)
wrc_layer(core_public DIRS wrc/core HEADERS ${WRC_QUANTITY_HEADERS})
wrc_layer(core DIRS core wrc/core HEADERS ${WRC_QUANTITY_HEADERS})
wrc_layer(generator_public DIRS wrc/generator)
# The generator measures a refinement with the runtime's cubic line arithmetic, and writes its
# journal with the table formats' little-endian fields (header-only, both).
wrc_layer(generator DIRS generator runtime/interp runtime/format)
# The wheelset FMU: the runtime's C API below it.
wrc_layer(fmu DIRS fmu HEADERS ${WRC_RUNTIME_PUBLIC_HEADERS})
# The dynamics model (studies/dynamics): the solver's and the runtime's public headers below it,
# and the angle constants of the tools (tools/angles.h, header-only).
wrc_layer(dynamics DIRS studies/dynamics HEADERS tools/angles.h)
# The studies (studies/, with the dynamics model): above the generator, the solver and the
# runtime, and beside the command line, of which they share the option checks, exit codes,
# gnuplot, text outputs and table check (the library wrc_cli_support) and the angle constants,
# nothing else.
set(WRC_CLI_SHARED_HEADERS tools/angles.h tools/wrc/commands.h tools/wrc/exit_codes.h
                           tools/wrc/gnuplot.h tools/wrc/output_text.h tools/wrc/thread_option.h
                           tools/wrc/verify.h)
wrc_layer(studies DIRS studies HEADERS ${WRC_CLI_SHARED_HEADERS})
# The command line: its own sources, the dynamics model (`wrc fmu` checks a table with its
# table forces) and of the studies their entry point only.
wrc_layer(tools DIRS tools studies/dynamics HEADERS studies/studies.h)
