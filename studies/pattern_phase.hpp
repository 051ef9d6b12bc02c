#pragma once
/// \file
/// Where an n-fold pattern sits about the growth axis, and a linear phase condition that holds
/// it there: the out-of-plane displacement's n-th Fourier sine component about the pattern's
/// own orientation, which is zero on the state and changes to first order when the pattern
/// turns over the material (pattern_rotation.hpp). docs/continuation.md, "Phase condition".

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// The orientation theta0 (rad, in (-pi/n, pi/n]) of the n-fold pattern of the out-of-plane
/// displacement w = z (the reference lies in z = 0): with the lumped reference areas A_i of the
/// sheet vertices and their polar angles theta_i about the growth centre,
/// sum A_i w_i e^{-i n theta_i} = rho e^{-i n theta0}, so that w ~ rho cos(n (theta - theta0)).
/// Taken from `x`, or from `direction` where the state has no such pattern (rho below 1e-12 of
/// the sheet's area times its extent: the flat sheet at a branch point, whose direction is the
/// critical mode). Throws std::invalid_argument for sizes other than the model's dimension,
/// n < 1, or when neither has an n-fold component.
double pattern_orientation(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                           const Eigen::Ref<const Eigen::VectorXd>& direction, int folds);

/// The functional c with c . y = sum A_i sin(n (theta_i - theta0)) z_i(y) over the sheet
/// vertices, theta0 = pattern_orientation(model, x, direction, folds): zero at x (to rounding)
/// when its pattern sets theta0, and d(c . x)/d(turn) = n rho' != 0 for the turn of a pattern
/// of amplitude rho'. Its multiplier in a phase-conditioned trace is a distributed normal load
/// ~ sin(n (theta - theta0)), the force with which the mesh holds the pattern where it is.
/// Throws as pattern_orientation.
Eigen::VectorXd pattern_phase_functional(const ShellModel& model,
                                         const Eigen::Ref<const Eigen::VectorXd>& x,
                                         const Eigen::Ref<const Eigen::VectorXd>& direction,
                                         int folds);

}  // namespace growshell
