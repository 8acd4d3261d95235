# Tests print nothing unless asked: runs each test program of TESTS (paths separated by |) without
# VISP_PROJECTIVE_TEST_VERBOSE and fails if one fails or prints, on stdout or stderr, any line that is not GoogleTest's
# own ("[ RUN      ] ...", "Running main() from ...", ...). Run by the ctest case tests_print_nothing
# (tests/CMakeLists.txt): cmake "-DTESTS=<program>|<program>..." -P check-tests-print-nothing.cmake
unset(ENV{VISP_PROJECTIVE_TEST_VERBOSE})
string(REPLACE "|" ";" TESTS "${TESTS}")
set(failed "")
foreach(test IN LISTS TESTS)
  execute_process(COMMAND ${test} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    string(APPEND failed "${test} exited with ${rc}\n")
  endif()
  # The output as a list of lines: brackets and semicolons replaced first, so that no line splits or joins others.
  set(text "${out}\n${err}")
  string(REPLACE "[" "<lb>" text "${text}")
  string(REPLACE "]" "<rb>" text "${text}")
  string(REPLACE ";" "<sc>" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  foreach(line IN LISTS lines)
    if(line STREQUAL "" OR line MATCHES "^<lb>(==========|----------|  PASSED  |  FAILED  |  SKIPPED |       OK | RUN      )<rb>"
       OR line MATCHES "^Running main\\(\\) from " OR line MATCHES "^Note: Google Test "
       OR line MATCHES "^ *YOU HAVE [0-9]+ DISABLED TESTS?$" OR line MATCHES "^ *[0-9]+ FAILED TESTS?$")
      continue()
    endif()
    string(REPLACE "<lb>" "[" line "${line}")
    string(REPLACE "<rb>" "]" line "${line}")
    string(REPLACE "<sc>" ";" line "${line}")
    string(APPEND failed "${test} printed: ${line}\n")
  endforeach()
endforeach()
if(failed)
  message(FATAL_ERROR "Tests must print nothing unless VISP_PROJECTIVE_TEST_VERBOSE is set (vpProjectiveTest::testLog()):\n"
                      "${failed}")
endif()
