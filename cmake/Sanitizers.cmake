# ATTEND_SANITIZE: a comma list of sanitizers for the whole build, e.g.
#   cmake -DATTEND_SANITIZE=address,undefined ...
# Empty (the default) builds without any. scripts/sanitize.sh is the documented way to build
# and run the test suite this way (README.md, "Sanitizers").
#
# The flags go to every target of the project, libraries, programs, plugins and tests alike:
# ASan needs the program and everything it loads instrumented the same way, and a plugin or test
# left out would hide its own reports.
set(ATTEND_SANITIZE "" CACHE STRING
    "Comma list of sanitizers (address, undefined, leak, thread); empty for none")

if(ATTEND_SANITIZE)
  string(REPLACE "," ";" attend_sanitizers "${ATTEND_SANITIZE}")
  foreach(sanitizer IN LISTS attend_sanitizers)
    if(NOT sanitizer MATCHES "^(address|undefined|leak|thread)$")
      message(FATAL_ERROR
              "ATTEND_SANITIZE: unknown sanitizer '${sanitizer}' (address, undefined, leak, thread)")
    endif()
  endforeach()
  if("thread" IN_LIST attend_sanitizers AND
     ("address" IN_LIST attend_sanitizers OR "leak" IN_LIST attend_sanitizers))
    message(FATAL_ERROR "ATTEND_SANITIZE: thread cannot be combined with address or leak")
  endif()

  # Frame pointers give the reports whole stack traces at the cost of one register.
  set(attend_sanitize_flags -fsanitize=${ATTEND_SANITIZE} -fno-omit-frame-pointer)
  if("undefined" IN_LIST attend_sanitizers)
    # By default UBSan prints its report and carries on, so the test would still pass; stopping
    # at the first report makes it fail.
    list(APPEND attend_sanitize_flags -fno-sanitize-recover=undefined)
  endif()
  add_compile_options(${attend_sanitize_flags})
  add_link_options(${attend_sanitize_flags})
  message(STATUS "attend: sanitizers ${ATTEND_SANITIZE}")
endif()
