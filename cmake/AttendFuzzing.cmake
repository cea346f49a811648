# libFuzzer instrumentation for the fuzz build (-DATTEND_BUILD_FUZZERS=ON, clang only;
# docs/FUZZING.md). The project's own targets are compiled with coverage instrumentation and
# AddressSanitizer + UBSan but without libFuzzer's main; only the fuzz targets link libFuzzer.
# UBSan reports are made fatal, so that libFuzzer records them as findings instead of printing
# them and going on.

set(ATTEND_FUZZ_SANITIZERS "address,undefined")
set(ATTEND_FUZZ_COMPILE_OPTIONS
    -fsanitize=fuzzer-no-link,${ATTEND_FUZZ_SANITIZERS} -fno-sanitize-recover=all
    -fno-omit-frame-pointer)

# Adds the instrumentation to every library and program defined in `dir` and the folders below
# it. Executables and shared objects link the sanitizer runtimes, so that the rest of the build
# (the `attend` program, the examples) still links and runs under the same sanitizers.
function(attend_instrument_for_fuzzing dir)
  get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type MATCHES "^(STATIC_LIBRARY|OBJECT_LIBRARY|SHARED_LIBRARY|MODULE_LIBRARY|EXECUTABLE)$")
      target_compile_options(${target} PRIVATE ${ATTEND_FUZZ_COMPILE_OPTIONS})
    endif()
    if(type MATCHES "^(SHARED_LIBRARY|MODULE_LIBRARY|EXECUTABLE)$")
      target_link_options(${target} PRIVATE -fsanitize=${ATTEND_FUZZ_SANITIZERS})
    endif()
  endforeach()
  get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
  foreach(subdir IN LISTS subdirs)
    attend_instrument_for_fuzzing("${subdir}")
  endforeach()
endfunction()

# attend_add_fuzzer(NAME SOURCES ... DEPS ...)
# One libFuzzer executable, build-fuzz/fuzz/fuzz_NAME, with the shared helpers of fuzz/.
function(attend_add_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  set(target fuzz_${name})
  add_executable(${target} ${ARG_SOURCES})
  target_compile_options(${target} PRIVATE -Wall -Wextra
                         -fsanitize=fuzzer,${ATTEND_FUZZ_SANITIZERS} -fno-sanitize-recover=all
                         -fno-omit-frame-pointer)
  target_link_options(${target} PRIVATE -fsanitize=fuzzer,${ATTEND_FUZZ_SANITIZERS})
  target_link_libraries(${target} PRIVATE attend_fuzz_support ${ARG_DEPS})
  set_property(GLOBAL APPEND PROPERTY ATTEND_FUZZERS ${target})
endfunction()
