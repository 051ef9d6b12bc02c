#pragma once
/// \file
/// The pairs of a state that are near: broad-phase candidates kept by their exact
/// (unmollified) distance at that state, the union of two pair sets, and the smallest distance
/// over a pair set. Pure geometry of the sheet's proxy; the contact solvers build their
/// constraint and penalty pair sets from it.

#include <Eigen/Core>

#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_proxy.hpp"

namespace growshell {

/// Which near pairs near_contact_pairs keeps: edge-edge pairs or not, and per proxy vertex
/// every near triangle or only the nearest (the contact solvers' options, e.g.
/// ContactSolveOptions, explain the choice).
struct NearPairSelection {
  bool edge_edge_pairs = true;
  bool nearest_triangle_only = false;
};

/// Near pairs of state x: candidates of the broad phase at query distance `distance` whose
/// exact distance (with the mollifier off) is below `distance`; with
/// selection.nearest_triangle_only, per proxy vertex only the nearest such triangle (ties to
/// the lower index), and edge-edge pairs only if selection.edge_edge_pairs.
ContactCandidates near_contact_pairs(const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x,
                                     double distance, double exclusion_radius,
                                     const NearPairSelection& selection = {});

/// The sorted union of two pair sets, without duplicates.
ContactCandidates merge_contact_pairs(const ContactCandidates& a, const ContactCandidates& b);

/// Smallest exact (unmollified) distance (m) between the primitives of `pairs` at state x;
/// +infinity if there is no pair.
double smallest_pair_distance(const ContactProxy& proxy, const ContactCandidates& pairs,
                              const Eigen::Ref<const Eigen::VectorXd>& x);

}  // namespace growshell
