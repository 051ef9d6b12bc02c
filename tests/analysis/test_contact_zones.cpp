// contact_zones and contact_plane_angle on hand-made pairs with known answers: zones by
// proximity and by normal, their forces, force-weighted normals and centroids, the active
// fraction, a mollified edge-edge pair counted with its force, the angle between planes, and
// bad input rejected naming it. (The zone of a solved contact state:
// tests/contact_solver/test_contact_equilibrium.cpp.)
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "libshell/analysis/contact_zones.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "tests/support/identity_proxy.hpp"

namespace growshell {
namespace {

using test_support::flatten;
using test_support::identity_proxy;

// Zone A: three points over and under a large triangle in z = 0 (normals +z, -z, +z), their
// contact points 0.41 and 0.40 m apart in a chain (0.8 m end to end), linked at 0.5 m.
// Zone B, 10 m away: two points over two triangles whose planes have normals n1 (tilted by
// gamma from z about y) and n2 (n1 turned by 0.2 rad about the first triangle's tangent t1).
// Two more pairs far from both carry forces below the active fraction (one tiny, one
// slightly negative, as Ipopt leaves inactive multipliers).
struct ZoneScene {
  static constexpr double kGamma = 1.1;
  Eigen::Vector3d n1, n2;
  Eigen::MatrixX3d points;
  Eigen::MatrixX3i triangles;
  ContactCandidates pairs;
  Eigen::VectorXd forces;

  ZoneScene() {
    n1 = Eigen::Vector3d(std::sin(kGamma), 0.0, std::cos(kGamma));
    const Eigen::Vector3d t1(std::cos(kGamma), 0.0, -std::sin(kGamma)), t2(0.0, 1.0, 0.0);
    const Eigen::Vector3d t2b = std::cos(0.2) * t2 + std::sin(0.2) * n1;
    n2 = t1.cross(t2b);
    const Eigen::Vector3d c(10.0, 0.0, 0.0), c2 = c + 0.2 * t2;
    // 0-2: triangle 0 in z = 0; 3-5: the points of zone A.
    std::vector<Eigen::Vector3d> p = {{0, 0, 0},       {2, 0, 0},        {0, 2, 0},
                                      {0.1, 0.1, 0.1}, {0.5, 0.1, -0.1}, {0.9, 0.1, 0.1}};
    // 6-8: triangle 1 (normal n1); 9-11: triangle 2 (normal n2); 12, 13: points over them.
    p.insert(p.end(), {Eigen::Vector3d(c), Eigen::Vector3d(c + t1), Eigen::Vector3d(c + t2),
                       Eigen::Vector3d(c2), Eigen::Vector3d(c2 + t1), Eigen::Vector3d(c2 + t2b),
                       Eigen::Vector3d(c + 0.2 * t1 + 0.3 * t2 + 0.1 * n1),
                       Eigen::Vector3d(c2 + 0.2 * t1 + 0.05 * t2b + 0.05 * n2)});
    // 14-16: triangle 3, far away; 17, 18: the points of the two inactive pairs.
    p.insert(p.end(), {{-10, 0, 0}, {-9, 0, 0}, {-10, 1, 0}, {-9.8, 0.1, 0.2}, {-9.8, 0.2, -0.3}});
    points.resize(static_cast<Eigen::Index>(p.size()), 3);
    for (std::size_t i = 0; i < p.size(); ++i)
      points.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
    triangles.resize(4, 3);
    triangles << 0, 1, 2, 6, 7, 8, 9, 10, 11, 14, 15, 16;
    pairs.vertex_triangle.resize(7, 2);
    pairs.vertex_triangle << 3, 0, 4, 0, 5, 0, 12, 1, 13, 2, 17, 3, 18, 3;
    pairs.edge_edge.resize(0, 2);
    forces.resize(7);
    forces << 2.0, 1.0, 0.5, 0.7, 0.25, 1e-5, -1e-9;
  }
};

TEST(ContactZones, TwoZonesWithKnownForcesNormalsAndAngle) {
  const ZoneScene z;
  const ContactProxy proxy = identity_proxy(z.points, z.triangles);
  const Eigen::VectorXd x = flatten(z.points);
  ContactGapConstraints gaps(proxy, z.pairs, 0.05, x.size());
  const std::vector<ContactZone> zones = contact_zones(gaps, x, z.forces, 0.5);
  ASSERT_EQ(zones.size(), 2u);
  // Largest total force first; pair lists are constraint indices.
  EXPECT_EQ(zones[0].pairs, (std::vector<Eigen::Index>{0, 1, 2}));
  EXPECT_EQ(zones[1].pairs, (std::vector<Eigen::Index>{3, 4}));
  // Sums of the same three or two doubles: exact up to one rounding each.
  EXPECT_NEAR(zones[0].force, 3.5, 1e-15);
  EXPECT_NEAR(zones[1].force, 0.95, 1e-15);
  // Zone A: the -z normal of the point under the plane is flipped to the strongest pair's +z.
  EXPECT_LE((zones[0].normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  // Centroid: force-weighted midpoints of the closest points (vertex and its foot).
  const Eigen::Vector3d centroid_a =
      (2.0 * Eigen::Vector3d(0.1, 0.1, 0.05) + 1.0 * Eigen::Vector3d(0.5, 0.1, -0.05) +
       0.5 * Eigen::Vector3d(0.9, 0.1, 0.05)) /
      3.5;
  EXPECT_LE((zones[0].centroid - centroid_a).norm(), 1e-12);
  // Zone B: force-weighted mean of n1 and n2. The pair normals come from closest points of
  // O(10 m) coordinates, so they carry rounding of about 1e-15 / 0.05 m: 1e-12 is ample.
  const Eigen::Vector3d normal_b = (0.7 * z.n1 + 0.25 * z.n2).normalized();
  EXPECT_LE((zones[1].normal - normal_b).norm(), 1e-12) << zones[1].normal.transpose();
  EXPECT_NEAR(contact_plane_angle(zones), std::acos(normal_b.z()), 1e-12);

  // A link distance below the chain's links splits zone A into its three pairs.
  const std::vector<ContactZone> split = contact_zones(gaps, x, z.forces, 0.3);
  ASSERT_EQ(split.size(), 4u);
  EXPECT_EQ(split[0].pairs, (std::vector<Eigen::Index>{0}));
  EXPECT_EQ(split[1].pairs, (std::vector<Eigen::Index>{1}));
  EXPECT_EQ(split[2].pairs, (std::vector<Eigen::Index>{3, 4}));
  EXPECT_EQ(split[3].pairs, (std::vector<Eigen::Index>{2}));
  // Pair 1's own normal is -z (no stronger pair in its zone to align with).
  EXPECT_LE((split[1].normal - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  // active_fraction 0 admits the tiny positive force (a third zone), never the negative one.
  const std::vector<ContactZone> all = contact_zones(gaps, x, z.forces, 0.5, 0.0);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[2].pairs, (std::vector<Eigen::Index>{5}));
  // No force at all: no zone.
  EXPECT_TRUE(contact_zones(gaps, x, Eigen::VectorXd::Zero(7), 0.5).empty());
  // The normal test: zone B's two normals differ by exactly 0.2 rad, zone A's by 0 (+z, -z).
  EXPECT_EQ(contact_zones(gaps, x, z.forces, 0.5, 1e-3, 0.21).size(), 2u);
  const std::vector<ContactZone> by_normal = contact_zones(gaps, x, z.forces, 0.5, 1e-3, 0.19);
  ASSERT_EQ(by_normal.size(), 3u);
  EXPECT_EQ(by_normal[0].pairs, (std::vector<Eigen::Index>{0, 1, 2}));
  EXPECT_EQ(by_normal[1].pairs, (std::vector<Eigen::Index>{3}));
  EXPECT_EQ(by_normal[2].pairs, (std::vector<Eigen::Index>{4}));
  EXPECT_NEAR(contact_plane_angle({by_normal[1], by_normal[2]}), 0.2, 1e-12);
  EXPECT_THROW(contact_zones(gaps, x, z.forces, 0.5, 1e-3, 0.0), std::invalid_argument);
  EXPECT_THROW(contact_zones(gaps, x, z.forces, 0.5, 1e-3, 2.0), std::invalid_argument);
}

// cone_contact_plane_angle: the zones of contact_zones with a link of 0.1 radius, the active
// fraction 1e-3 and 30 degrees between normals. With radius 5 (link 0.5 m) these are the two
// zones above, and gamma is their planes' angle; with radius 3 (link 0.3 m) zone A falls
// apart into its three pairs, the two largest of which (+z and -z) lie in one plane.
TEST(ContactZones, ConePlaneAngleUsesTheStudiesZones) {
  const ZoneScene z;
  const ContactProxy proxy = identity_proxy(z.points, z.triangles);
  const Eigen::VectorXd x = flatten(z.points);
  ContactGapConstraints gaps(proxy, z.pairs, 0.05, x.size());
  EXPECT_EQ(cone_contact_plane_angle(gaps, x, z.forces, 5.0),
            contact_plane_angle(contact_zones(gaps, x, z.forces, 0.5, 1e-3, std::numbers::pi / 6)));
  const Eigen::Vector3d normal_b = (0.7 * z.n1 + 0.25 * z.n2).normalized();
  EXPECT_NEAR(cone_contact_plane_angle(gaps, x, z.forces, 5.0), std::acos(normal_b.z()), 1e-12);
  EXPECT_NEAR(cone_contact_plane_angle(gaps, x, z.forces, 3.0), 0.0, 1e-12);
  EXPECT_TRUE(std::isnan(cone_contact_plane_angle(gaps, x, Eigen::VectorXd::Zero(7), 5.0)));
}

// A mollified edge-edge pair pushes with multiplier * mollifier (ContactPairGeometry), and
// that is the force a zone sums and weights its normal with. Edge P along x at height 0.3
// over edge Q at angle alpha = 0.02 in z = 0 (both of length 2): r = sin^2(alpha) / 1e-3 =
// 0.4, m = (2 - r) r = 0.64 (tests/contact). In the same zone a point over a triangle whose
// plane is tilted by beta = 0.4 about y.
TEST(ContactZones, MollifiedEdgePairCountsWithItsForceNotItsMultiplier) {
  const double alpha = 0.02, beta = 0.4;
  const Eigen::Vector3d nt(std::sin(beta), 0.0, std::cos(beta)),
      t1(std::cos(beta), 0.0, -std::sin(beta)), t2(0.0, 1.0, 0.0), c0(0.0, 0.5, 0.0);
  Eigen::MatrixX3d points(8, 3);
  points.row(0) << -1, 0, 0.3;
  points.row(1) << 1, 0, 0.3;
  points.row(2) << -std::cos(alpha), -std::sin(alpha), 0;
  points.row(3) << std::cos(alpha), std::sin(alpha), 0;
  points.row(4) = c0.transpose();
  points.row(5) = (c0 + t1).transpose();
  points.row(6) = (c0 + t2).transpose();
  points.row(7) = (c0 + 0.2 * t1 + 0.3 * t2 + 0.3 * nt).transpose();
  Eigen::MatrixX3i triangles(1, 3);
  triangles << 4, 5, 6;
  Eigen::MatrixX2i edges(2, 2);
  edges << 0, 1, 2, 3;
  const ContactProxy proxy = identity_proxy(points, triangles, edges);
  ContactCandidates pairs;
  pairs.vertex_triangle.resize(1, 2);
  pairs.vertex_triangle << 7, 0;
  pairs.edge_edge.resize(1, 2);
  pairs.edge_edge << 0, 1;
  const Eigen::VectorXd x = flatten(points);
  ContactGapConstraints gaps(proxy, pairs, 0.3, x.size());
  const double r = std::pow(std::sin(alpha), 2) / 1e-3;
  const double m = (2.0 - r) * r;
  ASSERT_NEAR(gaps.pair_geometry(x, 1).mollifier, m, 1e-14);
  const Eigen::Vector2d multipliers(0.5, 1.0);  // vertex-triangle, edge-edge
  const std::vector<ContactZone> zones = contact_zones(gaps, x, multipliers, 1.0);
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_NEAR(zones[0].force, 0.5 + m, 1e-14);
  const Eigen::Vector3d normal = (m * Eigen::Vector3d(0, 0, 1) + 0.5 * nt).normalized();
  EXPECT_LE((zones[0].normal - normal).norm(), 1e-12) << zones[0].normal.transpose();
  // The active test compares forces too: at active_fraction 0.7 the point pair (0.5) stays
  // active against the largest force 0.64 (threshold 0.448), though it would not against the
  // largest multiplier 1.0 (threshold 0.7).
  const std::vector<ContactZone> strong = contact_zones(gaps, x, multipliers, 1.0, 0.7);
  ASSERT_EQ(strong.size(), 1u);
  EXPECT_EQ(strong[0].pairs, (std::vector<Eigen::Index>{0, 1}));
}

TEST(ContactZones, PlaneAngleOfHandMadeZones) {
  ContactZone a, b;
  a.normal = Eigen::Vector3d(0, 0, 1);
  EXPECT_TRUE(std::isnan(contact_plane_angle({})));
  EXPECT_TRUE(std::isnan(contact_plane_angle({a})));
  for (const double gamma : {0.0, 0.3, std::numbers::pi / 2, 2.0, std::numbers::pi}) {
    b.normal = Eigen::Vector3d(std::sin(gamma), 0.0, std::cos(gamma));
    // Planes, not normals: gamma and pi - gamma are the same pair of planes.
    const double expected = gamma <= std::numbers::pi / 2 ? gamma : std::numbers::pi - gamma;
    // acos loses accuracy only near 0 (dot = 1): 1e-7 there, 1e-12 elsewhere.
    EXPECT_NEAR(contact_plane_angle({a, b}), expected,
                expected < 0.1 || expected > std::numbers::pi - 0.1 ? 1e-7 : 1e-12)
        << gamma;
  }
}

TEST(ContactZones, RejectsBadInput) {
  const ZoneScene z;
  const ContactProxy proxy = identity_proxy(z.points, z.triangles);
  const Eigen::VectorXd x = flatten(z.points);
  ContactGapConstraints gaps(proxy, z.pairs, 0.05, x.size());
  auto message_of = [](auto&& call) {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message_of([&] {
              contact_zones(gaps, x, Eigen::VectorXd::Ones(6), 0.5);
            }).find("forces has 6"),
            std::string::npos);
  for (const double bad : {0.0, -1.0, nan})
    EXPECT_NE(message_of([&] { contact_zones(gaps, x, z.forces, bad); }).find("link_distance"),
              std::string::npos)
        << bad;
  for (const double bad : {-0.1, nan})
    EXPECT_NE(
        message_of([&] { contact_zones(gaps, x, z.forces, 0.5, bad); }).find("active_fraction"),
        std::string::npos)
        << bad;
}

}  // namespace
}  // namespace growshell
