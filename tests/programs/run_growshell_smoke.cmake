# Runs `growshell run` on a small scene (h = 0.04, rings mesh with size_slope 0.25, up to
# phi_e = 0.3) and checks its results.json, figure and binary VTU (drawn by render_surface.py); that a second run into the same
# directory is refused and changes nothing; that bad input is refused by name and writes
# nothing; and that --resume continues the record from its last commit without repeating a
# row, dropping what a killed run left uncommitted. Variables: PROGRAM, SOURCE_DIR, OUT.
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
set(run "${OUT}/run")
file(WRITE "${OUT}/small.json"
     "{\"thickness\": 0.04, \"mesh\": {\"size_slope\": 0.25}, \"continuation\": {\"phi_max\": 0.3}}\n")
execute_process(COMMAND "${PROGRAM}" run "${OUT}/small.json" --out "${run}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "growshell run failed (${rc}):\n${log}\n${err}")
endif()

# results.json: named keys.
file(READ "${run}/results.json" results)
string(JSON study GET "${results}" study)
string(JSON family GET "${results}" mesh family)
string(JSON phi_branch GET "${results}" phi_branch)
string(JSON phi_last GET "${results}" phi_last)
string(JSON kiss TYPE "${results}" phi_kiss)
if(NOT study STREQUAL "cone_branch" OR NOT family STREQUAL "rings")
  message(FATAL_ERROR "results.json: study = ${study}, mesh.family = ${family}:\n${results}")
endif()
# The first branch point on this mesh is 0.017151 (measured; c2 h^2 = 0.016963): within 0.5 %.
if(phi_branch LESS 0.017065 OR phi_branch GREATER 0.017237)
  message(FATAL_ERROR "results.json: phi_branch = ${phi_branch}, not within 0.5 % of 0.017151")
endif()
if(phi_last LESS 0.3 OR NOT kiss STREQUAL "NULL")
  message(FATAL_ERROR "results.json: phi_last = ${phi_last}, phi_kiss ${kiss}:\n${results}")
endif()
foreach(f branch.csv events.json record.json scene.json cost.json states/point_00005.state)
  if(NOT EXISTS "${run}/${f}")
    message(FATAL_ERROR "growshell run wrote no ${f}")
  endif()
endforeach()

# The figure, when /usr/bin/python3 has matplotlib; otherwise a note why not.
execute_process(COMMAND /usr/bin/python3 -c "import matplotlib" RESULT_VARIABLE no_matplotlib
                OUTPUT_QUIET ERROR_QUIET)
if(no_matplotlib EQUAL 0)
  if(NOT EXISTS "${run}/eb_hat.png")
    message(FATAL_ERROR "matplotlib is importable but growshell run drew no eb_hat.png:\n${log}")
  endif()
elseif(NOT log MATCHES "figure skipped: [^\n]*matplotlib")
  message(FATAL_ERROR "no matplotlib, and growshell run did not say the figure was skipped:\n${log}")
endif()
# The VTU snapshots are binary (appended raw); scripts/render_surface.py reads them.
file(READ "${run}/last.vtu" vtu LIMIT 400)
if(NOT vtu MATCHES "format=\"appended\" offset=\"0\"")
  message(FATAL_ERROR "last.vtu is not appended raw:\n${vtu}")
endif()
if(no_matplotlib EQUAL 0)
  execute_process(COMMAND /usr/bin/python3 "${SOURCE_DIR}/scripts/render_surface.py"
                          "${run}/last.vtu" "${OUT}/last.png" --log --phi 0.3
                  RESULT_VARIABLE rc OUTPUT_VARIABLE rlog ERROR_VARIABLE rerr)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${OUT}/last.png")
    message(FATAL_ERROR "render_surface.py could not draw last.vtu (${rc}):\n${rlog}\n${rerr}")
  endif()
endif()

# Every file of a directory with its hash, to see that a refused run changes nothing.
function(directory_state dir out)
  file(GLOB_RECURSE files LIST_DIRECTORIES true RELATIVE "${dir}" "${dir}/*")
  list(SORT files)
  set(state "")
  foreach(f IN LISTS files)
    if(IS_DIRECTORY "${dir}/${f}")
      string(APPEND state "${f}/\n")
    else()
      file(SHA256 "${dir}/${f}" hash)
      string(APPEND state "${f} ${hash}\n")
    endif()
  endforeach()
  set(${out} "${state}" PARENT_SCOPE)
endfunction()
directory_state("${run}" before)

# A second run into the same directory without --resume or --overwrite is refused.
execute_process(COMMAND "${PROGRAM}" run "${OUT}/small.json" --out "${run}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "is not empty.*--resume.*--overwrite")
  message(FATAL_ERROR "a second run into ${run} was not refused (${rc}):\n${log}\n${err}")
endif()
directory_state("${run}" after)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "the refused run changed ${run}")
endif()

# A bad study key is refused by name and writes nothing, even with --overwrite.
file(WRITE "${OUT}/bad.json" "{\"thickness\": 0.04, \"study\": {\"tolerance\": -1}}\n")
file(WRITE "${OUT}/unknown.json" "{\"study\": {\"kind\": \"cone\"}}\n")
# A mesh whose rim cannot resolve the fold count (16 vertices): refused before the flat trace.
file(WRITE "${OUT}/coarse.json" "{\"thickness\": 0.04, \"mesh\": {\"size_slope\": 0.3}}\n")
foreach(bad IN ITEMS "bad.json;study.tolerance = -1" "unknown.json;study.kind"
                     "coarse.json;too coarse to count the cone's folds: rim has 16 vertices")
  list(GET bad 0 scene)
  list(GET bad 1 key)
  execute_process(COMMAND "${PROGRAM}" run "${OUT}/${scene}" --out "${OUT}/bad"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "${key}")
    message(FATAL_ERROR "${scene} was not refused naming ${key} (${rc}):\n${err}")
  endif()
  if(EXISTS "${OUT}/bad")
    message(FATAL_ERROR "the refused ${scene} wrote ${OUT}/bad")
  endif()
  execute_process(COMMAND "${PROGRAM}" run "${OUT}/${scene}" --out "${run}" --overwrite
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  directory_state("${run}" after)
  if(rc EQUAL 0 OR NOT before STREQUAL after)
    message(FATAL_ERROR "${scene} with --overwrite was not refused, or changed ${run} (${rc})")
  endif()
endforeach()

# --set with an unknown key, or without '=', is refused by name and changes nothing.
foreach(bad IN ITEMS "mesh.ringz=3;unknown key 'mesh.ringz'" "thickness;takes KEY=VALUE"
                     "study.tolerance=-1;study.tolerance = -1")
  list(GET bad 0 setting)
  list(GET bad 1 message)
  execute_process(COMMAND "${PROGRAM}" run "${OUT}/small.json" --out "${run}" --overwrite
                          --set "${setting}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  directory_state("${run}" after)
  if(rc EQUAL 0 OR NOT err MATCHES "${message}" OR NOT before STREQUAL after)
    message(FATAL_ERROR "--set ${setting} was not refused naming '${message}', or changed "
                        "${run} (${rc}):\n${err}")
  endif()
endforeach()

# --resume with a scene that would change the states already traced is refused by key.
file(WRITE "${OUT}/thinner.json"
     "{\"thickness\": 0.03, \"mesh\": {\"size_slope\": 0.25}, \"continuation\": {\"phi_max\": 0.4}}\n")
execute_process(COMMAND "${PROGRAM}" run "${OUT}/thinner.json" --out "${run}" --resume
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
directory_state("${run}" after)
if(rc EQUAL 0 OR NOT err MATCHES "thickness = 0.04" OR NOT before STREQUAL after)
  message(FATAL_ERROR "--resume with another thickness was not refused by name (${rc}):\n${err}")
endif()

# --resume after a killed run: a row and a state written after the last commit are dropped,
# and the record goes on to the new phi_max without repeating a row.
file(STRINGS "${run}/branch.csv" rows_before)
list(LENGTH rows_before n_before)
file(APPEND "${run}/branch.csv" "9,9,9,9,9,9,9,9,9,9,9,9,9,9\n")
file(WRITE "${run}/states/.point_00099.state.tmp" "partial")
# The longer trace is the first scene with --set continuation.phi_max=0.4.
execute_process(COMMAND "${PROGRAM}" run "${OUT}/small.json" --out "${run}" --resume
                        --set continuation.phi_max=0.4
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT log MATCHES "resuming from")
  message(FATAL_ERROR "--resume failed (${rc}):\n${log}\n${err}")
endif()
file(STRINGS "${run}/branch.csv" rows_after)
list(LENGTH rows_after n_after)
if(NOT n_after GREATER n_before)
  message(FATAL_ERROR "--resume appended no rows")
endif()
math(EXPR last_before "${n_before} - 1")
set(previous_phi -1)
set(previous_s -1)
foreach(i RANGE 1 ${last_before})
  list(GET rows_before ${i} a)
  list(GET rows_after ${i} b)
  if(NOT a STREQUAL b)
    message(FATAL_ERROR "--resume changed row ${i}: ${a} -> ${b}")
  endif()
endforeach()
math(EXPR last_after "${n_after} - 1")
foreach(i RANGE 1 ${last_after})
  list(GET rows_after ${i} row)
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 0 phi)
  list(GET fields 8 s)
  if(NOT phi GREATER previous_phi OR NOT s GREATER previous_s)
    message(FATAL_ERROR "branch.csv row ${i} repeats or goes back (phi_e ${phi}, arclength ${s}) "
                        "after --resume")
  endif()
  set(previous_phi ${phi})
  set(previous_s ${s})
endforeach()
if(EXISTS "${run}/states/.point_00099.state.tmp")
  message(FATAL_ERROR "--resume left the killed run's temporary in states/")
endif()
math(EXPR states_expected "${n_after} - 1")
file(GLOB states "${run}/states/*")
list(LENGTH states n_states)
if(NOT n_states EQUAL states_expected)
  message(FATAL_ERROR "${n_states} saved states for ${states_expected} rows after --resume")
endif()
file(READ "${run}/results.json" results)
string(JSON phi_last GET "${results}" phi_last)
string(JSON phi_branch_after GET "${results}" phi_branch)
file(READ "${run}/scene.json" scene_as_run)
string(JSON phi_max_as_run GET "${scene_as_run}" continuation phi_max)
if(NOT phi_max_as_run EQUAL 0.4)
  message(FATAL_ERROR "scene.json after --resume --set continuation.phi_max=0.4 says phi_max "
                      "${phi_max_as_run}")
endif()
if(phi_last LESS 0.4 OR NOT phi_branch_after EQUAL phi_branch)
  message(FATAL_ERROR "results.json after --resume: phi_last ${phi_last}, phi_branch "
                      "${phi_branch_after} (was ${phi_branch})")
endif()

# A study that does not fit in memory (here 600 MB of address space for a mesh of 186k
# vertices) is refused by name, with the mesh's size, and leaves no directory behind.
set(oom "${OUT}/out_of_memory")
execute_process(COMMAND sh -c "ulimit -v 600000 && exec \"$0\" run \"$1\" --out \"$2\" --set mesh.size_slope=0.01 --set thickness=0.002"
                        "${PROGRAM}" "${OUT}/small.json" "${oom}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "out of memory: the mesh of [0-9]+ vertices \\(about [0-9]+ unknowns\\)")
  message(FATAL_ERROR "a study too large for memory was not refused by name (${rc}):\n${log}\n${err}")
endif()
if(EXISTS "${oom}")
  message(FATAL_ERROR "the study too large for memory left ${oom} behind")
endif()
message(STATUS "growshell run: phi_branch ${phi_branch}, ${n_before} rows, ${n_after} after --resume")
