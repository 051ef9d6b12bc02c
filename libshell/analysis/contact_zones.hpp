#pragma once
/// \file
/// Contact zones of a solved contact state: the active pairs grouped by proximity, each with
/// its total force and the plane through it (normal = force-weighted mean of the pair
/// normals), and the angle gamma between the planes of the two largest zones (physics brief:
/// gamma = pi/2 for the symmetric e-cone at first contact).

#include <Eigen/Core>
#include <vector>

#include "libshell/contact/contact_gap_constraints.hpp"

#include <numbers>

namespace growshell {

/// One zone (global Cartesian basis, SI units).
struct ContactZone {
  std::vector<Eigen::Index> pairs;  ///< constraint indices of its active pairs
  double force = 0.0;               ///< sum of the pair forces (N)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< unit normal of its contact plane
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< force-weighted contact point (m)
};

/// Zones, largest force first. A pair is active if its force exceeds active_fraction times
/// the largest force (>= 0); two active pairs belong to the same zone if their contact points
/// (midpoints of the closest points) are closer than link_distance (m, > 0) and their normals
/// differ by less than max_normal_angle (radians, in (0, pi/2]; pi/2 = proximity only),
/// transitively. The normal test keeps apart zones that meet along a line, such as the upper
/// and lower contact of an e-cone, whose planes cross at the apex at gamma ~ pi/2.
/// Pair normals are sign-aligned with the zone's strongest pair before averaging (a normal's
/// sign only says which primitive is listed first). Throws std::invalid_argument if forces
/// does not have constraints.count() entries or the parameters are out of range.
std::vector<ContactZone> contact_zones(const ContactGapConstraints& constraints,
                                       const Eigen::Ref<const Eigen::VectorXd>& x,
                                       const Eigen::Ref<const Eigen::VectorXd>& forces,
                                       double link_distance, double active_fraction = 1e-3,
                                       double max_normal_angle = std::numbers::pi / 2);

/// Angle (radians, in [0, pi/2]) between the contact planes of the two largest zones; NaN if
/// there are fewer than two zones.
double contact_plane_angle(const std::vector<ContactZone>& zones);

/// gamma of an e-cone of radius `radius` (m) in contact (../shared/docs/physics.md): the angle
/// between the planes of its two largest zones, with the zones every growshell program and
/// study measures it on: pairs with more than 1e-3 of the largest force, linked within
/// 0.1 radius, with normals within 30 degrees of each other (so that the upper and lower
/// contact, which meet at the apex, stay apart). NaN with fewer than two zones or no force.
double cone_contact_plane_angle(const ContactGapConstraints& constraints,
                                const Eigen::Ref<const Eigen::VectorXd>& x,
                                const Eigen::Ref<const Eigen::VectorXd>& forces, double radius);

}  // namespace growshell
