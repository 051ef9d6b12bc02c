# examples/library_example.cpp, the README's library example: it builds, runs, and finds the
# default study's cone (Eb_hat = 1.948876 at phi_e = 1 measured; the cone_branch study of
# examples/scenes/cone_h004.json gives 1.94877 there, linearly interpolated between samples
# 0.1 apart, which is within that interpolation's error of 1e-4), and README.md shows the file
# exactly as it is compiled. Variables: PROGRAM, SOURCE, README.
execute_process(COMMAND "${PROGRAM}" RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "library_example failed (${rc}):\n${log}\n${err}")
endif()
if(NOT log MATCHES "phi_e = 1\\.0 [^\n]*Eb_hat = ([0-9.]+) 1/m")
  message(FATAL_ERROR "library_example printed no line for phi_e = 1.0:\n${log}")
endif()
set(eb ${CMAKE_MATCH_1})
if(eb LESS 1.9487 OR eb GREATER 1.9491)
  message(FATAL_ERROR "library_example: Eb_hat(1.0) = ${eb}, not 1.94888 +- 1e-4 relative")
endif()
file(READ "${SOURCE}" source)
file(READ "${README}" readme)
string(FIND "${readme}" "```cpp\n${source}```" at)
if(at EQUAL -1)
  message(FATAL_ERROR "README.md does not show examples/library_example.cpp as it is (a ```cpp "
                      "block holding the whole file)")
endif()
message(STATUS "library_example: Eb_hat(1.0) = ${eb}")
