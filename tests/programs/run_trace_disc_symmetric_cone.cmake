# The two-fold cone at h = 0.04 on the default mesh, which has the cone's symmetry (mesh.family =
# rings, size_slope 0.1, core floor h/4: both mirrors and the quarter turn), traced by default
# in the mirror subspace, keeps its improper quarter-turn symmetry S4 (defect < 1e-3) and its
# stability (the index without the pattern's turn) up to first contact (gap = h, at the apex
# core, 5.652), as the h -> 0 cone does; the hexagonal lattice disc loses S4 there (defect
# 1e-3 at phi_e = 4.3). The eigenvalues show why the turn is left out of the index: it is the
# lowest mode, odd under both mirrors, and slightly negative on this mesh.
# Variables: PROGRAM (trace_disc), EIGEN_PROGRAM (branch_eigenvalues), SECTOR_PROGRAM
# (cone_mode_sectors), OUT.
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
# The exclusion radius is pi h / 2 (not the default 8 h), so that the trace meets the gap = h
# event at the apex core below 5.8 and stops there.
file(WRITE "${OUT}/scene.json"
     "{\"thickness\": 0.04, \"continuation\": {\"phi_max\": 5.8},\n"
     " \"physics\": {\"contact_exclusion_radius\": 0.06283185307179587}}\n")
execute_process(COMMAND "${PROGRAM}" "${OUT}/scene.json" --through-contact 1 --eigenmodes 0
                        --out "${OUT}/trace"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "trace_disc failed (${rc}):\n${log}\n${err}")
endif()
file(STRINGS "${OUT}/trace/branch.csv" rows)
list(LENGTH rows n)
math(EXPR last "${n} - 1")
set(h 0.04)
set(checked 0)
set(worst 0)
foreach(i RANGE 1 ${last})
  list(GET rows ${i} row)
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 0 phi)
  list(GET fields 5 gap)
  list(GET fields 6 negative)
  list(GET fields 11 defect)
  if(phi LESS 0.1 OR NOT gap GREATER h)
    continue()  # the switch onto the cone, or past first contact
  endif()
  math(EXPR checked "${checked} + 1")
  if(NOT defect LESS 1e-3)
    message(FATAL_ERROR "S4 defect ${defect} >= 1e-3 before first contact at phi_e = ${phi}: ${row}")
  endif()
  if(NOT negative EQUAL 0)
    message(FATAL_ERROR "the symmetric cone is unstable before first contact at phi_e = ${phi}: ${row}")
  endif()
  if(defect GREATER worst)
    set(worst ${defect})
  endif()
endforeach()
if(checked LESS 40)
  message(FATAL_ERROR "only ${checked} samples between phi_e = 0.1 and first contact")
endif()
file(READ "${OUT}/trace/events.json" events)
if(events MATCHES "symmetry_lost")
  message(FATAL_ERROR "events.json reports symmetry_lost:\n${events}")
endif()
if(NOT events MATCHES "\"kind\": \"contact\", \"phi_e\": 5\\.[5-9]")
  message(FATAL_ERROR "no first contact between phi_e = 5.5 and 6:\n${events}")
endif()
# The lowest eigenvalues at 5.0 and 5.6 in the full space (branch_eigenvalues: H v = lambda M v,
# M the lumped reference area, N/m^3, six rigid-motion pins): the lowest is the nearly free turn
# of the fold pattern: odd under both mirrors and even under S4 once its rigid part is removed
# (parities measured -0.9996 and +0.9996), its overlap with the turn field 0.99999, its
# eigenvalue measured -1.4e-3 at 5.09 and -4.5e-3 at 5.59. (The next eigenvalue there, 0.2, is
# the turn mixed with a rigid motion that the pins hold weakly, not a mode of the sheet: the
# sectors below give the sheet's.)
execute_process(COMMAND "${EIGEN_PROGRAM}" "${OUT}/trace" --count 2 --at 5.0,5.6
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "branch_eigenvalues failed (${rc}):\n${log}\n${err}")
endif()
file(STRINGS "${OUT}/trace/eigenvalues.csv" eigen_rows)
list(LENGTH eigen_rows eigen_n)
if(NOT eigen_n EQUAL 3)
  message(FATAL_ERROR "eigenvalues.csv has ${eigen_n} lines, not a header and 2 states")
endif()
foreach(i RANGE 1 2)
  list(GET eigen_rows ${i} row)
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 1 lambda1)
  list(GET fields 5 parity_x1)
  list(GET fields 7 parity_y1)
  list(GET fields 9 parity_s4_1)
  list(GET fields 13 turn_overlap1)
  if(lambda1 GREATER 1e-2 OR lambda1 LESS -1e-2 OR NOT parity_x1 LESS -0.99 OR NOT parity_y1 LESS -0.99
     OR NOT parity_s4_1 GREATER 0.99 OR NOT turn_overlap1 GREATER 0.999)
    message(FATAL_ERROR "the lowest eigenvalue is not the nearly free pattern turn (small, odd "
                        "under both mirrors, even under S4, the turn field): ${row}")
  endif()
endforeach()
# The sheet's softest modes class by class (cone_mode_sectors: each parity sector of the two
# mirrors with its own rigid motions removed), at 5.0, against ../shared/docs/physics.md's h -> 0
# cone, whose lowest modes are B2 < E < B1, all positive. Measured on this mesh: B2 1.674, E
# 2.170, B1 8.360, the turn (A2) -3.9e-3; the gmsh_d4 mesh gives B2 1.650 and E 2.207 (a 1.4 %
# and 1.7 % difference, docs/results.md, "The softest modes of the symmetric cone"), so B2 is
# asserted within 5 %. Each mode has its sector's S4 parity to 1e-3, and a positive rigid-free
# eigenvalue is above the pinned one, which a rigid shift of the mode lowers.
execute_process(COMMAND "${SECTOR_PROGRAM}" "${OUT}/trace" --count 2 --at 5.0
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cone_mode_sectors failed (${rc}):\n${log}\n${err}")
endif()
file(STRINGS "${OUT}/trace/mode_sectors.csv" sector_rows)
list(LENGTH sector_rows sector_n)
if(NOT sector_n EQUAL 7)
  message(FATAL_ERROR "mode_sectors.csv has ${sector_n} lines, not a header and 3 x 2 modes")
endif()
foreach(cls B2 E B1 A2)
  set(lowest_${cls} "")
endforeach()
foreach(i RANGE 1 6)
  list(GET sector_rows ${i} row)
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 1 sector)
  list(GET fields 2 cls)
  list(GET fields 3 lambda)
  list(GET fields 4 parity)
  list(GET fields 6 pinned)
  if(cls STREQUAL "?")
    message(FATAL_ERROR "a mode of sector ${sector} is neither even nor odd under S4: ${row}")
  endif()
  if(cls STREQUAL "E")
    if(parity GREATER 1e-3 OR parity LESS -1e-3)
      message(FATAL_ERROR "an E mode has S4 parity ${parity}, not 0: ${row}")
    endif()
  elseif(NOT (parity GREATER 0.999 OR parity LESS -0.999))
    message(FATAL_ERROR "S4 parity ${parity} is not +-1 to 1e-3: ${row}")
  endif()
  if(lambda GREATER 0 AND lambda LESS pinned)
    message(FATAL_ERROR "the rigid-free eigenvalue lies below the pinned one: ${row}")
  endif()
  if("${lowest_${cls}}" STREQUAL "" OR lambda LESS lowest_${cls})
    set(lowest_${cls} ${lambda})
  endif()
endforeach()
foreach(cls B2 E B1 A2)
  if("${lowest_${cls}}" STREQUAL "")
    message(FATAL_ERROR "no ${cls} mode at 5.0:\n${log}")
  endif()
endforeach()
if(lowest_B2 LESS 1.59 OR lowest_B2 GREATER 1.76)
  message(FATAL_ERROR "the softest B2 mode is ${lowest_B2} N/m^3, not 1.674 within 5 %:\n${log}")
endif()
if(NOT (lowest_B2 LESS lowest_E AND lowest_E LESS lowest_B1))
  message(FATAL_ERROR "the modes are not ordered B2 < E < B1 as the h -> 0 cone's:\n${log}")
endif()
if(lowest_A2 GREATER 1e-2 OR lowest_A2 LESS -1e-2)
  message(FATAL_ERROR "the pattern's turn (A2) is ${lowest_A2}, not near zero:\n${log}")
endif()
# --rings is the lattice family's resolution: with the rings family it is refused by name.
execute_process(COMMAND "${PROGRAM}" "${OUT}/scene.json" --rings 6 --out "${OUT}/bad"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "--rings 6 sets the resolution of mesh.family = lattice")
  message(FATAL_ERROR "--rings with the rings family was not refused by name (${rc}): ${err}")
endif()
if(EXISTS "${OUT}/bad")
  message(FATAL_ERROR "the refused run wrote ${OUT}/bad")
endif()
# A mesh file that does not exist is named, and nothing is written.
file(WRITE "${OUT}/missing_mesh.json"
     "{\"mesh\": {\"family\": \"file\", \"file\": \"${OUT}/no_such_mesh.msh\"}}\n")
execute_process(COMMAND "${PROGRAM}" "${OUT}/missing_mesh.json" --out "${OUT}/missing"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "no_such_mesh.msh")
  message(FATAL_ERROR "a missing mesh file was not named (${rc}): ${err}")
endif()
if(EXISTS "${OUT}/missing")
  message(FATAL_ERROR "the run with a missing mesh file wrote ${OUT}/missing")
endif()
message(STATUS "symmetric cone: ${checked} samples before first contact, largest S4 defect ${worst}")
