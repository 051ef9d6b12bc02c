# Run with `cmake -P` by the ctest test install_consumer (see tests/CMakeLists.txt).
# Installs the already built growshell into WORK_DIR/prefix, then configures, builds and runs
# the consumer project in CONSUMER_SOURCE_DIR against that prefix only.
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS GROWSHELL_BINARY_DIR GROWSHELL_SOURCE_DIR CONSUMER_SOURCE_DIR WORK_DIR
                     GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "install_consumer: -D${var}=... is required")
  endif()
endforeach()

set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/build")

# Runs a command, echoes it, and stops the test with its output on failure.
function(run_step what)
  message(STATUS "install_consumer: ${what}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install_consumer: ${what} failed (${rc}):\n${out}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

# Start from nothing, so a stale install or consumer cache cannot hide a packaging error.
file(REMOVE_RECURSE "${prefix}" "${consumer_build}")

set(config_args "")
if(CONFIG)
  set(config_args --config "${CONFIG}")
endif()
run_step("install into ${prefix}"
  "${CMAKE_COMMAND}" --install "${GROWSHELL_BINARY_DIR}" --prefix "${prefix}" ${config_args})

# The package must not point back into the source or build tree (it has to be relocatable).
file(GLOB_RECURSE package_files "${prefix}/*.cmake")
if(NOT package_files)
  message(FATAL_ERROR "install_consumer: no CMake package files were installed under ${prefix}")
endif()
foreach(f IN LISTS package_files)
  file(READ "${f}" text)
  foreach(tree IN ITEMS "${GROWSHELL_SOURCE_DIR}" "${GROWSHELL_BINARY_DIR}")
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "install_consumer: ${f} refers to ${tree}")
    endif()
  endforeach()
endforeach()
# One header of each top folder (core/ holds only headers, so it is easily forgotten).
foreach(header IN ITEMS core/sparse_objective.hpp libshell/mesh/triangle_mesh.hpp
                        solvers/newton/newton_solver.hpp studies/cone_branch_study.hpp)
  if(NOT EXISTS "${prefix}/include/growshell/${header}")
    message(FATAL_ERROR "install_consumer: ${header} is not installed under include/growshell/")
  endif()
endforeach()
# The installed driver runs from the prefix alone (its runpath finds the installed library)
# and finds the installed figure script.
if(EXISTS "${prefix}/bin/growshell")
  if(NOT EXISTS "${prefix}/share/growshell/plot_study.py")
    message(FATAL_ERROR "install_consumer: bin/growshell is installed without share/growshell/plot_study.py")
  endif()
  run_step("run the installed growshell --help" "${prefix}/bin/growshell" --help)
  if(NOT step_output MATCHES "cone_branch")
    message(FATAL_ERROR "install_consumer: growshell --help lists no cone_branch study:\n${step_output}")
  endif()
endif()

set(build_type_arg "")
if(CONFIG)
  set(build_type_arg "-DCMAKE_BUILD_TYPE=${CONFIG}")
endif()
run_step("configure consumer"
  "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${consumer_build}" -G "${GENERATOR}"
  "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" ${build_type_arg}
  "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXE_LINKER_FLAGS}"
  "-DCMAKE_PREFIX_PATH=${prefix}"
  # Only our fresh install may satisfy find_package(growshell).
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
  "-DGROWSHELL_EXPECTED_PREFIX=${prefix}")
run_step("build consumer" "${CMAKE_COMMAND}" --build "${consumer_build}" ${config_args})

find_program(consumer_exe NAMES growshell_consumer
  PATHS "${consumer_build}" "${consumer_build}/${CONFIG}" NO_DEFAULT_PATH NO_CACHE)
if(NOT consumer_exe)
  message(FATAL_ERROR "install_consumer: growshell_consumer was not built in ${consumer_build}")
endif()
run_step("run consumer" "${consumer_exe}")
message(STATUS "install_consumer: ${step_output}")
