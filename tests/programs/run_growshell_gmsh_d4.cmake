# The cone_branch study on the second mesh family with the cone's symmetry, gmsh_d4 (Gmsh's
# sector reflected into the disc: no structure shared with the default rings mesh), h = 0.04,
# size_slope 0.14, from flat to first contact. It must give the physics the rings mesh gives,
# within this coarse mesh's error as the convergence sweep of docs/results.md ("Two mesh
# families with the cone's symmetry") measured it:
#  - the study finds the mesh's mirrors and traces in the mirror subspace (no "full space" note,
#    which the unsymmetric gmsh family gets), and the flat disc's n = 2 mode is doubly
#    degenerate (a branch point of multiplicity 2), as on the perfect disc;
#  - phi_branch within [c2 h^2, +2 %] (c2 h^2 = 0.016963; measured 0.017205, +1.4 %; the
#    finest gmsh_d4 mesh gives +0.4 %);
#  - phi_max within 0.02 of 4.066 (the families' finest values are 4.0705 and 4.0601, the
#    default rings mesh's 4.0658; measured 4.0689);
#  - Eb_hat_max within [4.266, +1.5 %] (the rings' finest 4.2664, approached from above by
#    gmsh_d4 under refinement; measured 4.3148, +1.1 %);
#  - no negative eigenvalue without the pattern's turn before first contact, and S4 to
#    rounding (measured 5e-16; the unsymmetric gmsh mesh gives 1e-4 to 1e-2);
#  - the trace stops at first contact (gap = h at the apex core, with the exclusion radius
#    pi h / 2 set in the scene rather than the default 8 h) between 5.5 and 5.7 (measured
#    5.592);
#  - turned by 22.5 degrees off the mirror lines at 5.5 (study.orientation_check_at) the cone
#    relaxes to a state between 0.2 % and 1 % lower that breaks S4 (defect between 3e-3 and
#    8e-3), the energy falling inside r = h: the apex core's skew of docs/results.md ("The apex
#    core against the mesh"; measured -0.578 %, 0.0056 here, -0.66 %, 0.0052 at 5.4 on
#    gmsh_d4 at 0.1, -0.39 %, 0.0053 on the rings mesh).
# About a minute and a half. Variables: PROGRAM, OUT.
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
file(WRITE "${OUT}/d4.json"
     "{\"thickness\": 0.04, \"mesh\": {\"family\": \"gmsh_d4\", \"size_slope\": 0.14},\n"
     " \"physics\": {\"contact_exclusion_radius\": 0.06283185307179587},\n"
     " \"continuation\": {\"phi_max\": 6.0},\n"
     " \"study\": {\"eigenmodes\": 0, \"orientation_check_at\": 5.5},\n"
     " \"output\": {\"write_vtk\": false}}\n")
execute_process(COMMAND "${PROGRAM}" run "${OUT}/d4.json" --out "${OUT}/run"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "growshell run failed (${rc}):\n${log}\n${err}")
endif()
if(log MATCHES "full space")
  message(FATAL_ERROR "the cone on gmsh_d4 was not traced in the mirror subspace:\n${log}")
endif()
if(NOT log MATCHES "branch_point at phi_e = [0-9.]+ \\(multiplicity 2, negative 0 -> 2\\)")
  message(FATAL_ERROR "no doubly degenerate first branch point:\n${log}")
endif()
file(READ "${OUT}/run/results.json" results)
foreach(key phi_branch phi_max eb_hat_max phi_gap_h max_s4_defect_before_contact)
  string(JSON ${key} GET "${results}" ${key})
endforeach()
string(JSON family GET "${results}" mesh family)
string(JSON stability TYPE "${results}" phi_crit_stability)
if(NOT family STREQUAL "gmsh_d4")
  message(FATAL_ERROR "results.json: mesh.family = ${family}")
endif()
if(phi_branch LESS 0.016963 OR phi_branch GREATER 0.017302)
  message(FATAL_ERROR "phi_branch = ${phi_branch}, not within [c2 h^2, +2 %]:\n${results}")
endif()
if(phi_max LESS 4.046 OR phi_max GREATER 4.086)
  message(FATAL_ERROR "phi_max = ${phi_max}, not within 0.02 of 4.066:\n${results}")
endif()
if(eb_hat_max LESS 4.266 OR eb_hat_max GREATER 4.330)
  message(FATAL_ERROR "eb_hat_max = ${eb_hat_max}, not within [4.266, +1.5 %]:\n${results}")
endif()
if(NOT stability STREQUAL "NULL")
  message(FATAL_ERROR "the symmetric cone lost stability before first contact:\n${results}")
endif()
if(NOT max_s4_defect_before_contact LESS 1e-12)
  message(FATAL_ERROR "S4 defect ${max_s4_defect_before_contact} on a mesh with the quarter turn")
endif()
if(phi_gap_h LESS 5.5 OR phi_gap_h GREATER 5.7)
  message(FATAL_ERROR "first contact at ${phi_gap_h}, not between 5.5 and 5.7:\n${results}")
endif()
foreach(key orientation_energy_relative orientation_s4_defect orientation_energy_change_core)
  string(JSON ${key} GET "${results}" ${key})
endforeach()
if(orientation_energy_relative LESS -0.01 OR orientation_energy_relative GREATER -0.002)
  message(FATAL_ERROR "turned at 5.5 the cone is ${orientation_energy_relative} against the "
                      "traced one, not in [-0.01, -0.002]:\n${results}")
endif()
if(orientation_s4_defect LESS 3e-3 OR orientation_s4_defect GREATER 8e-3)
  message(FATAL_ERROR "the turned cone's S4 defect ${orientation_s4_defect} is not in [3e-3, 8e-3]")
endif()
if(NOT orientation_energy_change_core LESS 0)
  message(FATAL_ERROR "the turned cone's energy does not fall in the core:\n${results}")
endif()
