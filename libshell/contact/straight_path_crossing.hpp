#pragma once
/// \file
/// Whether a proxy vertex passes through a proxy triangle while the sheet moves along the
/// straight path x(τ) = x0 + τ (x1 - x0), τ in [0, 1]: continuous collision detection for
/// vertex-triangle pairs. A path that moves a vertex through a layer ends with the vertex on
/// the wrong side, where a distance-based penalty pushes it further in; a solver that jumps
/// to an extrapolated state checks the jump with this first.
///
/// Proxy positions are linear in x, so every vertex and triangle corner moves on a straight
/// line at constant speed. For a pair (p, t = (a, b, c)) the signed volume
/// f(τ) = (p - a) · ((b - a) × (c - a)) is then a cubic in τ; the vertex lies in the
/// triangle's plane where f = 0, and it passes through the triangle where such a root has
/// the vertex inside the triangle (barycentric coordinates >= 0). Roots are bracketed on the
/// cubic's monotone pieces (between its critical points) and bisected. A path that touches the
/// plane and turns back (a double root) is not a passage and is not reported.
///
/// Only pairs that can meet are examined: each point of the proxy moves by at most D, the
/// largest vertex displacement, so a vertex and a triangle more than 2 D apart at x0 never
/// touch on the path; the pairs within 2 D at x0 (the neighbours on the sheet within the
/// exclusion radius left out, as every contact pair set leaves them out) are those of
/// near_contact_pairs.

#include <Eigen/Core>
#include <optional>

#include "libshell/contact/contact_proxy.hpp"

namespace growshell {

/// A vertex-triangle passage on a straight path.
struct PathCrossing {
  Eigen::Index vertex = -1;    ///< proxy vertex
  Eigen::Index triangle = -1;  ///< proxy triangle (row of ContactProxy::triangles)
  double time = 0.0;           ///< τ in [0, 1] where the vertex is in the triangle
};

/// The earliest passage of a proxy vertex through a proxy triangle (pairs nearer on the
/// reference than exclusion_radius excluded) on the straight path from x0 to x1, or nothing
/// if no vertex passes through a triangle. Throws std::invalid_argument if x0 or x1 does not
/// have proxy.map.cols() entries, or if exclusion_radius is negative or not finite.
std::optional<PathCrossing> first_vertex_triangle_crossing(
    const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x0,
    const Eigen::Ref<const Eigen::VectorXd>& x1, double exclusion_radius);

/// The same for one vertex p and triangle (a, b, c) moving from the rows of `start` to those of
/// `end` (rows p, a, b, c): the time τ in [0, 1] where p passes through the triangle, the
/// earliest if several; nothing if it does not.
std::optional<double> vertex_triangle_crossing_time(const Eigen::Matrix<double, 4, 3>& start,
                                                    const Eigen::Matrix<double, 4, 3>& end);

}  // namespace growshell
