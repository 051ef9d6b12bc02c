# The econe_contact study end to end on a coarse rings mesh (h = 0.04, size_slope 0.14, exclusion
# radius 8h, no Ipopt check), from flat through contact to phi_e = 7.3. It must give the physics
# the default meshes of both families give (docs/results.md, "The contact era"), within this
# coarse mesh's error measured against them:
#  - the symmetric branch keeps S4 through contact to the corrector's tolerance: the mirror
#    subspace does not impose it (defect below 1e-8; measured 2e-16 here and 1.4e-10 on the
#    default rings mesh, against 1e-2 for the skewed cone);
#  - first contact between 6.50 and 6.60 (measured 6.5416; rings and gmsh_d4 at size_slope 0.1:
#    6.549 and 6.547);
#  - the symmetric branch loses stability between 6.92 and 7.07 (measured 6.964; 7.030 and
#    7.028 at size_slope 0.1 with the default proxy; over mesh, proxy and family the value
#    spreads over 6.965-7.123, docs/contact.md, "The proxy's density");
#  - a skewed cone is found at 7.2, lower than the symmetric one by more than 0.3 % (measured
#    0.84 %), without S4 (defect above 1e-3 on all of its samples; measured 0.010 to 0.039);
#  - traced down, the skewed branch crosses the symmetric one between 5.55 and 5.70 (measured
#    5.618 twice; 5.636 on the default rings mesh): a property of the two traced branches, not
#    phi_e^crit (docs/results.md, "The apex core against the mesh");
#  - the orientation check at the contact start: the pattern turned by 22.5 degrees relaxes to
#    a state between 0.6 % and 1.1 % lower that breaks S4 (defect between 3e-3 and 8e-3), with
#    the energy falling inside r = h and rising outside, and results.json warns (measured
#    -0.877 %, 0.0052 here; -0.871 %, 0.0054 on the default rings mesh and -0.778 %, 0.0045 on
#    gmsh_d4 at 0.1; -0.75 % to -1.04 % at 6.0 over both families and four resolutions).
#  - the turned state traced down and up (turned/): it breaks S4 from between 5.1 and 5.4
#    (measured 5.2505, its fold, where the downward trace ends; 5.2651 on the default rings
#    mesh), stays stable to 7.3 above its start (no loss of stability), lies below the
#    symmetric branch by 0.6 % to 2 % at most, still breaks S4 at its top (defect above 3e-3;
#    measured 0.030), every one of its samples and the skewed cone's breaks S4, and no stable
#    skewed cone lies below it
#    (phi_crit_energy null, measured against it: the skewed cone stays 0.23 % or more above).
# The skewed branch's downward trace may end early below that crossing where the penalty's
# pairs change (docs/guide/econe_contact.md, "Known limits"); the study then exits with 3 and
# says so, which this test accepts, and nothing else. Its stability, and so phi_e^crit by
# energy, hangs on a mode that is mostly the pattern's turn and is not asserted.
#  - stage 6 (study.hard_contact_at [7.0]): both branches at 7.0 under Ipopt's hard
#    constraints, converged with the gap >= 0.99 h; the held cone keeps S4 and gamma = pi/2;
#    the program hard_contact_at gives the study's numbers for the turned cone.
#  - stage 7 (study.compare_modes [3]): the three-fold cone, traced without contact, leaves
#    the flat sheet at c3 h^2 / R^2 (physics.md: c3 = 21.1087; measured 0.034009, +0.7 %; within 5 %, this mesh's error
#    for n = 2 being 1.1 %), reaches 7.3 without contact, and lies above the two-fold cone
#    wherever both were traced (physics.md, item 6);
#  - stage 8 (study.wind_to 7.45, shapes at 7.4): the sheet grown on from the turned cone's
#    highest stable sample (7.301; the skewed cone's top lies 0.48 % above it in energy) by
#    minimisation, in steps of at most 0.05, every state a strict minimum, continuing that
#    branch (E_b-hat continuous, the skew growing), with its shapes written at 7.4 and 7.45.
# About 4 minutes (the orientation check about 20 s of it, the turned branch about 40 s, the
# Ipopt checks about 60 s, the three-fold cone 18 s, the winding 10 s). Variables: PROGRAM, HARD_CONTACT_PROGRAM (hard_contact_at), OUT.
# Quoted strings in if() are strings, not names of variables (the script sets one called turned).
cmake_policy(SET CMP0054 NEW)
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
file(WRITE "${OUT}/econe.json"
     "{\"thickness\": 0.04, \"mesh\": {\"size_slope\": 0.14},\n"
     " \"physics\": {\"contact_exclusion_radius\": 0.32},\n"
     " \"continuation\": {\"phi_max\": 7.3},\n"
     " \"study\": {\"kind\": \"econe_contact\", \"skew_search_at\": 7.2, \"eigenmodes\": 0,\n"
     "           \"ipopt_check\": false, \"hard_contact_at\": [7.0],\n"
     "           \"wind_to\": 7.45, \"wind_shapes_at\": [7.4], \"compare_modes\": [3]},\n"
     " \"output\": {\"write_vtk\": false}}\n")
execute_process(COMMAND "${PROGRAM}" run "${OUT}/econe.json" --out "${OUT}/run"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL 0 AND NOT rc EQUAL 3)
  message(FATAL_ERROR "growshell run failed (${rc}):\n${log}\n${err}")
endif()
set(rc_first_run ${rc})
file(READ "${OUT}/run/results.json" results)
foreach(key phi_first_contact phi_crit_stability max_s4_defect_symmetric completed end)
  string(JSON ${key} GET "${results}" ${key})
endforeach()
string(JSON below GET "${results}" skewed energy_below_symmetric)
string(JSON found GET "${results}" skewed found)
if(NOT found)
  message(FATAL_ERROR "no skewed cone found:\n${results}")
endif()
if(rc EQUAL 3 AND NOT end MATCHES "^skewed branch downwards: ")
  message(FATAL_ERROR "the study ended early for another reason than the skewed branch's "
                      "downward trace (${end}):\n${results}")
endif()
if(NOT max_s4_defect_symmetric LESS 1e-8)
  message(FATAL_ERROR "the symmetric branch lost S4 (${max_s4_defect_symmetric}):\n${results}")
endif()
if(phi_first_contact LESS 6.50 OR phi_first_contact GREATER 6.60)
  message(FATAL_ERROR "first contact at ${phi_first_contact}, not in [6.50, 6.60]:\n${results}")
endif()
if(phi_crit_stability LESS 6.92 OR phi_crit_stability GREATER 7.07)
  message(FATAL_ERROR "stability lost at ${phi_crit_stability}, not in [6.92, 7.07]:\n${results}")
endif()
if(NOT below GREATER 0.003)
  message(FATAL_ERROR "the skewed cone is only ${below} below the symmetric one:\n${results}")
endif()
string(JSON crossings LENGTH "${results}" crossings)
if(crossings LESS 1)
  message(FATAL_ERROR "the skewed branch never crosses the symmetric one:\n${results}")
endif()
string(JSON crossing GET "${results}" crossings 0 phi_e)
if(crossing LESS 5.55 OR crossing GREATER 5.70)
  message(FATAL_ERROR "first energy crossing at ${crossing}, not in [5.55, 5.70]:\n${results}")
endif()
string(JSON turned GET "${results}" orientation_check turned 0)
foreach(key converged energy_relative s4_defect energy_change_core energy_change_outside)
  string(JSON turned_${key} GET "${turned}" ${key})
endforeach()
if(NOT turned_converged)
  message(FATAL_ERROR "the orientation check's relaxation failed:\n${turned}")
endif()
if(turned_energy_relative LESS -0.011 OR turned_energy_relative GREATER -0.006)
  message(FATAL_ERROR "the turned state is ${turned_energy_relative} against the traced one, "
                      "not in [-0.011, -0.006]:\n${turned}")
endif()
if(turned_s4_defect LESS 3e-3 OR turned_s4_defect GREATER 8e-3)
  message(FATAL_ERROR "the turned state's S4 defect ${turned_s4_defect} is not in [3e-3, 8e-3]")
endif()
if(NOT turned_energy_change_core LESS 0 OR NOT turned_energy_change_outside GREATER 0)
  message(FATAL_ERROR "the energy of the turned state does not fall in the core and rise "
                      "outside it:\n${turned}")
endif()
string(JSON warning GET "${results}" warnings 0)
if(NOT warning MATCHES "^orientation: ")
  message(FATAL_ERROR "results.json does not warn about the orientation: ${warning}")
endif()
# The turned branch, and phi_crit_energy measured against it.
string(JSON reference GET "${results}" phi_crit_energy_reference)
string(JSON crit_energy_type TYPE "${results}" phi_crit_energy)
if(NOT reference STREQUAL "turned" OR NOT crit_energy_type STREQUAL "NULL")
  message(FATAL_ERROR "phi_crit_energy is measured against '${reference}' and is "
                      "${crit_energy_type}, not null against the turned branch:\n${results}")
endif()
string(JSON turned_branch GET "${results}" turned)
foreach(key lowest_phi_breaking_s4 largest_energy_below_symmetric top_s4_defect highest_phi)
  string(JSON branch_${key} GET "${turned_branch}" ${key})
endforeach()
string(JSON turned_stability_type TYPE "${turned_branch}" phi_crit_stability)
if(branch_lowest_phi_breaking_s4 LESS 5.1 OR branch_lowest_phi_breaking_s4 GREATER 5.4)
  message(FATAL_ERROR "the turned branch breaks S4 from ${branch_lowest_phi_breaking_s4}, not "
                      "from between 5.1 and 5.4:\n${turned_branch}")
endif()
if(NOT turned_stability_type STREQUAL "NULL" OR branch_highest_phi LESS 7.29)
  message(FATAL_ERROR "the turned branch lost stability or ended below 7.29:\n${turned_branch}")
endif()
if(branch_largest_energy_below_symmetric LESS 0.006 OR
   branch_largest_energy_below_symmetric GREATER 0.02)
  message(FATAL_ERROR "the turned branch lies at most ${branch_largest_energy_below_symmetric} "
                      "below the symmetric one, not 0.6 % to 2 %:\n${turned_branch}")
endif()
if(NOT branch_top_s4_defect GREATER 3e-3)
  message(FATAL_ERROR "the turned branch keeps S4 at its top:\n${turned_branch}")
endif()
if(NOT EXISTS "${OUT}/run/turned/branch.csv")
  message(FATAL_ERROR "no turned/branch.csv")
endif()
# Every sample of the skewed and the turned cone breaks S4 (column s4_defect of their
# branch.csv, above 1e-3 and below 0.5, where the measure holds): their traces take no step
# onto the S4-symmetric cone, which a corrector can converge to next to their folds (before
# the step test, the turned cone's downward trace on this mesh went on down that cone from
# 5.248 to 4.05, and its CSV called it the turned cone).
foreach(branch skewed turned)
  file(STRINGS "${OUT}/run/${branch}/branch.csv" rows)
  list(GET rows 0 header)
  string(REPLACE "," ";" header "${header}")
  list(FIND header s4_defect column)
  list(REMOVE_AT rows 0)
  set(checked 0)
  foreach(row IN LISTS rows)
    string(REPLACE "," ";" values "${row}")
    list(GET values ${column} defect)
    if(NOT defect GREATER 1e-3 OR NOT defect LESS 0.5)
      message(FATAL_ERROR "a ${branch} sample with S4 defect ${defect}: ${row}")
    endif()
    math(EXPR checked "${checked} + 1")
  endforeach()
  if(checked LESS 20)
    message(FATAL_ERROR "the ${branch} branch has only ${checked} samples")
  endif()
endforeach()
# The turned cone's downward trace ends at its first special point (the fold where it loses
# stability; measured 5.2505 on this mesh) or where phi_e turns back.
string(JSON turned_end GET "${turned_branch}" end)
if(NOT turned_end MATCHES "^downwards: (found max_special_points special points|stopped at event 'turns_back'|approached a fold at parameter [0-9.]+ [^;]*);")
  message(FATAL_ERROR "the turned cone's downward trace did not end at its fold: ${turned_end}")
endif()
# The turned cone at 7.0 solved again under Ipopt's hard constraints (hard_contact_at): the
# contact solver of record agrees with the penalty's state. Measured: converged, smallest
# distance 0.99999990 h (the penalty's 0.989 h), elastic energy 0.06 % above the penalty's
# (which lets pairs come closer than h), S4 defect 0.0095 (the penalty's 0.0135), the largest
# state difference 0.41 h; about 60 s. A second call refuses to overwrite its result. (Only
# when the examples are built.)
# Stage 6: both traced branches at 7.0 under Ipopt's hard constraints (study.hard_contact_at).
string(JSON n_hard LENGTH "${results}" hard_contact)
if(NOT n_hard EQUAL 2)
  message(FATAL_ERROR "hard_contact holds ${n_hard} checks, not 2 (turned, symmetric):\n${results}")
endif()
foreach(i 0 1)
  foreach(key branch file converged hard_min_distance_over_h hard_s4_defect hard_gamma
              relative_energy_difference hard_elastic_energy)
    string(JSON study_hard_${key} GET "${results}" hard_contact ${i} ${key})
  endforeach()
  if(NOT EXISTS "${OUT}/run/${study_hard_file}" OR NOT study_hard_converged
     OR study_hard_hard_min_distance_over_h LESS 0.99)
    message(FATAL_ERROR "the study's hard-contact check ${i} (${study_hard_branch}) did not "
                        "converge with the gap >= 0.99 h, or wrote no file:\n${results}")
  endif()
  if(study_hard_branch STREQUAL "symmetric")
    # The held cone keeps S4 under the hard constraints, and its contact planes stay at pi/2.
    if(NOT study_hard_hard_s4_defect LESS 1e-6 OR study_hard_hard_gamma LESS 1.5707)
      message(FATAL_ERROR "the held symmetric cone lost S4 or gamma = pi/2 under the hard "
                          "constraints:\n${results}")
    endif()
  else()
    set(turned_hard_energy ${study_hard_hard_elastic_energy})
  endif()
endforeach()
if(HARD_CONTACT_PROGRAM)
  execute_process(COMMAND "${HARD_CONTACT_PROGRAM}" "${OUT}/run/turned" --phi 7.0
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "hard_contact_at failed (${rc}):\n${log}\n${err}")
  endif()
  file(READ "${OUT}/run/turned/hard_contact_phi7.0.json" hard)
  foreach(key converged relative_energy_difference hard_min_distance_over_h hard_s4_defect
              hard_gamma)
    string(JSON ${key} GET "${hard}" ${key})
  endforeach()
  # gamma from Ipopt's multipliers: the two contact planes stay near perpendicular at 7.0
  # (measured 1.487 on this coarse mesh, whose turned cone skews more: S4 defect 0.0095 under
  # the hard constraints; 1.557 and 1.562 on the two default meshes). Before the traces refused
  # correctors of more than 8 iterations, the upward trace here snapped at 6.60 (a corrector
  # of 10 iterations) onto a branch with gamma 1.562 at 7.0.
  if(hard_gamma LESS 1.45 OR hard_gamma GREATER 1.5708)
    message(FATAL_ERROR "gamma under the hard constraints at 7.0 is ${hard_gamma}, not in "
                        "[1.45, pi/2]:\n${hard}")
  endif()
  # The program and the study's stage 6 solve the same state the same way: the same numbers.
  string(JSON program_hard_energy GET "${hard}" hard_elastic_energy)
  if(NOT program_hard_energy EQUAL turned_hard_energy)
    message(FATAL_ERROR "hard_contact_at gives ${program_hard_energy} J at 7.0, the study "
                        "${turned_hard_energy} J")
  endif()
  if(NOT converged OR hard_min_distance_over_h LESS 0.99 OR relative_energy_difference LESS -0.01
     OR relative_energy_difference GREATER 0 OR NOT hard_s4_defect GREATER 3e-3)
    message(FATAL_ERROR "under the hard constraints the turned cone at 7.0 is not the penalty's "
                        "within 1 % keeping its skew and the gap >= 0.99 h:\n${hard}")
  endif()
  execute_process(COMMAND "${HARD_CONTACT_PROGRAM}" "${OUT}/run/turned" --phi 7.0
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "hard_contact_phi7.0.json exists")
    message(FATAL_ERROR "hard_contact_at overwrote its earlier result (${rc}): ${err}")
  endif()
endif()
if(NOT EXISTS "${OUT}/run/econe_contact.png")
  message(WARNING "no econe_contact.png (matplotlib missing?)")
endif()
if(NOT EXISTS "${OUT}/run/contact_angle.png")
  message(WARNING "no contact_angle.png (matplotlib missing?)")
endif()
# energy_ratio_f: f = E_s / E_b at the highest row of each branch's record, for the four
# branches with contact in their order (to round-off: the value is the record's), between 0.15
# and 0.35 (measured 0.239 symmetric, 0.251 skewed, 0.268 turned, 0.283 wound at 7.30-7.45;
# f rises with phi_e past first contact on every branch, from 0.18-0.20 at 6.6), and the
# wound cone's above the branch it was grown on from.
set(check_ratios [=[
import csv, json, sys
directory = sys.argv[1]
results = json.load(open(directory + "/results.json"))
entries = results["energy_ratio_f"]
names = [e["branch"] for e in entries]
if names != ["symmetric", "skewed", "turned", "wound"]:
    sys.exit(f"energy_ratio_f lists {names}")
f = {}
for e in entries:
    rows = list(csv.DictReader(open(f"{directory}/{e['branch']}/branch.csv")))
    top = max(rows, key=lambda r: float(r["phi_e"]))
    expected = float(top["E_stretch"]) / float(top["E_bend"])
    if float(top["phi_e"]) != e["phi_e"] or abs(e["f"] / expected - 1) > 1e-12:
        sys.exit(f"{e} is not f at the top row of {e['branch']}/branch.csv ({top['phi_e']}, {expected})")
    if not 0.15 < e["f"] < 0.35:
        sys.exit(f"{e}: f outside (0.15, 0.35)")
    f[e["branch"]] = e["f"]
start = results["wound"]["start_branch"]
if not f["wound"] > f[start]:
    sys.exit(f"the wound cone's f {f['wound']} is not above its start's ({start}: {f[start]})")
print(f)
]=])
execute_process(COMMAND /usr/bin/python3 -c "${check_ratios}" "${OUT}/run"
                RESULT_VARIABLE ratios_bad OUTPUT_VARIABLE ratios ERROR_VARIABLE ratios_why)
if(NOT ratios_bad EQUAL 0)
  message(FATAL_ERROR "energy_ratio_f: ${ratios_why}")
endif()
message(STATUS "energy_ratio_f: ${ratios}")
# Stage 8: the winding from the top of the turned cone.
string(JSON wound GET "${results}" wound)
foreach(key reached start_branch start_phi highest_phi failed_steps)
  string(JSON wound_${key} GET "${wound}" ${key})
endforeach()
string(JSON wound_shapes LENGTH "${wound}" shapes)
string(JSON shape_0_phi GET "${wound}" shapes 0 phi_e)
string(JSON shape_1_phi GET "${wound}" shapes 1 phi_e)
if(NOT wound_reached OR NOT wound_start_branch STREQUAL "turned" OR
   NOT wound_start_phi GREATER_EQUAL 7.29 OR NOT wound_highest_phi GREATER_EQUAL 7.4499 OR
   NOT wound_failed_steps EQUAL 0 OR NOT wound_shapes EQUAL 2 OR NOT shape_0_phi EQUAL 7.4 OR
   NOT shape_1_phi EQUAL 7.45)
  message(FATAL_ERROR "the winding did not run from the turned cone's top to 7.45 without a "
                      "failed step, with its shapes at 7.4 and 7.45:\n${wound}")
endif()
foreach(k 0 1)
  string(JSON shell GET "${wound}" shapes ${k} shell)
  string(JSON contact GET "${wound}" shapes ${k} contact)
  foreach(file "${shell}" "${contact}")
    file(READ "${OUT}/run/${file}" head LIMIT 120)
    if(NOT head MATCHES "<VTKFile type=\"UnstructuredGrid\"")
      message(FATAL_ERROR "${file} is not a VTU file")
    endif()
  endforeach()
endforeach()
# Its rows against its start, the top of the branch it starts from (the last row of that
# branch's record, traced upwards to 7.3): forward by at most 0.05 (less for the stop at 7.4), each a minimum, E_b-hat moving
# by less than 0.4 per radian (+ 1e-3; measured 0.05 to 0.27 per radian from 7.3 to 7.7, a
# drop onto another state moves it by 0.1 or more), the skew growing.
set(check_wound [=[
import csv, sys
start = list(csv.DictReader(open(sys.argv[1])))
wound = list(csv.DictReader(open(sys.argv[2])))
if len(wound) < 3:
    sys.exit(f"the winding has {len(wound)} rows, not at least 3")
previous = start[-1]
if abs(float(previous["phi_e"]) - float(sys.argv[3])) > 1e-9:
    sys.exit(f"the winding starts at {sys.argv[3]}, not at its branch's top {previous['phi_e']}")
for row in wound:
    step = float(row["phi_e"]) - float(previous["phi_e"])
    jump = abs(float(row["Eb_hat"]) - float(previous["Eb_hat"]))
    if not (0 < step <= 0.05 + 1e-9 and float(row["n_negative"]) == 0 and jump < 0.4 * step + 1e-3
            and float(row["s4_defect"]) > float(previous["s4_defect"])):
        sys.exit(f"wound row {row} after {previous}")
    previous = row
]=])
execute_process(COMMAND /usr/bin/python3 -c "${check_wound}" "${OUT}/run/${wound_start_branch}/branch.csv"
                        "${OUT}/run/wound/branch.csv" ${wound_start_phi}
                RESULT_VARIABLE wound_bad ERROR_VARIABLE wound_why)
if(NOT wound_bad EQUAL 0)
  message(FATAL_ERROR "the winding's record: ${wound_why}")
endif()
# Stage 7: the three-fold cone beside the two-fold one.
string(JSON three GET "${results}" compared_modes 0)
foreach(key mode phi_branch highest_phi lowest_energy_above_two_fold csv)
  string(JSON three_${key} GET "${three}" ${key})
endforeach()
execute_process(COMMAND /usr/bin/python3 -c
                        "import sys; b = float(sys.argv[1]); sys.exit(0 if abs(b / (21.1087 * 0.04**2) - 1) < 0.05 else 1)"
                        ${three_phi_branch} RESULT_VARIABLE off)
if(NOT three_mode EQUAL 3 OR NOT off EQUAL 0 OR NOT three_highest_phi GREATER_EQUAL 7.29 OR
   NOT three_lowest_energy_above_two_fold GREATER 0 OR NOT EXISTS "${OUT}/run/${three_csv}")
  message(FATAL_ERROR "the three-fold cone: branch point ${three_phi_branch} (c3 h^2 = "
                      "0.03377), to ${three_highest_phi}, at least "
                      "${three_lowest_energy_above_two_fold} above the two-fold cone:\n${three}")
endif()
# contact_cost.json: the five traces with contact, each with its steps and factorisations,
# their sums, the hard-contact checks made and the winding's steps; the per-step ratios are
# the counts over the steps.
set(check_cost [=[
import json, sys
cost = json.load(open(sys.argv[1] + "/contact_cost.json"))
expected_traces = sys.argv[2].split(",") if sys.argv[2] else []
names = [t["trace"] for t in cost["traces"]]
if names != expected_traces:
    sys.exit(f"contact_cost.json traces {names}, not {expected_traces}")
for t in cost["traces"]:
    if not (t["steps"] > 0 and t["factorizations"] >= t["steps"]
            and t["factorizations_per_step"] == t["factorizations"] / t["steps"]):
        sys.exit(f"trace {t}")
total = cost["all_traces"]
for key in ("steps", "factorizations", "stability_evaluations", "segments"):
    if total[key] != sum(t[key] for t in cost["traces"]):
        sys.exit(f"all_traces {key} {total[key]} is not the traces' sum")
if cost["hard_contact_checks"] != int(sys.argv[3]):
    sys.exit(f"{cost['hard_contact_checks']} hard-contact checks made, not {sys.argv[3]}")
winding = cost["winding"]
if int(sys.argv[4]) == 0:
    if winding is not None:
        sys.exit(f"winding work {winding} where no winding step was taken")
elif winding["steps"] != int(sys.argv[4]) or winding["factorizations"] < winding["steps"]:
    sys.exit(f"winding {winding}, not {sys.argv[4]} steps")
]=])
string(JSON wound_steps GET "${wound}" steps)
execute_process(COMMAND /usr/bin/python3 -c "${check_cost}" "${OUT}/run"
                        "symmetric,skewed_down,skewed_up,turned_down,turned_up" 2 ${wound_steps}
                RESULT_VARIABLE cost_bad ERROR_VARIABLE cost_why)
if(NOT cost_bad EQUAL 0)
  message(FATAL_ERROR "contact_cost.json of the first run: ${cost_why}")
endif()
# Resuming the finished study (issue #17): the cone and the n-fold cone are resumed from their
# last states, steps 3-7 (the branches with contact, the turned cone, the hard-constraint
# checks) are taken from DIR/stages.json instead of being traced again, and the winding from
# its record. The resumed run ends as the first did, its results.json holds the same values
# (all but the wall times) and every branch record is unchanged to the byte. About 30 s: the
# orientation check's relaxation is run again.
foreach(branch symmetric skewed turned wound)
  file(READ "${OUT}/run/${branch}/branch.csv" csv_before_${branch})
endforeach()
string(REGEX REPLACE "\"[a-z_]*seconds\": [^,\n]*" "" results_before "${results}")
execute_process(COMMAND "${PROGRAM}" run "${OUT}/econe.json" --out "${OUT}/run" --resume
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
if(NOT rc EQUAL rc_first_run)
  message(FATAL_ERROR "the resumed study exited with ${rc}, the first run with "
                      "${rc_first_run}:\n${log}\n${err}")
endif()
foreach(line "# stage 2-4: taken from stages.json" "# stage 5: taken from stages.json"
             "#   taken from stages.json")
  if(NOT log MATCHES "${line}")
    message(FATAL_ERROR "the resumed study's log does not say '${line}':\n${log}")
  endif()
endforeach()
if(log MATCHES "\nsymmetric |\nskewed |\nturned ")
  message(FATAL_ERROR "the resumed study traced a branch with contact again:\n${log}")
endif()
file(READ "${OUT}/run/results.json" results_resumed)
string(REGEX REPLACE "\"[a-z_]*seconds\": [^,\n]*" "" results_after "${results_resumed}")
if(NOT results_after STREQUAL results_before)
  message(FATAL_ERROR "the resumed study's results.json differs from the first run's:\n"
                      "${results_resumed}\nfirst run:\n${results}")
endif()
foreach(branch symmetric skewed turned wound)
  file(READ "${OUT}/run/${branch}/branch.csv" csv_after)
  if(NOT csv_after STREQUAL csv_before_${branch})
    message(FATAL_ERROR "the resumed study changed ${branch}/branch.csv")
  endif()
endforeach()
# The resumed run's contact_cost.json is its own: no trace, no check, no winding step.
execute_process(COMMAND /usr/bin/python3 -c "${check_cost}" "${OUT}/run" "" 0 0
                RESULT_VARIABLE cost_bad ERROR_VARIABLE cost_why)
if(NOT cost_bad EQUAL 0)
  message(FATAL_ERROR "contact_cost.json of the resumed run: ${cost_why}")
endif()
