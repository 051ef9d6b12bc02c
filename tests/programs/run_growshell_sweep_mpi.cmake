# Runs `mpiexec -n 2 growshell sweep` over three thicknesses of a small scene and the same
# sweep on one process, and checks: every point was run exactly once, by one of the ranks;
# both sweeps' sweep.json have every point completed with the same results (the studies are
# deterministic; wall_seconds aside); a bad value is refused by rank 0 before anything is
# written. Variables: PROGRAM, MPIEXEC, OUT.
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
file(WRITE "${OUT}/small.json"
     "{\"mesh\": {\"size_slope\": 0.25}, \"continuation\": {\"phi_max\": 0.06}, "
     "\"output\": {\"write_vtk\": false}}\n")
# OpenMPI refuses root without these (CI runs as root); --oversubscribe lets 2 ranks share
# fewer cores.
set(ENV{OMPI_ALLOW_RUN_AS_ROOT} 1)
set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} 1)
# Containers often forbid the cross-memory attach that OpenMPI's shared-memory transport uses
# for large messages; copying through the shared segment works everywhere.
set(ENV{OMPI_MCA_btl_vader_single_copy_mechanism} none)
set(points thickness=0.04,0.05,0.045)
execute_process(COMMAND "${MPIEXEC}" -n 2 --oversubscribe "${PROGRAM}" sweep "${OUT}/small.json"
                        --out "${OUT}/mpi" --param ${points}
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mpiexec -n 2 growshell sweep failed (${rc}):\n${log}\n${err}")
endif()
if(NOT EXISTS "${OUT}/mpi/sweep.png" AND NOT log MATCHES "figure skipped")
  message(FATAL_ERROR "rank 0 neither drew sweep.png nor said why not:\n${log}")
endif()
if(NOT log MATCHES "3 points on 2 MPI ranks")
  message(FATAL_ERROR "the sweep did not run on 2 ranks:\n${log}")
endif()
foreach(p 000 001 002)
  string(REGEX MATCHALL "\\[rank [01]\\] # point point_${p}\n" starts "${log}")
  list(LENGTH starts k)
  if(NOT k EQUAL 1)
    message(FATAL_ERROR "point_${p} was started ${k} times:\n${log}")
  endif()
endforeach()
execute_process(COMMAND "${PROGRAM}" sweep "${OUT}/small.json" --out "${OUT}/serial"
                        --param ${points}
                RESULT_VARIABLE rc OUTPUT_VARIABLE slog ERROR_VARIABLE serr)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the serial sweep failed (${rc}):\n${slog}\n${serr}")
endif()
file(READ "${OUT}/mpi/sweep.json" mpi)
file(READ "${OUT}/serial/sweep.json" serial)
foreach(i 0 1 2)
  string(JSON status GET "${mpi}" points ${i} status)
  if(NOT status STREQUAL "completed")
    message(FATAL_ERROR "MPI point ${i}: ${status}")
  endif()
  foreach(key phi_branch phi_last eb_hat_max thickness)
    string(JSON a GET "${mpi}" points ${i} results ${key})
    string(JSON b GET "${serial}" points ${i} results ${key})
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "point ${i} ${key}: ${a} on 2 ranks, ${b} on one process")
    endif()
  endforeach()
endforeach()
# A bad value: refused by rank 0, nothing written.
execute_process(COMMAND "${MPIEXEC}" -n 2 --oversubscribe "${PROGRAM}" sweep "${OUT}/small.json"
                        --out "${OUT}/bad" --param thickness=0.04,-1
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "thickness = -1 must be finite and > 0")
  message(FATAL_ERROR "a bad value was not refused by name (${rc}):\n${log}\n${err}")
endif()
if(EXISTS "${OUT}/bad")
  message(FATAL_ERROR "the refused MPI sweep wrote ${OUT}/bad")
endif()
