# Runs crit_hard_contact on a synthetic trace_contact run whose re-solves are all given through
# --reuse, so that no Ipopt solve runs and the program's own logic is checked exactly:
#   symmetric branch (penalty and hard):  E = 1 - 0.1 (phi - 6.02), rows at 5.8, 5.9, ..., 6.4
#   skewed branch, penalty:               E = 1 - 0.3 (phi - 6.02), rows at 6.4, 6.3, ..., 5.8
#   skewed branch, hard:                  the same + 0.06, except row 5 (phi = 5.9), which is
#                                         0.05 higher still: a re-solve that left its branch.
# The penalty crossing is at 6.02. The hard energies cross at 6.02 + 0.06 / 0.2 = 6.32, above the
# first re-solved rows (5.9 ... 6.2), so the program must extend twice along both sheets, and
# it must leave out skewed row 5. Variables: PROGRAM, OUT.
cmake_policy(VERSION 3.16)
file(REMOVE_RECURSE "${OUT}")
set(run "${OUT}/run")
set(reuse "${OUT}/reuse")
file(MAKE_DIRECTORY "${run}" "${reuse}")
file(WRITE "${run}/scene.json" [=[
{
  "geometry": {"shape": "disc", "radius": 1.0, "inner_radius": 0.25},
  "thickness": 0.04,
  "material": {"youngs_modulus": 10000.0, "poisson_ratio": 0.3},
  "mesh": {"family": "lattice", "rings": 6}
}
]=])
set(header "phi_e,E_stretch,E_bend,Eb_hat,area,min_gap,n_negative,gamma,n_contacts,contact_force,E_penalty,dE_dphi")
set(reuse_header "row,phi_e,converged,E_penalty_state,E_elastic_penalty_state,E_elastic,dE_dphi,max_state_difference,min_distance,gamma,constrained_pairs,active_pairs,contact_force,rounds,iterations,seconds")
set(sym "${header}\n")
set(skew "${header}\n")
set(sym_hard "${reuse_header}\n")
set(skew_hard "${reuse_header}\n")
foreach(i RANGE 0 6)
  math(EXPR up "58 + ${i}")    # symmetric: phi = 5.8 + 0.1 i
  math(EXPR down "64 - ${i}")  # skewed: phi = 6.4 - 0.1 i
  foreach(branch sym skew)
    if(branch STREQUAL "sym")
      set(tenths ${up})
      set(slope "-0.1")
    else()
      set(tenths ${down})
      set(slope "-0.3")
    endif()
    math(EXPR whole "${tenths} / 10")
    math(EXPR frac "${tenths} % 10")
    set(phi "${whole}.${frac}")
    # E = 1 + slope (phi - 6.02), written with enough digits for the program's 1e-9 checks.
    math(EXPR hundredths "${tenths} * 10 - 602")
    # slope * hundredths / 100, as a decimal: slope is -0.1 or -0.3.
    if(branch STREQUAL "sym")
      math(EXPR milli "-${hundredths}")        # -0.1 * h/100 = -h/1000
    else()
      math(EXPR milli "-3 * ${hundredths}")    # -0.3 * h/100 = -3h/1000
    endif()
    math(EXPR e_milli "1000 + ${milli}")
    set(energy "${e_milli}e-3")
    string(APPEND ${branch} "${phi},${energy},0,1,1,0.05,0,nan,0,0,0,${slope}\n")
    set(hard_milli ${e_milli})
    if(branch STREQUAL "skew")
      math(EXPR hard_milli "${e_milli} + 60")
      if(i EQUAL 5)
        math(EXPR hard_milli "${hard_milli} + 50")
      endif()
    endif()
    string(APPEND ${branch}_hard
           "${i},${phi},1,${energy},${energy},${hard_milli}e-3,${slope},0,0.04,nan,0,0,0,1,1,0\n")
  endforeach()
endforeach()
file(WRITE "${run}/branch_symmetric.csv" "${sym}")
file(WRITE "${run}/branch_skewed.csv" "${skew}")
file(WRITE "${reuse}/hard_contact_symmetric.csv" "${sym_hard}")
file(WRITE "${reuse}/hard_contact_skewed.csv" "${skew_hard}")

execute_process(COMMAND "${PROGRAM}" "${run}" --reuse "${reuse}" --out "${OUT}/result"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "crit_hard_contact failed (${rc}):\n${log}\n${err}")
endif()
file(READ "${OUT}/result/hard_contact_crossing.json" json)
foreach(expected
        "\"penalty_crossing\": 6\\.0(2|20000000[0-9]*|19999999[0-9]*),"
        "\"hard_contact_crossing\": 6\\.3(2|20000000[0-9]*|19999999[0-9]*),"
        "\"left_branch_skewed_rows\": \\[5\\]"
        "\"left_branch_symmetric_rows\": \\[\\]"
        "\"samples_symmetric\": 6"
        "\"samples_skewed\": 6")
  if(NOT json MATCHES "${expected}")
    message(FATAL_ERROR "hard_contact_crossing.json does not match ${expected}:\n${json}\n${log}")
  endif()
endforeach()
if(NOT log MATCHES "extending up.*extending up")
  message(FATAL_ERROR "expected two extensions upwards:\n${log}")
endif()
