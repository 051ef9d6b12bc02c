#pragma once
/// \file
/// The events a cone study locates along its branch (test functions whose sign change is an
/// event, solvers/continuation/pseudo_arclength.hpp).

#include <vector>

#include "solvers/continuation/pseudo_arclength.hpp"
#include "studies/cone_sample_measures.hpp"

namespace growshell {

/// The cone's events, in this order:
///  - "contact": gap minus `contact_distance` (two non-neighbouring parts of the sheet come
///    within the contact distance, e.g. the thickness); ends the trace if stop_at_contact;
///  - "midsurface_contact": the signed gap (the mid-surface first passes through itself);
///  - "eb_max": dE_b-hat/dphi_e along the branch (a maximum of E_b-hat on a forward trace).
/// The functions keep a reference to `measures`, which must outlive the trace.
std::vector<BranchEvent> cone_branch_events(ConeSampleMeasurer& measures, double contact_distance,
                                            bool stop_at_contact);

}  // namespace growshell
