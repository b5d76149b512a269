# Per-target settings shared by the library, tools, experiments and tests.

# Warnings: an interface target linked PRIVATE by every peg3d target.
add_library(peg3d_warnings INTERFACE)
target_compile_options(peg3d_warnings INTERFACE -Wall -Wextra -pedantic $<$<BOOL:${PEG3D_WERROR}>:-Werror>)

# Sanitizers: an interface target linked PUBLIC by the library so every consumer is instrumented too.
add_library(peg3d_sanitizers INTERFACE)
if(PEG3D_SANITIZE)
  list(JOIN PEG3D_SANITIZE "," _peg3d_san)
  target_compile_options(peg3d_sanitizers INTERFACE -fsanitize=${_peg3d_san} -fno-omit-frame-pointer
                                                    -fno-sanitize-recover=all)
  target_link_options(peg3d_sanitizers INTERFACE -fsanitize=${_peg3d_san})
endif()
# Fuzzing: coverage instrumentation for everything; only the fuzz targets link libFuzzer's main.
if(PEG3D_FUZZ)
  target_compile_options(peg3d_sanitizers INTERFACE -fsanitize=fuzzer-no-link)
endif()

# peg3d_add_executable(name SOURCES ... [LIBRARY lib]): a thin executable linking the library (peg3d::peg3d,
# or one part of it: the tests of peg3d_sweep link that alone, so the build proves it needs nothing else).
function(peg3d_add_executable name)
  cmake_parse_arguments(ARG "" "LIBRARY" "SOURCES;LIBS" ${ARGN})
  if(NOT ARG_LIBRARY)
    set(ARG_LIBRARY peg3d::peg3d)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBRARY} peg3d_warnings ${ARG_LIBS})
  target_compile_features(${name} PRIVATE cxx_std_20)
  set_target_properties(${name} PROPERTIES CXX_EXTENSIONS OFF)
endfunction()
