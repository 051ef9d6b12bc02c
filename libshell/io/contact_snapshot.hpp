#pragma once
/// \file
/// The contact proxy of a shell state as a triangle surface with each point's contact force
/// and contact flag, for viewing the contact zones (write it with write_vtu).

#include <Eigen/Core>

#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/vtk_writer.hpp"

namespace growshell {

/// The proxy surface at state x (points = proxy vertices, triangles = proxy triangles) with
/// point data "contact_force" (N: the magnitude of the summed force that the pairs of `gaps`
/// with forces `forces` (N, one per pair, >= 0) put on the point, each pair's force split over
/// its four proxy vertices by the closest-point weights |w_i|) and "in_contact" (1 where that
/// force is positive, else 0), and cell data "in_contact" (1 if any corner is in contact).
/// `gaps` may have no pairs (then forces must be empty). Throws std::invalid_argument if x or
/// forces have the wrong size.
SurfaceSnapshot contact_snapshot(const ContactProxy& proxy, const ContactGapConstraints& gaps,
                                 const Eigen::Ref<const Eigen::VectorXd>& x,
                                 const Eigen::Ref<const Eigen::VectorXd>& forces);

}  // namespace growshell
