#pragma once
/// \file
/// Smallest distance between non-neighbouring parts of the sheet's mid-surface, to detect
/// when a deforming sheet first touches itself (e.g. the folds of a growing e-cone).

#include <Eigen/Core>
#include <limits>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// Options of smallest_self_distance. Lengths in metres.
struct SelfDistanceOptions {
  /// Exclusion radius r_ex (> 0, metres): two surface points whose REFERENCE (undeformed)
  /// positions are closer than r_ex are neighbours along the sheet and never count as
  /// contact. A fold of radius rho brings points at reference distance s to the chord
  /// 2 rho sin(s / (2 rho)), so a tight fold of radius h/2 is only ignored if
  /// r_ex >= pi h / 2; the scene default is 8 h (the apex model of docs/contact.md).
  double exclusion_radius = 0.0;
  /// Each element is sampled on its regular sub-triangulation with this many segments per
  /// edge (>= 1; 1 = the three corners only): (n + 1)(n + 2) / 2 limit-surface samples per
  /// element. The accuracy knob (see SelfDistance::distance).
  int samples_per_edge = 2;
  /// Samples whose reference position lies within this distance (metres, >= 0) of
  /// `core_center` are ignored. Near the apex of a cone every generator converges, so any two
  /// points just outside the exclusion radius on opposite sides of the apex are close in
  /// space although the sheet there is smooth (the core); 0 keeps every sample.
  double core_radius = 0.0;
  Eigen::Vector3d core_center = Eigen::Vector3d::Zero();
};

/// Result of smallest_self_distance (metres, global Cartesian basis).
struct SelfDistance {
  /// Smallest current distance between two samples whose reference distance is at least the
  /// exclusion radius; infinity if there is no such pair.
  ///
  /// Accuracy: the samples are a subset of the surface, so with d_true the infimum over all
  /// pairs of surface points with reference distance >= r_ex, distance >= d_true. Let delta
  /// be the covering radius of the samples (every surface point lies within delta of a
  /// sample; for a sub-triangle with longest edge l, delta <= l / sqrt(3)). Then in general
  /// distance <= d_true + 2 delta, and for two facing, near-parallel sheets (the contact
  /// case) distance <= sqrt(d_true^2 + delta^2) + O(delta^2 curvature): the error is
  /// tangential and second order. Both bounds hold up to how the discrete samples straddle
  /// the exclusion boundary (a pair just outside r_ex may be represented only by a sample
  /// pair up to 2 delta_ref further apart in the reference). Refine with samples_per_edge.
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();      ///< current position of sample a
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();      ///< current position of sample b
  Eigen::Vector3d reference_a = Eigen::Vector3d::Zero();  ///< reference position of sample a
  Eigen::Vector3d reference_b = Eigen::Vector3d::Zero();  ///< reference position of sample b
  Eigen::Index element_a = -1;  ///< element of sample a (-1 if distance is infinite)
  Eigen::Index element_b = -1;  ///< element of sample b (-1 if distance is infinite)
  /// Sample pairs whose current distance was evaluated, over all grid passes (cost measure).
  Eigen::Index pairs_checked = 0;
};

/// Smallest distance between samples of the limit surface at state x (control points,
/// vertex-major like ShellModel, metres) that are not neighbours in the reference (see
/// SelfDistanceOptions). Samples: for the elements e in increasing order, the parameter
/// points (v, w) = (i / n, j / n), i = 0..n, j = 0..n-i (i outer), evaluated with
/// evaluate_limit_surface on x and on model.reference_positions(); a corner or edge sample
/// is taken only from the first element that has it (its neighbours' copies are the same
/// surface point, and would multiply the cost). Sample indices follow that order; ties in
/// the distance go to the pair with the smallest (lower index, higher index), and sample a
/// has the lower index. Deterministic and exact: equal to the brute-force minimum over all
/// pairs of these samples.
///
/// Broad phase: a uniform grid of cell size c over the current samples; scanning each cell
/// against its 26 neighbours finds every pair closer than c. It starts at c = the mean
/// sample spacing; a pass whose best distance is below c is final, otherwise the next pass
/// uses c = that best distance (slightly enlarged) or 2c if none was found. Cost:
/// N log N for the sort plus N times the number of samples within about 3.5 d of a sample,
/// where d ~ the answer; since neighbouring points just beyond r_ex in the sheet itself are
/// at most ~r_ex apart, d <= ~r_ex (times the stretch) for any sheet larger than r_ex, so
/// the cost is linear in N at a fixed number of samples per exclusion radius (refining
/// at a fixed r_ex in metres raises the pairs per sample like (r_ex / spacing)^2).
///
/// Throws std::invalid_argument naming the field if exclusion_radius is not > 0,
/// samples_per_edge < 1, or x does not have model.dimension() entries or has a non-finite one.
SelfDistance smallest_self_distance(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                    const SelfDistanceOptions& options);

}  // namespace growshell
