#pragma once
/// \file
/// Broad phase of self-contact on the contact proxy: the vertex-triangle and edge-edge pairs
/// that may be closer than a query distance d in the current state and are not neighbours on
/// the sheet.
///
/// Neighbours on the sheet. Two primitives are neighbours (never a contact candidate) if
/// their REFERENCE distance, the smallest distance between a vertex of one and a vertex of the
/// other in ContactProxy::reference_positions, is below the exclusion radius r_ex; a vertex
/// that is a corner of the triangle, and edges that share a vertex, are always excluded.
/// The reference sheet is flat, so this Euclidean distance is the geodesic distance along
/// the reference sheet whenever the segment between the points stays on the sheet (always on
/// a convex sheet such as the disc; on an annulus of inner radius R_i it differs only for
/// pairs whose segment crosses the hole, i.e. at reference distances comparable to R_i, so for
/// r_ex << R_i the test is the geodesic one). Measuring it in the reference, not in the
/// current state, is what lets a tight fold be told from contact: a U-fold of radius rho
/// brings points at arclength s to the chord 2 rho sin(s / (2 rho)) <= s. The reference is
/// the ungrown flat sheet (ContactProxy::reference_positions); growth G = diag(1, lambda)
/// lengthens distances by a factor between 1 (radial) and lambda (circumferential), so a
/// radius r measured in the grown sheet corresponds to a flat radius between r / lambda and r
/// (pass r to be sure a tight fold is never taken for contact, r / lambda to be sure no
/// contact beyond r is missed).
///
/// Choosing r_ex (h = thickness; two mid-surfaces touch at distance h):
///  - r_ex >= h: points closer than h along the sheet are closer than h in space (up to
///    the stretch), so without exclusion every point would be "in contact" with its own
///    neighbourhood.
///  - r_ex >= pi h / 2: the tightest fold two touching layers can make has radius h / 2, whose
///    arc has length pi h / 2; points further apart along the sheet than that are on the two
///    legs of the fold, which face each other at distance h. A smaller r_ex would take the
///    bend of a tight fold (chord < h) for contact; a larger one misses the contact of the legs
///    within (r_ex - pi h / 2) / 2 of the bend.
///  - At a cone's apex two points on opposite sides at reference radius r are only about
///    c r apart (c < 2, the fold chord), so r_ex decides how close to the apex contact is
///    counted. The scene's default is 8 h, the apex model of docs/contact.md: pairs
///    straddling the apex within 4 h of it, where the sheet's curvature is not small against
///    1 / h, are one piece of material.
/// Because the reference distance of two
/// primitives is taken between their vertices, it exceeds the smallest reference distance
/// between points of the two primitives by at most one proxy edge length: refine the proxy so
/// that its edges are small against pi h / 2 - h = 0.57 h, or read r_ex as known to that
/// accuracy.
///
/// Current-state test: a pair is a candidate if its two current axis-aligned bounding boxes,
/// inflated by d, overlap, i.e. along every axis the gap between the boxes is <= d. Every pair
/// of primitives whose Euclidean distance is <= d passes (the test is conservative: pairs up
/// to sqrt(3) (d + box size) apart may pass too); the narrow phase measures the distance.

#include <Eigen/Core>

#include "libshell/contact/contact_proxy.hpp"

namespace growshell {

/// Parameters of the broad phase. Lengths in metres.
struct ContactCandidateOptions {
  /// Query distance d (finite, >= 0): pairs whose current bounding boxes come within d of each
  /// other along every axis are reported. For gap constraints gap >= h use d >= h plus the
  /// proxy's sag margin (proxy_sag) plus the largest motion expected before the next query.
  double query_distance = 0.0;
  /// Exclusion radius r_ex (finite, >= 0): pairs whose reference distance (see the file
  /// comment) is below r_ex are neighbours on the sheet and never reported; at least pi h / 2
  /// (see the file comment; the scene default is 8 h).
  double exclusion_radius = 0.0;
};

/// Candidate pairs of the broad phase; indices refer to the ContactProxy.
struct ContactCandidates {
  /// (proxy vertex p, proxy triangle t), p not a corner of t; sorted by (p, t), no duplicates.
  Eigen::MatrixX2i vertex_triangle;
  /// (edge a, edge b), rows of ContactProxy::edges, a < b, no shared vertex; sorted by
  /// (a, b), no duplicates.
  Eigen::MatrixX2i edge_edge;
  /// Cost measure: primitive pairs looked at before the exact box and exclusion tests (for the
  /// spatial hash, every stored primitive met in a cell visited by a query, duplicates
  /// included; for brute force, all pairs).
  Eigen::Index pairs_examined = 0;

  /// True if there is no candidate pair.
  bool empty() const { return vertex_triangle.rows() == 0 && edge_edge.rows() == 0; }
  /// Number of pairs of both kinds.
  Eigen::Index size() const { return vertex_triangle.rows() + edge_edge.rows(); }
};

/// All candidate pairs of `proxy` at the current proxy positions `positions` (metres, one row
/// per proxy vertex, e.g. proxy_positions(proxy, x)), found with a spatial hash.
///
/// Spatial hash: a uniform grid of cell size c = (mean current proxy edge length) + d
/// (enlarged if needed so that the grid has at most 2^20 cells per axis). Triangles and edges
/// are entered into every cell their current box overlaps; the (cell key, primitive) list is
/// sorted, and each vertex (for vertex-triangle) or edge (for edge-edge) visits the cells of
/// its box inflated by d, finding the stored primitives by binary search on the sorted keys.
/// Each query's hits are sorted and deduplicated, then the exact box test and the exclusion
/// are applied, so the result equals find_contact_candidates_brute_force exactly.
/// Deterministic (no hashing of pointers, no threads). Cost: O(N log N) for the sort and the
/// searches plus O(N k), k the number of primitives within about c + 2 d of a primitive; at
/// a fixed proxy density and d, r_ex proportional to the proxy spacing, k is bounded, so the
/// cost grows like N log N.
///
/// Throws std::invalid_argument naming the field or row for: query_distance or
/// exclusion_radius not finite or negative, positions with a row count other than
/// proxy.num_vertices(), or a non-finite position.
ContactCandidates find_contact_candidates(const ContactProxy& proxy,
                                          const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                          const ContactCandidateOptions& options);

/// Same result as find_contact_candidates by testing every vertex-triangle and every
/// edge-edge pair (O(V T + E^2)); the reference implementation for tests. Same exceptions.
ContactCandidates find_contact_candidates_brute_force(
    const ContactProxy& proxy, const Eigen::Ref<const Eigen::MatrixX3d>& positions,
    const ContactCandidateOptions& options);

/// No-contact fast path: true iff find_contact_candidates would return a non-empty result,
/// stopping at the first candidate found. A false answer proves that no vertex-triangle or
/// edge-edge pair of the proxy outside the exclusion radius is within distance d in the
/// current state. Same exceptions as find_contact_candidates.
bool has_contact_candidates(const ContactProxy& proxy,
                            const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                            const ContactCandidateOptions& options);

}  // namespace growshell
