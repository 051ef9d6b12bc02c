#pragma once
/// \file
/// An event that ends a trace where its parameter turns back: a fold, or a branch point at
/// which the corrector carried the trace onto the other branch in the opposite direction.

#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// The stopping event "turns_back": direction (+1: a trace of increasing lambda, -1:
/// decreasing) times dlambda/ds, which changes sign where lambda stops moving in the trace's
/// direction. A trace given it ends at the sample just past that point (located to
/// special_point_tolerance like any event), so its samples are single-valued in lambda and
/// all lie on the part of the branch it was started on. Throws std::invalid_argument unless
/// direction is +1 or -1.
BranchEvent turning_back_event(int direction);

}  // namespace growshell
