# Helpers that give every shanshui target the same warnings and layout.

function(shanshui_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local)
  # GCC 12 reports std::string concatenation at -O3 as overlapping memcpy (GCC bug 105329).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(SHANSHUI_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# shanshui_library(NAME SOURCES ... DEPS ...): libs/<name> with include/ as its public headers.
function(shanshui_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(shanshui_${name} STATIC ${ARG_SOURCES})
  add_library(shanshui::${name} ALIAS shanshui_${name})
  target_include_directories(shanshui_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(shanshui_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  shanshui_warnings(shanshui_${name})
endfunction()

function(shanshui_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  shanshui_warnings(${name})
endfunction()

# shanshui_module(NAME OF LIBRARY SOURCES ... DEPS ... LOADER source MACRO name): a part of
# a library built as a module beside the programs and loaded on first use (see
# shanshui/core/module.h), so that a program that never needs its heavy dependencies does
# not load them at start. LOADER is the library source that loads it; it gets MACRO defined
# to the module's build directory.
function(shanshui_module name)
  cmake_parse_arguments(ARG "" "OF;LOADER;MACRO" "SOURCES;DEPS" ${ARGN})
  add_library(${name} MODULE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  set_target_properties(${name} PROPERTIES
    LIBRARY_OUTPUT_DIRECTORY ${CMAKE_RUNTIME_OUTPUT_DIRECTORY}
    CXX_VISIBILITY_PRESET hidden)
  shanshui_warnings(${name})
  add_dependencies(${ARG_OF} ${name})
  set_source_files_properties(${ARG_LOADER} PROPERTIES
    COMPILE_DEFINITIONS ${ARG_MACRO}="${CMAKE_RUNTIME_OUTPUT_DIRECTORY}")
endfunction()
