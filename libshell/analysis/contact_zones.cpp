#include "libshell/analysis/contact_zones.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

namespace growshell {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

}  // namespace

std::vector<ContactZone> contact_zones(const ContactGapConstraints& constraints,
                                       const Eigen::Ref<const Eigen::VectorXd>& x,
                                       const Eigen::Ref<const Eigen::VectorXd>& forces,
                                       double link_distance, double active_fraction,
                                       double max_normal_angle) {
  if (forces.size() != constraints.count())
    throw std::invalid_argument("contact_zones: forces has " + std::to_string(forces.size()) +
                                " entries, expected " + std::to_string(constraints.count()));
  if (!(link_distance > 0.0)) throw std::invalid_argument("contact_zones: link_distance must be > 0");
  if (!(active_fraction >= 0.0)) throw std::invalid_argument("contact_zones: active_fraction must be >= 0");
  if (!(max_normal_angle > 0.0 && max_normal_angle <= 0.5 * std::numbers::pi + 1e-12))
    throw std::invalid_argument("contact_zones: max_normal_angle must be in (0, pi/2]");
  const double min_normal_cosine = std::cos(max_normal_angle) - 1e-12;
  std::vector<ContactZone> zones;
  // A pair's force is its multiplier times its mollifier: a mollified edge-edge constraint
  // m (d - offset) pushes with multiplier * m along grad d at contact (ContactPairGeometry),
  // so the bare multiplier of a nearly parallel edge pair overstates its force by 1 / m.
  std::vector<Eigen::Index> pushing;
  std::vector<ContactPairGeometry> pushing_geometry;
  std::vector<double> pushing_force;
  for (Eigen::Index k = 0; k < forces.size(); ++k)
    if (forces(k) > 0.0) {
      pushing.push_back(k);
      pushing_geometry.push_back(constraints.pair_geometry(x, k));
      pushing_force.push_back(forces(k) * pushing_geometry.back().mollifier);
    }
  double largest = 0.0;
  for (const double f : pushing_force) largest = std::max(largest, f);
  if (!(largest > 0.0)) return zones;
  std::vector<Eigen::Index> active;
  std::vector<ContactPairGeometry> geometry;
  std::vector<double> force;
  for (std::size_t i = 0; i < pushing.size(); ++i)
    if (pushing_force[i] > active_fraction * largest) {
      active.push_back(pushing[i]);
      geometry.push_back(pushing_geometry[i]);
      force.push_back(pushing_force[i]);
    }
  const int n = static_cast<int>(active.size());
  std::vector<Eigen::Vector3d> point(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    point[static_cast<std::size_t>(i)] =
        0.5 * (geometry[static_cast<std::size_t>(i)].closest_point_first + geometry[static_cast<std::size_t>(i)].closest_point_second);
  // Transitive grouping by distance (quadratic in the number of active pairs, which is small:
  // the pairs of the contact zones only).
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if ((point[static_cast<std::size_t>(i)] - point[static_cast<std::size_t>(j)]).norm() < link_distance &&
          std::abs(geometry[static_cast<std::size_t>(i)].normal.dot(geometry[static_cast<std::size_t>(j)].normal)) >=
              min_normal_cosine)
        parent[static_cast<std::size_t>(find_root(parent, i))] = find_root(parent, j);
  std::vector<int> zone_of_root(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    const int root = find_root(parent, i);
    if (zone_of_root[static_cast<std::size_t>(root)] < 0) {
      zone_of_root[static_cast<std::size_t>(root)] = static_cast<int>(zones.size());
      zones.emplace_back();
    }
    zones[static_cast<std::size_t>(zone_of_root[static_cast<std::size_t>(root)])].pairs.push_back(i);
  }
  for (ContactZone& z : zones) {
    // Align every normal with the zone's strongest pair, then average weighted by force.
    const auto strongest = *std::max_element(z.pairs.begin(), z.pairs.end(), [&](Eigen::Index a, Eigen::Index b) {
      return force[static_cast<std::size_t>(a)] < force[static_cast<std::size_t>(b)];
    });
    const Eigen::Vector3d reference = geometry[static_cast<std::size_t>(strongest)].normal;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), where = Eigen::Vector3d::Zero();
    for (Eigen::Index& i : z.pairs) {
      const double f = force[static_cast<std::size_t>(i)];
      const Eigen::Vector3d nrm = geometry[static_cast<std::size_t>(i)].normal;
      sum += f * (nrm.dot(reference) >= 0.0 ? nrm : Eigen::Vector3d(-nrm));
      where += f * point[static_cast<std::size_t>(i)];
      z.force += f;
      i = active[static_cast<std::size_t>(i)];  // from active-list index to constraint index
    }
    z.normal = sum.norm() > 0.0 ? Eigen::Vector3d(sum.normalized()) : reference;
    z.centroid = where / z.force;
  }
  std::sort(zones.begin(), zones.end(), [](const ContactZone& a, const ContactZone& b) { return a.force > b.force; });
  return zones;
}

double contact_plane_angle(const std::vector<ContactZone>& zones) {
  if (zones.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  return std::acos(std::min(1.0, std::abs(zones[0].normal.dot(zones[1].normal))));
}

double cone_contact_plane_angle(const ContactGapConstraints& constraints,
                                const Eigen::Ref<const Eigen::VectorXd>& x,
                                const Eigen::Ref<const Eigen::VectorXd>& forces, double radius) {
  if (forces.size() == 0 || !(forces.maxCoeff() > 0.0))
    return std::numeric_limits<double>::quiet_NaN();
  return contact_plane_angle(
      contact_zones(constraints, x, forces, 0.1 * radius, 1e-3, std::numbers::pi / 6));
}

}  // namespace growshell
