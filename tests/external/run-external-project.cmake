# ctest case external_project: installs the built plugin into a temporary prefix, then configures, builds and runs
# the external project of this directory against it.
#   cmake -DBUILD_DIR=<plugin build> -DWORK_DIR=<scratch> -DGENERATOR=<generator> [-DCONFIG=<config>]
#         [-DVISP_DIR=<the ViSP the plugin was built with>] [-DCXX_COMPILER=<the compiler the plugin was built with>]
#         [-DPYTHON=<the Python of the module> -DPYTHON_INSTALL_DIR=<where the module is installed, prefix-relative>]
#         -P run-external-project.cmake
foreach(var BUILD_DIR WORK_DIR GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "${var} is not set")
  endif()
endforeach()
if(NOT CONFIG)
  set(CONFIG Release)
endif()
set(prefix "${WORK_DIR}/prefix")
set(build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# The sub-build must find the ViSP the plugin was built with, not whichever ViSP is in /usr.
set(visp_dir "")
if(VISP_DIR)
  set(visp_dir "-DVISP_DIR=${VISP_DIR}")
endif()
# ... and its compiler: a sanitizer build's exported flags name the compiler's own sanitizer runtime.
set(cxx_compiler "")
if(CXX_COMPILER)
  set(cxx_compiler "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${step} failed (${rc}): ${ARGN}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run("install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}" --config "${CONFIG}")
foreach(f include/visp3/projective/vpProjectiveStereoRig.h include/visp3/projective/vpProjectiveRobot.h)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "not installed: ${prefix}/${f}")
  endif()
endforeach()
file(GLOB config "${prefix}/lib*/cmake/visp_projective/visp_projectiveConfig.cmake"
                 "${prefix}/lib/*/cmake/visp_projective/visp_projectiveConfig.cmake")
file(GLOB version "${prefix}/lib*/cmake/visp_projective/visp_projectiveConfigVersion.cmake"
                  "${prefix}/lib/*/cmake/visp_projective/visp_projectiveConfigVersion.cmake")
if(NOT config OR NOT version)
  message(FATAL_ERROR "package configuration not installed under ${prefix}")
endif()

# The installed Python module imports from the prefix alone and uses the installed library (its RUNPATH, relative to
# the module, finds the prefix's, not the build tree's): check-python-module.py.
if(PYTHON)
  run("python module" ${CMAKE_COMMAND} -E env "PYTHONPATH=${prefix}/${PYTHON_INSTALL_DIR}" "${PYTHON}"
      "${CMAKE_CURRENT_LIST_DIR}/check-python-module.py" "${prefix}")
  if(NOT last_output MATCHES "(^|\n)OK\n")
    message(FATAL_ERROR "the installed Python module did not print OK")
  endif()
endif()

run("configure" ${CMAKE_COMMAND} -S "${CMAKE_CURRENT_LIST_DIR}" -B "${build}" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=${CONFIG} -DCMAKE_PREFIX_PATH=${prefix} -DEXPECTED_PREFIX=${prefix} ${visp_dir} ${cxx_compiler})
run("build" ${CMAKE_COMMAND} --build "${build}" --config "${CONFIG}")
find_program(exe external_main PATHS "${build}" "${build}/${CONFIG}" NO_DEFAULT_PATH)
if(NOT exe)
  message(FATAL_ERROR "external_main not built in ${build}")
endif()
run("run" "${exe}")
if(NOT last_output MATCHES "(^|\n)OK\n")
  message(FATAL_ERROR "external_main did not print OK")
endif()
