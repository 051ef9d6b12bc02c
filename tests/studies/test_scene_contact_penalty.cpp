// scene_contact_proxy and scene_contact_penalty: the proxy has the scene's segments per edge,
// and the penalty's stiffness follows that proxy's spacing, so that a finer proxy carries the
// same contact pressure per penetration.
#include <gtest/gtest.h>

#include <string>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "studies/scene_contact_penalty.hpp"

namespace growshell {
namespace {

Scene scene_with_segments(int segments) {
  std::string text = R"({"thickness": 0.08, "mesh": {"rings": 4},
                         "study": {"kind": "econe_contact", "contact_proxy_segments": )";
  text += std::to_string(segments);
  text += "}}";
  return parse_scene(text, "test");
}

TEST(SceneContactProxy, HasTheScenesSegmentsPerEdge) {
  const Scene one = scene_with_segments(1);
  const ShellModel model(scene_mesh(one), scene_model_settings(one));
  const ContactProxy p1 = scene_contact_proxy(one, model);
  const ContactProxy p3 = scene_contact_proxy(scene_with_segments(3), model);
  // F n^2 triangles; V + E (n - 1) + F (n - 1)(n - 2) / 2 vertices (contact_proxy.hpp).
  const Eigen::Index F = p1.triangles.rows();
  const Eigen::Index V = p1.num_vertices();
  const Eigen::Index E = p1.edges.rows();
  EXPECT_EQ(p1.segments_per_edge, 1);
  EXPECT_EQ(p3.segments_per_edge, 3);
  EXPECT_EQ(p3.triangles.rows(), 9 * F);
  EXPECT_EQ(p3.num_vertices(), V + 2 * E + F);
}

TEST(SceneContactPenalty, StiffnessFollowsTheProxysSpacing) {
  const Scene one = scene_with_segments(1), two = scene_with_segments(2);
  const ShellModel model(scene_mesh(one), scene_model_settings(one));
  const ContactProxy p1 = scene_contact_proxy(one, model);
  const ContactProxy p2 = scene_contact_proxy(two, model);
  const ContactBranchOptions c1 = scene_contact_penalty(one, model, p1);
  const ContactBranchOptions c2 = scene_contact_penalty(two, model, p2);
  const double k1 = c1.stiffness, k2 = c2.stiffness;
  const double Y = one.material.youngs_modulus, h = 0.08;
  EXPECT_DOUBLE_EQ(k1, 10.0 * contact_stiffness_scale(Y, h, proxy_mean_edge_length(p1)));
  EXPECT_DOUBLE_EQ(k2, 10.0 * contact_stiffness_scale(Y, h, proxy_mean_edge_length(p2)));
  // Halving the spacing quarters k (to the unevenness of the lattice on the limit surface).
  EXPECT_NEAR(k2 / k1, 0.25, 0.02);
  // Everything else of the penalty is the proxy's business only through k.
  EXPECT_EQ(c1.contact_distance, c2.contact_distance);
  EXPECT_EQ(c1.exclusion_radius, c2.exclusion_radius);
  EXPECT_EQ(c1.candidate_margin, c2.candidate_margin);
}

TEST(SceneContactPenalty, TheScenesContactSurfaceSetsThePairsSurface) {
  Scene scene = scene_with_segments(1);
  const ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const ContactProxy proxy = scene_contact_proxy(scene, model);
  EXPECT_EQ(scene_contact_penalty(scene, model, proxy).gap.limit_surface, nullptr);
  scene.study.contact_surface = SceneContactSurface::LimitSurface;
  const ContactBranchOptions c = scene_contact_penalty(scene, model, proxy);
  ASSERT_NE(c.gap.limit_surface, nullptr);
  EXPECT_EQ(c.gap.limit_surface->exclusion_radius, c.exclusion_radius);
  EXPECT_EQ(c.gap.limit_surface->patches.patch.size(), model.patches().patch.size());
  EXPECT_EQ(c.gap.limit_surface->neighbourhoods.size(), model.patches().patch.size());
}

}  // namespace
}  // namespace growshell
