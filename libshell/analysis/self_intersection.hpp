#pragma once
/// \file
/// Whether the sheet's mid-surface passes through itself, and a signed gap that changes sign
/// when it first does: the test function that lets continuation locate the first
/// mid-surface contact of a growing e-cone (smallest_self_distance alone is unsigned and
/// never goes negative).

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// Options of find_self_intersection and signed_self_gap. Lengths in metres; the same
/// meaning as the fields of SelfDistanceOptions.
struct SelfIntersectionOptions {
  /// Exclusion radius r_ex (> 0, metres): two sub-triangles count only if every pair of their
  /// vertices is at least r_ex apart in the REFERENCE (undeformed) state, so triangles that
  /// are neighbours along the sheet (a tight fold, or simply adjacent triangles, which share
  /// vertices) never count. A fold of radius rho brings parts at reference distance pi rho
  /// face to face, so r_ex a little above pi rho (by about a sub-triangle size) ignores it.
  double exclusion_radius = 0.0;
  /// Segments per element edge of the regular sub-triangulation (>= 1): n^2 flat triangles
  /// per element. The accuracy knob: the test is exact for the piecewise-linear interpolant
  /// of the limit surface on this sub-triangulation, which lies within O(curvature l^2) of
  /// the limit surface (l the sub-triangle size).
  int samples_per_edge = 2;
  /// Triangles with a vertex whose reference position lies closer than this (metres, >= 0)
  /// to `core_center` are ignored (the smooth core of a cone, where every generator
  /// converges); 0 keeps every triangle.
  double core_radius = 0.0;
  /// Centre of the ignored core (reference position, metres; finite).
  Eigen::Vector3d core_center = Eigen::Vector3d::Zero();
};

/// Result of find_self_intersection (global Cartesian basis, metres).
struct SelfIntersection {
  /// True if two admissible sub-triangles (see SelfIntersectionOptions) intersect, touching
  /// included.
  bool intersects = false;
  /// Triangle pairs that passed the broad phase (overlapping bounding boxes), the core and
  /// the exclusion test and got the exact triangle-triangle test (cost measure).
  Eigen::Index triangle_pairs_tested = 0;
  /// A point on both triangles of the intersecting pair with the smallest (lower, higher)
  /// triangle index (current positions, metres); zero if intersects is false.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// Elements holding the two triangles of that pair (-1 if intersects is false).
  Eigen::Index element_a = -1;
  Eigen::Index element_b = -1;
};

/// Whether the piecewise-linear sampled limit surface at state x (control points,
/// vertex-major like ShellModel, metres) intersects itself between admissible triangles.
///
/// Surface: for the elements e in increasing order, the parameter points
/// (v, w) = (i / n, j / n), i + j <= n, evaluated with evaluate_limit_surface on x and on
/// model.reference_positions() (a corner or edge point shared by several elements is
/// evaluated once, so the triangulation is conforming); per element the triangles are, for
/// i = 0..n-1 and j = 0..n-1-i (i outer), the upward triangle ((i,j), (i+1,j), (i,j+1)) and,
/// if i + j < n - 1, the downward triangle ((i+1,j), (i+1,j+1), (i,j+1)); this order numbers
/// the triangles. Admissible pairs: see SelfIntersectionOptions.
///
/// Narrow phase: two non-coplanar triangles intersect iff an edge of one crosses the other
/// (the ends of their intersection segment lie on edges); each edge-triangle test computes
/// the crossing point of the edge with the triangle's plane and tests it against the
/// triangle's edges in the triangle's plane, which stays reliable for nearly coplanar
/// triangles (the crossing point stays on the edge). Triangles whose vertices lie exactly in
/// each other's plane (e.g. a flat sheet) get a 2-D overlap test. Degenerate (zero-area)
/// triangles never intersect. Broad phase: a uniform grid (spatial hash, sorted keys) over
/// the triangles' bounding boxes, with cell size the mean bounding-box size; each
/// overlapping pair is tested once. Cost: linear in the number of triangles at a fixed
/// number of triangles per exclusion radius. Deterministic; the result equals that of
/// testing all pairs.
///
/// Throws std::invalid_argument naming the field if exclusion_radius is not > 0,
/// samples_per_edge < 1, core_radius is not finite and >= 0, core_center is not finite, or
/// x does not have model.dimension() entries or has a non-finite one.
SelfIntersection find_self_intersection(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                        const SelfIntersectionOptions& options);

/// Signed gap (metres) for event location: d = smallest_self_distance(model, x, same
/// options).distance when the surface does not intersect itself (find_self_intersection),
/// and -max(d, DBL_MIN) when it does, so it changes sign when the mid-surface first passes
/// through itself. +infinity if no admissible pair of samples exists.
///
/// It is discontinuous at the event: d is the sampled distance, which is O(sample spacing)
/// rather than 0 when the surfaces touch, so the gap jumps from about +spacing to about
/// -spacing. Locate the event by bisection on the sign, not by interpolating the value.
/// Throws like find_self_intersection.
/// The signed gap from a distance `distance` = smallest_self_distance(...).distance already
/// computed with the same options: +distance without an intersection, -max(distance,
/// DBL_MIN) with one. signed_self_gap is this of its own two searches.
double signed_gap(const SelfIntersection& intersection, double distance);

double signed_self_gap(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                       const SelfIntersectionOptions& options);

}  // namespace growshell
