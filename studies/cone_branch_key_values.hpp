#pragma once
/// \file
/// The key values of a cone_branch study (results.json) as its branch record holds them:
/// from the recorded events and the branch.csv rows, so that a study resumed after a crash
/// reports the same values as one run in one go.

#include "studies/branch_record.hpp"
#include "studies/study_results.hpp"

namespace growshell {

/// Sets the key values of `results` from `record` (columns phi_e, n_negative, s4_defect;
/// events as the cone study records them), leaving the others (thickness, mesh, ...) alone:
///  - phi_branch: the first branch_point event on the "flat" branch;
///  - phi_max, eb_hat_max: the eb_max event with the largest recorded "eb_hat" (a sign change
///    of dE_b-hat/dphi_e is also reported at a minimum), or the first if none has a value;
///  - phi_gap_h, phi_kiss, phi_symmetry_lost: the first contact, midsurface_contact and
///    symmetry_lost events;
///  - phi_crit_stability: the first row with phi_e >= 0.1 and n_negative > 0;
///  - max_s4_defect_before_contact: the largest finite s4_defect of the rows with
///    0.1 <= phi_e < phi_gap_h (every row from 0.1 on without a contact event);
///  - phi_last: the last row's phi_e;
///  - phi_highest: the largest phi_e of the rows (where a branch that turns back at a fold
///    turned).
/// Values that the record does not have are reset to none. Throws std::out_of_range if the
/// record lacks one of the columns.
void set_cone_branch_key_values(const BranchRecord& record, ConeBranchResults& results);

}  // namespace growshell
