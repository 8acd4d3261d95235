# ctest case namespace_pattern: the plugin compiles against a ViSP built with ENABLE_VISP_NAMESPACE=ON (every ViSP class
# in namespace visp, ViSP 3.7 and later) only if it follows ViSP's own pattern everywhere. CI has no such ViSP (Debian
# 12 ships 3.5), so the pattern is checked here, file by file:
#  - every public header includes vpProjectiveConfig.h (which defines the macros on ViSP 3.5 and 3.6) and wraps its
#    declarations in BEGIN_VISP_NAMESPACE / END_VISP_NAMESPACE;
#  - every private header that includes a ViSP header says "using namespace VISP_NAMESPACE_NAME;" under
#    "#ifdef ENABLE_VISP_NAMESPACE", and so does every source, test, tutorial, app and Python binding file, or it
#    includes ("...") one of those private headers of its own folder tree, which says it for it (a source's first
#    lines are its includes: no ViSP name stands before them).
#   cmake -DSOURCE_DIR=<repo> -P check-namespace-pattern.cmake
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "SOURCE_DIR is not set")
endif()
set(bad "")
file(GLOB public_headers "${SOURCE_DIR}/include/visp3/projective/*.h")
foreach(f ${public_headers})
  file(READ "${f}" text)
  get_filename_component(name "${f}" NAME)
  if(name STREQUAL "vpProjectiveConfig.h")
    continue()
  endif()
  if(NOT text MATCHES "#include <visp3/projective/vpProjectiveConfig.h>" OR NOT text MATCHES "\nBEGIN_VISP_NAMESPACE\n"
     OR NOT text MATCHES "\nEND_VISP_NAMESPACE\n")
    list(APPEND bad "${f}: a public header includes vpProjectiveConfig.h and wraps its declarations in BEGIN_VISP_NAMESPACE / END_VISP_NAMESPACE")
  endif()
endforeach()
file(GLOB_RECURSE sources "${SOURCE_DIR}/src/*.cpp" "${SOURCE_DIR}/src/*.h" "${SOURCE_DIR}/tests/*.cpp"
     "${SOURCE_DIR}/tests/*.h" "${SOURCE_DIR}/tutorials/*.cpp" "${SOURCE_DIR}/tutorials/*.h" "${SOURCE_DIR}/apps/*.cpp"
     "${SOURCE_DIR}/apps/*.h" "${SOURCE_DIR}/python/*.cpp" "${SOURCE_DIR}/python/*.h")
set(pattern "#ifdef ENABLE_VISP_NAMESPACE\nusing namespace VISP_NAMESPACE_NAME;\n#endif")
foreach(f ${sources})
  file(READ "${f}" text)
  if(f MATCHES "\\.h$" AND NOT text MATCHES "#include <visp3/")
    continue() # a private header that names no ViSP type
  endif()
  if(text MATCHES "${pattern}")
    continue()
  endif()
  # A quoted include of a private header that carries the pattern, looked up as the build does: from src/ and tests/
  # (the include folders) and from the file's own folder.
  set(carried FALSE)
  get_filename_component(dir "${f}" DIRECTORY)
  string(REGEX MATCHALL "#include \"[^\"]+\"" includes "${text}")
  foreach(inc ${includes})
    string(REGEX REPLACE "#include \"([^\"]+)\"" "\\1" inc "${inc}")
    foreach(candidate "${SOURCE_DIR}/src/${inc}" "${SOURCE_DIR}/tests/${inc}" "${dir}/${inc}")
      if(NOT carried AND EXISTS "${candidate}")
        file(READ "${candidate}" header)
        if(header MATCHES "${pattern}")
          set(carried TRUE)
        endif()
      endif()
    endforeach()
  endforeach()
  if(NOT carried)
    list(APPEND bad "${f}: add '#ifdef ENABLE_VISP_NAMESPACE / using namespace VISP_NAMESPACE_NAME; / #endif' after the includes")
  endif()
endforeach()
if(bad)
  string(REPLACE ";" "\n" bad "${bad}")
  message(FATAL_ERROR "ViSP namespace pattern broken:\n${bad}")
endif()
list(LENGTH public_headers nh)
list(LENGTH sources ns)
message(STATUS "namespace pattern holds in ${nh} public headers and ${ns} other files")
