#pragma once
/// \file
/// Counting the folds of an e-cone from the shape of its rim.

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// Fourier content of the rim's out-of-plane profile.
struct RimFoldAnalysis {
  /// Amplitude of mode m = 0..max_mode of the closed curve of unit directions from the apex
  /// to the rim points, as a function of the reference polar angle about the growth centre
  /// (square root of the power summed over x, y, z: independent of the cone's orientation;
  /// dimensionless). A flat disc has only m = 1 (amplitude sqrt 2); an n-fold cone with generator
  /// elevation ~ a cos(n theta) has amplitude ~ 2 J_1(a) at m = n, the largest for m >= 2.
  /// The apex is the sheet vertex at the centre (a ring: the centroid of its inner rim).
  Eigen::VectorXd mode_amplitudes;
  /// The mode m >= 2 with the largest amplitude: the number of folds (2 for the e-cone's
  /// saddle, 3 for the three-fold cone); 0 for a planar rim (rms elevation of the directions
  /// above their best plane through the apex below 1e-8).
  int folds = 0;
};

/// Analyses the rim (sheet vertices next to the ghost layer, at their limit positions).
/// Throws std::invalid_argument if max_mode < 2 or the rim has too few vertices to resolve it.
RimFoldAnalysis analyze_rim_folds(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                  int max_mode = 8);

}  // namespace growshell
