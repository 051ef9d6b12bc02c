# Runs `growshell sweep` over two thicknesses on a small scene and checks: sweep.json and
# sweep.csv hold both points with their results, equal to those of `growshell run` of the same
# point; --resume runs nothing again and changes nothing; a point killed after its last
# commit is resumed from its record; a bad value is refused by name before anything is
# written; a point that fails is reported with its reason while the others complete (exit 3).
# Variables: PROGRAM, OUT.
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
set(sweep "${OUT}/sweep")
file(WRITE "${OUT}/small.json"
     "{\"mesh\": {\"size_slope\": 0.25}, \"continuation\": {\"phi_max\": 0.06}, "
     "\"output\": {\"write_vtk\": false}}\n")
execute_process(COMMAND "${PROGRAM}" sweep "${OUT}/small.json" --out "${sweep}"
                        --param thickness=0.04,0.05
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "growshell sweep failed (${rc}):\n${log}\n${err}")
endif()
file(READ "${sweep}/sweep.json" summary)
string(JSON n LENGTH "${summary}" points)
if(NOT n EQUAL 2)
  message(FATAL_ERROR "sweep.json has ${n} points, not 2:\n${summary}")
endif()
foreach(i 0 1)
  string(JSON status GET "${summary}" points ${i} status)
  string(JSON h GET "${summary}" points ${i} params thickness)
  string(JSON h_run GET "${summary}" points ${i} results thickness)
  string(JSON phi_branch_${i} GET "${summary}" points ${i} results phi_branch)
  if(NOT status STREQUAL "completed" OR NOT h EQUAL h_run)
    message(FATAL_ERROR "point ${i}: status ${status}, thickness ${h} (results: ${h_run})")
  endif()
endforeach()
# The first branch point at h = 0.04 and 0.05 (c2 h^2 = 0.016963, 0.026505), within 2 %.
if(phi_branch_0 LESS 0.0166 OR phi_branch_0 GREATER 0.0173 OR phi_branch_1 LESS 0.0260
   OR phi_branch_1 GREATER 0.0271)
  message(FATAL_ERROR "phi_branch ${phi_branch_0}, ${phi_branch_1}: not near c2 h^2")
endif()
# The figure, when /usr/bin/python3 has matplotlib; otherwise a note why not.
execute_process(COMMAND /usr/bin/python3 -c "import matplotlib" RESULT_VARIABLE no_matplotlib
                OUTPUT_QUIET ERROR_QUIET)
if(no_matplotlib EQUAL 0)
  if(NOT EXISTS "${sweep}/sweep.png" OR NOT log MATCHES "wrote [^\n]*/sweep.png")
    message(FATAL_ERROR "matplotlib is importable but growshell sweep drew no sweep.png:\n${log}")
  endif()
elseif(NOT log MATCHES "figure skipped: [^\n]*matplotlib")
  message(FATAL_ERROR "no matplotlib, and growshell sweep did not say the figure was skipped:\n${log}")
endif()
file(STRINGS "${sweep}/sweep.csv" csv)
list(LENGTH csv rows)
list(GET csv 0 header)
if(NOT rows EQUAL 3 OR NOT header MATCHES "^index,directory,thickness,status,.*phi_branch")
  message(FATAL_ERROR "sweep.csv: ${rows} lines, header ${header}")
endif()

# The same point alone gives the same results.
execute_process(COMMAND "${PROGRAM}" run "${OUT}/small.json" --out "${OUT}/alone"
                        --set thickness=0.05
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
file(READ "${OUT}/alone/results.json" alone)
string(JSON phi_alone GET "${alone}" phi_branch)
if(NOT rc EQUAL 0 OR NOT phi_alone STREQUAL phi_branch_1)
  message(FATAL_ERROR "growshell run at thickness 0.05 gives phi_branch ${phi_alone}, the sweep "
                      "${phi_branch_1} (${rc}: ${err})")
endif()

# A second sweep into the directory is refused; --resume with other values is refused by name;
# --resume with the same plan runs nothing.
execute_process(COMMAND "${PROGRAM}" sweep "${OUT}/small.json" --out "${sweep}"
                        --param thickness=0.04,0.05
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "not empty.*--resume.*--overwrite")
  message(FATAL_ERROR "a second sweep into ${sweep} was not refused (${rc}): ${err}")
endif()
execute_process(COMMAND "${PROGRAM}" sweep "${OUT}/small.json" --out "${sweep}"
                        --param thickness=0.04,0.03 --resume
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "parameters differ")
  message(FATAL_ERROR "--resume with other values was not refused (${rc}): ${err}")
endif()
execute_process(COMMAND "${PROGRAM}" sweep "${OUT}/small.json" --out "${sweep}"
                        --param thickness=0.04,0.05 --resume
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
file(READ "${sweep}/sweep.json" again)
if(NOT rc EQUAL 0 OR log MATCHES "switching onto" OR NOT again STREQUAL summary)
  message(FATAL_ERROR "--resume of a finished sweep ran a study or changed sweep.json (${rc}):\n${log}")
endif()

# A point killed after its last commit (no results.json, a row past the commit) is resumed.
file(REMOVE "${sweep}/point_001/results.json")
file(APPEND "${sweep}/point_001/branch.csv" "9,9,9,9,9,9,9,9,9,9,9,9,9,9\n")
execute_process(COMMAND "${PROGRAM}" sweep "${OUT}/small.json" --out "${sweep}"
                        --param thickness=0.04,0.05 --resume
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
file(READ "${sweep}/sweep.json" resumed)
string(JSON phi_resumed GET "${resumed}" points 1 results phi_branch)
if(NOT rc EQUAL 0 OR NOT log MATCHES "point_001[^\n]*\n.*resuming from" OR NOT phi_resumed STREQUAL phi_branch_1)
  message(FATAL_ERROR "the killed point was not resumed, or changed phi_branch to ${phi_resumed} "
                      "(${rc}):\n${log}")
endif()
file(STRINGS "${sweep}/point_001/branch.csv" point_rows)
foreach(row IN LISTS point_rows)
  if(row MATCHES "^9,9,9")
    message(FATAL_ERROR "the resumed point kept the killed run's uncommitted row")
  endif()
endforeach()

# A bad value is refused by name before anything is written.
execute_process(COMMAND "${PROGRAM}" sweep "${OUT}/small.json" --out "${OUT}/bad"
                        --param thickness=0.04,-1
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "point_001 \\(thickness=-1\\): thickness = -1" OR EXISTS "${OUT}/bad")
  message(FATAL_ERROR "a bad sweep value was not refused by name, or wrote ${OUT}/bad (${rc}): ${err}")
endif()

# A point that fails (its record corrupted) is reported with its reason, and the other stays
# completed: exit status 3.
file(REMOVE "${sweep}/point_001/results.json")
file(WRITE "${sweep}/point_001/record.json" "garbage\n")
execute_process(COMMAND "${PROGRAM}" sweep "${OUT}/small.json" --out "${sweep}"
                        --param thickness=0.04,0.05 --resume
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
file(READ "${sweep}/sweep.json" failing)
string(JSON status_0 GET "${failing}" points 0 status)
string(JSON status_1 GET "${failing}" points 1 status)
string(JSON reason_1 GET "${failing}" points 1 reason)
string(JSON results_1 TYPE "${failing}" points 1 results)
if(NOT rc EQUAL 3 OR NOT status_0 STREQUAL "completed" OR NOT status_1 STREQUAL "failed"
   OR NOT reason_1 MATCHES "record.json" OR NOT results_1 STREQUAL "NULL")
  message(FATAL_ERROR "a failing point: exit ${rc}, statuses ${status_0} ${status_1}, reason "
                      "'${reason_1}', results ${results_1}:\n${log}\n${err}")
endif()
message(STATUS "growshell sweep: phi_branch ${phi_branch_0}, ${phi_branch_1}")
