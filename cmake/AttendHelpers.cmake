# attend_add_library(NAME SOURCES ... PUBLIC_DEPS ... PRIVATE_DEPS ...)
# One static library per module folder; include paths are rooted at the project root so that
# headers are included as "module/file.h".
function(attend_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_compile_options(${name} PRIVATE -Wall -Wextra)
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
endfunction()

# attend_add_test(NAME SOURCES ... DEPS ... [COST SECONDS])
# One GoogleTest executable; each TEST is registered with ctest separately.
# COST: ctest's estimate of a test's time, for tests far slower than the rest, so that
# `ctest -j` starts them first instead of last (ctest has no measured cost in a fresh build).
function(attend_add_test name)
  cmake_parse_arguments(ARG "" "COST" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_compile_options(${name} PRIVATE -Wall -Wextra)
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} attend_test_support GTest::gtest_main)
  set(cost_property)
  if(ARG_COST)
    set(cost_property COST ${ARG_COST})
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
    PROPERTIES ENVIRONMENT "ATTEND_HOME=${PROJECT_SOURCE_DIR}" ${cost_property})
endfunction()

# attend_export_plugin_api(TARGET)
# Makes an executable able to load feature plugins (features/plugin_api.h): it exports its
# symbols, and links the libraries whose functions a plugin may call in whole, so that every
# function of that API is present even when the program itself does not use it.
function(attend_export_plugin_api target)
  set_target_properties(${target} PROPERTIES ENABLE_EXPORTS ON)
  set(archives)
  foreach(library attend_features attend_saliency attend_config attend_pyramid attend_colour
                  attend_util)
    list(APPEND archives "$<TARGET_FILE:${library}>")
  endforeach()
  target_link_options(${target} PRIVATE "LINKER:--whole-archive" ${archives}
                      "LINKER:--no-whole-archive")
  add_dependencies(${target} attend_features)
endfunction()
