# ctest case visp_headers_detects: check-visp-headers.cmake tells a guarded include from an unguarded one. Each case is
# a one-file source tree written to WORK_DIR and checked against the real header lists; the case passes only if the
# check's verdict is the expected one.
#   cmake -DSCRIPT=<repo>/tests/check-visp-headers.cmake -DHEADERS=<repo>/tests/visp-headers.txt -DWORK_DIR=<dir>
#         -P check-visp-headers-detects.cmake
if(NOT SCRIPT OR NOT HEADERS OR NOT WORK_DIR)
  message(FATAL_ERROR "SCRIPT, HEADERS and WORK_DIR must be set")
endif()

set(wrong "")
function(expect name verdict text)
  set(dir "${WORK_DIR}/${name}")
  file(REMOVE_RECURSE "${dir}")
  file(WRITE "${dir}/src/case.cpp" "${text}")
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${dir} -DHEADERS=${HEADERS} -P ${SCRIPT}
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  if(verdict STREQUAL "pass" AND NOT rc EQUAL 0)
    set(wrong "${wrong}\n${name}: should pass, the check failed:\n${err}" PARENT_SCOPE)
  elseif(verdict STREQUAL "fail" AND rc EQUAL 0)
    set(wrong "${wrong}\n${name}: should fail (a supported ViSP does not install the header), the check passed" PARENT_SCOPE)
  endif()
endfunction()

expect(everywhere pass "#include <visp3/core/vpMatrix.h>\n#include <visp3/projective/vpServoProjective.h>\n")
expect(unguarded fail "#include <visp3/core/vpMatrix.h>\n#include <visp3/robot/vpAfma4.h>\n")
expect(guarded pass "#include <visp3/core/vpConfig.h>\n#if VISP_VERSION_INT < VP_VERSION_INT(3, 7, 0) // removed\n#include <visp3/robot/vpAfma4.h>\n#endif\n")
expect(guard_too_wide fail "#if VISP_VERSION_INT < VP_VERSION_INT(3, 7, 1)\n#include <visp3/robot/vpAfma4.h>\n#endif\n")
expect(guard_reversed fail "#if VISP_VERSION_INT >= VP_VERSION_INT(3, 7, 0)\n#include <visp3/robot/vpAfma4.h>\n#endif\n")
expect(in_else pass "#if VISP_VERSION_INT >= VP_VERSION_INT(3, 7, 0)\n#include <visp3/gui/vpDisplayFactory.h>\n#else\n#include <visp3/robot/vpAfma4.h>\n#endif\n")
expect(in_elif pass "#if VISP_VERSION_INT >= VP_VERSION_INT(3, 7, 0)\n#include <visp3/core/vpHSV.h>\n#elif VISP_VERSION_INT >= VP_VERSION_INT(3, 6, 0)\n#include <visp3/core/vpRGBf.h>\n#endif\n")
expect(elif_too_wide fail "#if VISP_VERSION_INT >= VP_VERSION_INT(3, 7, 0)\n#include <visp3/core/vpHSV.h>\n#elif VISP_VERSION_INT >= VP_VERSION_INT(3, 5, 0)\n#include <visp3/core/vpRGBf.h>\n#endif\n")
expect(new_header_unguarded fail "#include <visp3/gui/vpDisplayFactory.h>\n")
expect(nested_in_feature_test pass "#ifdef VISP_HAVE_X11\n#if defined(VISP_HAVE_APRILTAG) && VISP_VERSION_INT >= VP_VERSION_INT(3, 7, 0)\n#include <visp3/gui/vpDisplayFactory.h>\n#endif\n#endif\n")
expect(feature_test_only fail "#ifdef VISP_HAVE_AFMA4\n#include <visp3/robot/vpAfma4.h>\n#endif\n")
expect(unknown_header fail "#include <visp3/core/vpMatrixx.h>\n")
expect(unreadable_version_test fail "#if VISP_VERSION_INT < VP_VERSION_INT(3, 7, 0) || defined(X)\n#include <visp3/core/vpMatrix.h>\n#endif\n")

if(wrong)
  message(FATAL_ERROR "check-visp-headers.cmake gave a wrong verdict:${wrong}")
endif()
message(STATUS "check-visp-headers.cmake: 13 verdicts as expected")
