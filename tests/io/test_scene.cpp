#include "libshell/io/scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <variant>

#include <unistd.h>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/gmsh_disc_mesh.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"
#include "tests/support/error_message.hpp"

namespace growshell {
namespace {

/// The message with which parse_scene refuses `text`, empty if it takes it.
std::string refusal(const std::string& text) {
  return test_support::error_of([&text] { parse_scene(text, "t"); });
}

bool mentions(const std::string& message, const std::string& part) {
  return message.find(part) != std::string::npos;
}

namespace fs = std::filesystem;

/// The repository root, found from this file's (absolute) path: tests/io/test_scene.cpp.
fs::path repo_root() { return fs::path(__FILE__).parent_path().parent_path().parent_path(); }

/// A scratch directory per test, removed at the end.
class SceneFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // The process id keeps concurrent runs from other build directories apart.
    dir_ = fs::temp_directory_path() /
           ("growshell_scene_" + std::to_string(::getpid()) + "_" + info->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }

  fs::path dir_;
};

using test_support::error_of;

// ---- Defaults ----------------------------------------------------------------------------

TEST(Scene, DefaultsAreThePapersDisc) {
  const Scene s = default_scene();
  EXPECT_EQ(s.geometry.shape, SceneShape::Disc);
  EXPECT_EQ(s.geometry.radius, 1.0);
  ASSERT_TRUE(std::holds_alternative<ConstantThickness>(s.thickness));
  EXPECT_EQ(std::get<ConstantThickness>(s.thickness).value, 0.02);
  EXPECT_EQ(s.material.youngs_modulus, 1e4);
  EXPECT_EQ(s.material.poisson_ratio, 0.3);
  EXPECT_EQ(s.growth.law, GrowthLaw::Circumferential);
  EXPECT_EQ(s.growth.center, Eigen::Vector2d::Zero());
  EXPECT_EQ(s.mesh.rings, 24);
  EXPECT_EQ(s.mesh.grading_exponent, 3.0);
  EXPECT_FALSE(s.mesh.min_spacing.has_value());
  EXPECT_EQ(resolved_min_spacing(s), 0.005);  // h / 4 (rings), exact in binary up to one rounding
  EXPECT_EQ(s.mesh.quadrature_degree, 2);
  EXPECT_FALSE(s.physics.contact);
  EXPECT_FALSE(s.physics.contact_distance.has_value());
  EXPECT_FALSE(s.physics.contact_exclusion_radius.has_value());
  EXPECT_EQ(resolved_exclusion_radius(s), 8 * 0.02);  // the apex model: 8 h
  EXPECT_EQ(s.continuation.phi_start, 0.0);
  EXPECT_EQ(s.continuation.phi_max, 3.73);
  EXPECT_EQ(s.continuation.max_step, 0.1);
  EXPECT_EQ(s.continuation.min_step, 1e-4);
  EXPECT_EQ(s.continuation.direction, ContinuationDirection::Forward);
  EXPECT_EQ(s.continuation.mode, 2);
  EXPECT_EQ(s.continuation.perturbation_amplitude, 1e-3);
  EXPECT_EQ(s.continuation.seed, 1u);
  EXPECT_EQ(s.output.directory, "out");
  EXPECT_EQ(s.output.snapshot_every, 0);
  EXPECT_EQ(s.study.kind, StudyKind::ConeBranch);
  EXPECT_EQ(study_kind_name(s.study.kind), "cone_branch");
  EXPECT_FALSE(s.study.through_contact);
  EXPECT_EQ(s.study.tolerance, 1e-6);
  EXPECT_EQ(s.study.max_tangent_angle, 0.3);
  EXPECT_EQ(s.study.eigenmodes, 2);
  EXPECT_TRUE(s.study.symmetric_subspace);
  EXPECT_FALSE(s.study.half_turn_subspace);
  EXPECT_TRUE(s.study.index_excludes_pattern_turn);
  EXPECT_EQ(s.study.symmetry_threshold, 1e-3);
  EXPECT_EQ(s.study.core_radius, 0.0);
  EXPECT_NO_THROW(validate_scene(s));
}

TEST(Scene, MinSpacingFollowsAThicknessOverride) {
  Scene s = default_scene();
  apply_override(s, "thickness", "0.005");
  EXPECT_EQ(resolved_min_spacing(s), 0.00125);  // h / 4 for the rings and gmsh families
  apply_override(s, "mesh.family", "gmsh");
  EXPECT_EQ(resolved_min_spacing(s), 0.00125);
  apply_override(s, "mesh.family", "lattice");
  EXPECT_EQ(resolved_min_spacing(s), 0.0025);  // h / 2 for the lattice
  apply_override(s, "mesh.min_spacing", "0.004");
  EXPECT_EQ(resolved_min_spacing(s), 0.004);
  apply_override(s, "mesh.min_spacing", "auto");
  EXPECT_EQ(resolved_min_spacing(s), 0.0025);
}

// ---- Round trip --------------------------------------------------------------------------

/// A scene in which every field differs from its default.
Scene everything_changed() {
  Scene s;
  s.geometry.shape = SceneShape::Ring;
  s.geometry.radius = 2.5;
  s.geometry.inner_radius = 0.1 + 0.2;  // not exactly 0.3: the writer must keep all digits
  s.thickness = LinearThickness{0.03, 1.0 / 3.0};
  s.material.youngs_modulus = 2.5e7;
  s.material.poisson_ratio = -0.25;
  s.growth.center = {0.125, -0.5};
  s.mesh.rings = 7;
  s.mesh.radial_layers = 9;
  s.mesh.grading_exponent = 1.0;
  s.mesh.min_spacing = 0.003;
  s.mesh.quadrature_degree = 5;
  s.physics.contact = true;
  s.physics.contact_distance = 0.021;
  s.physics.contact_exclusion_radius = 0.125;
  s.continuation.phi_start = 6.5;
  s.continuation.phi_min = 1.0;
  s.continuation.phi_max = 12.566370614359172;
  s.continuation.max_step = 0.05;
  s.continuation.min_step = 1e-6;
  s.continuation.direction = ContinuationDirection::Backward;
  s.continuation.mode = 3;
  s.continuation.perturbation_amplitude = 0.0;
  s.continuation.seed = 4294967295u;
  s.output.directory = "results/ring \"a\"";
  s.output.snapshot_every = 4;
  s.output.write_vtk = false;
  s.study.through_contact = true;
  s.study.tolerance = 1e-5;
  s.study.max_tangent_angle = 0.8;
  s.study.eigenmodes = 0;
  s.study.symmetric_subspace = true;
  s.study.half_turn_subspace = true;
  s.study.symmetry_threshold = 1.0 / 3.0;
  s.study.core_radius = 0.05;
  return s;
}

TEST(Scene, ExclusionRadiusFollowsAThicknessOverrideAndMustReachTheContactDistance) {
  Scene s = default_scene();
  apply_override(s, "thickness", "0.04");
  EXPECT_EQ(resolved_exclusion_radius(s), 8 * 0.04);
  apply_override(s, "physics.contact_exclusion_radius", "0.16");
  EXPECT_EQ(resolved_exclusion_radius(s), 0.16);
  // Below the contact distance neighbours on a flat sheet would be taken for contact.
  s.physics.contact_exclusion_radius = 0.03;
  EXPECT_EQ(error_of([&] { validate_scene(s); }),
            "physics.contact_exclusion_radius = 0.03 must be >= the contact distance 0.04 "
            "(physics.contact_distance, or the thickness at the centre if auto)");
  s.physics.contact_distance = 0.025;
  EXPECT_EQ(resolved_exclusion_radius(s), 0.03);
  s.physics.contact_exclusion_radius = -1.0;
  EXPECT_EQ(error_of([&] { validate_scene(s); }),
            "physics.contact_exclusion_radius = -1 must be finite and > 0");
  apply_override(s, "physics.contact_exclusion_radius", "auto");
  EXPECT_EQ(resolved_exclusion_radius(s), 8 * 0.04);
}

TEST_F(SceneFileTest, MeshFamiliesBuildTheirMeshes) {
  Scene s = default_scene();
  s.thickness = ConstantThickness{0.04};
  s.mesh.family = MeshFamily::Rings;
  const TriangleMesh rings = scene_mesh(s);
  // The rings family has the quarter turn, faces included; its size floor is h / 4 = 0.01.
  EXPECT_NO_THROW(check_maps_faces_onto_faces(MeshTopology(rings), quarter_turn_symmetry(rings.vertices, 1e-9)));
  s.mesh.family = MeshFamily::Gmsh;
  s.mesh.size_slope = 0.3;
  const TriangleMesh gmsh = scene_mesh(s);
  EXPECT_GT(gmsh.faces.rows(), 100);
  EXPECT_NE(gmsh.vertices.rows(), rings.vertices.rows());
  // gmsh_d4: Gmsh's sector reflected, with the rings family's quarter turn (faces included),
  // read from its name in a scene file; the unsymmetric gmsh mesh does not have it.
  apply_override(s, "mesh.family", "gmsh_d4");
  EXPECT_EQ(s.mesh.family, MeshFamily::GmshD4);
  EXPECT_TRUE(graded_by_size(s.mesh.family));
  const TriangleMesh gmsh_d4 = scene_mesh(s);
  EXPECT_NO_THROW(check_maps_faces_onto_faces(MeshTopology(gmsh_d4),
                                              quarter_turn_symmetry(gmsh_d4.vertices, 1e-9)));
  EXPECT_THROW(quarter_turn_symmetry(gmsh.vertices, 1e-9), std::invalid_argument);
  s.mesh.family = MeshFamily::Gmsh;
  // A file: the Gmsh sheet written as .msh and read back gets the same ghost layer.
  const std::string msh = (dir_ / "disc.msh").string();
  GmshDiscMeshOptions o;
  o.size_slope = 0.3;
  o.size_floor = 0.01;
  o.msh_file = msh;
  make_gmsh_disc_sheet(o);
  s.mesh.family = MeshFamily::File;
  s.mesh.file = msh;
  const TriangleMesh from_file = scene_mesh(s);
  EXPECT_EQ(from_file.faces, gmsh.faces);
  EXPECT_LT((from_file.vertices - gmsh.vertices).cwiseAbs().maxCoeff(), 1e-12);
}

// The default scene is meshed by the rings family: make_ring_disc_mesh with the default
// size_slope 0.1 and the floor h/4; for a ring the same family makes the annulus.
TEST(Scene, DefaultFamilyIsTheRingsMeshForDiscsAndRings) {
  Scene s = default_scene();
  EXPECT_EQ(s.mesh.family, MeshFamily::Rings);
  EXPECT_EQ(mesh_family_name(s.mesh.family), "rings");
  RingDiscMeshOptions o;
  o.size_slope = 0.1;
  o.size_floor = 0.005;
  const TriangleMesh disc = make_ring_disc_mesh(o);
  const TriangleMesh from_scene = scene_mesh(s);
  EXPECT_EQ(from_scene.faces, disc.faces);
  EXPECT_EQ(from_scene.vertices, disc.vertices);
  s.geometry.shape = SceneShape::Ring;
  s.geometry.inner_radius = 0.5;
  o.inner_radius = 0.5;
  const TriangleMesh annulus = make_ring_disc_mesh(o);
  EXPECT_EQ(scene_mesh(s).faces, annulus.faces);
  EXPECT_EQ(scene_mesh(s).vertices, annulus.vertices);
  // The inner rim (ring 0: 64 vertices) lies on r = R_i.
  for (int v = 0; v < 64; ++v) EXPECT_NEAR(annulus.vertices.row(v).norm(), 0.5, 1e-15);
}

TEST(Scene, MeshFamilyErrorsNameTheKey) {
  Scene s = default_scene();
  s.mesh.family = MeshFamily::File;
  EXPECT_EQ(error_of([&] { validate_scene(s); }),
            "mesh.family = file needs mesh.file, the path of a .msh or .obj mesh");
  s.mesh.file = "mesh.stl";
  EXPECT_NE(error_of([&] { scene_mesh(s); }).find("the mesh format is told by the extension"),
            std::string::npos);
  s = default_scene();
  s.mesh.file = "disc.msh";
  EXPECT_EQ(error_of([&] { validate_scene(s); }),
            "mesh.file = 'disc.msh' is read only with mesh.family = file");
  s = default_scene();
  EXPECT_EQ(error_of([&] { apply_override(s, "mesh.family", "hexagon"); }),
            "mesh.family = \"hexagon\" must be one of \"lattice\", \"rings\", \"gmsh\", \"gmsh_d4\", \"file\"");
}

TEST_F(SceneFileTest, FullFileRoundTripKeepsEveryField) {
  const Scene a = everything_changed();
  ASSERT_NO_THROW(validate_scene(a));
  const Scene b = read_scene(write("scene.json", scene_to_json(a)));
  EXPECT_EQ(b.geometry.shape, a.geometry.shape);
  EXPECT_EQ(b.geometry.radius, a.geometry.radius);
  EXPECT_EQ(b.geometry.inner_radius, a.geometry.inner_radius);  // bit-exact
  ASSERT_TRUE(std::holds_alternative<LinearThickness>(b.thickness));
  EXPECT_EQ(std::get<LinearThickness>(b.thickness).center, 0.03);
  EXPECT_EQ(std::get<LinearThickness>(b.thickness).rim, 1.0 / 3.0);
  EXPECT_EQ(b.material.youngs_modulus, a.material.youngs_modulus);
  EXPECT_EQ(b.material.poisson_ratio, a.material.poisson_ratio);
  EXPECT_EQ(b.growth.law, a.growth.law);
  EXPECT_EQ(b.growth.center, a.growth.center);
  EXPECT_EQ(b.mesh.rings, a.mesh.rings);
  EXPECT_EQ(b.mesh.radial_layers, a.mesh.radial_layers);
  EXPECT_EQ(b.mesh.grading_exponent, a.mesh.grading_exponent);
  EXPECT_EQ(b.mesh.min_spacing, a.mesh.min_spacing);
  EXPECT_EQ(b.mesh.quadrature_degree, a.mesh.quadrature_degree);
  EXPECT_EQ(b.physics.contact, a.physics.contact);
  EXPECT_EQ(b.physics.contact_distance, a.physics.contact_distance);
  EXPECT_EQ(b.physics.contact_exclusion_radius, a.physics.contact_exclusion_radius);
  EXPECT_EQ(b.continuation.phi_start, a.continuation.phi_start);
  EXPECT_EQ(b.continuation.phi_min, a.continuation.phi_min);
  EXPECT_EQ(b.continuation.phi_max, a.continuation.phi_max);
  EXPECT_EQ(b.continuation.max_step, a.continuation.max_step);
  EXPECT_EQ(b.continuation.min_step, a.continuation.min_step);
  EXPECT_EQ(b.continuation.direction, a.continuation.direction);
  EXPECT_EQ(b.continuation.mode, a.continuation.mode);
  EXPECT_EQ(b.continuation.perturbation_amplitude, a.continuation.perturbation_amplitude);
  EXPECT_EQ(b.continuation.seed, a.continuation.seed);
  EXPECT_EQ(b.output.directory, a.output.directory);
  EXPECT_EQ(b.output.snapshot_every, a.output.snapshot_every);
  EXPECT_EQ(b.output.write_vtk, a.output.write_vtk);
  EXPECT_EQ(b.study.kind, a.study.kind);
  EXPECT_EQ(b.study.through_contact, a.study.through_contact);
  EXPECT_EQ(b.study.tolerance, a.study.tolerance);
  EXPECT_EQ(b.study.max_tangent_angle, a.study.max_tangent_angle);
  EXPECT_EQ(b.study.eigenmodes, a.study.eigenmodes);
  EXPECT_EQ(b.study.symmetric_subspace, a.study.symmetric_subspace);
  EXPECT_EQ(b.study.half_turn_subspace, a.study.half_turn_subspace);
  EXPECT_EQ(b.study.symmetry_threshold, a.study.symmetry_threshold);
  EXPECT_EQ(b.study.core_radius, a.study.core_radius);
  EXPECT_EQ(scene_to_json(b), scene_to_json(a));
}

TEST_F(SceneFileTest, DefaultSceneRoundTripsAndWritesEveryKey) {
  const std::string text = scene_to_json(default_scene());
  EXPECT_EQ(scene_to_json(read_scene(write("d.json", text))), text);
  for (const std::string& key : scene_keys()) {
    const std::string leaf = key.substr(key.rfind('.') + 1);
    EXPECT_NE(text.find("\"" + leaf + "\":"), std::string::npos) << key;
  }
  EXPECT_NE(text.find("\"min_spacing\": \"auto\""), std::string::npos);
}

TEST_F(SceneFileTest, PartialFileOverridesOnlyWhatItSets) {
  const Scene s = read_scene(write("p.json", R"({
    // comments are allowed
    "thickness": 0.005,
    "mesh": {"rings": 12},
    "continuation": {"direction": "backward", "phi_start": 2}
  })"));
  EXPECT_EQ(std::get<ConstantThickness>(s.thickness).value, 0.005);
  EXPECT_EQ(s.mesh.rings, 12);
  EXPECT_EQ(s.continuation.direction, ContinuationDirection::Backward);
  EXPECT_EQ(s.continuation.phi_start, 2.0);
  // Untouched keys keep their defaults, including those of the sections the file opened.
  EXPECT_EQ(s.mesh.grading_exponent, 3.0);
  EXPECT_EQ(s.continuation.phi_max, 3.73);
  EXPECT_EQ(s.material.youngs_modulus, 1e4);
  EXPECT_EQ(resolved_min_spacing(s), 0.00125);
}

TEST(Scene, ANumberBeyondDoubleIsMalformedJsonNotACrash) {
  // Found by fuzz/fuzz_scene_parser: the JSON parser reports it as out_of_range, not as a
  // parse error.
  try {
    parse_scene("{\"thickness\": 1e400}", "text");
    FAIL() << "a number beyond double was read";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("text: malformed JSON"), std::string::npos) << e.what();
  }
}

TEST(Scene, ModelFingerprintChangesWithTheModelOnly) {
  const Scene base = default_scene();
  const std::uint64_t f = scene_model_fingerprint(base);
  auto with = [&](auto change) {
    Scene s = base;
    change(s);
    return scene_model_fingerprint(s);
  };
  // What the trace does, where it writes and what it studies leave the model alone.
  EXPECT_EQ(with([](Scene& s) { s.continuation.phi_max = 7.6; }), f);
  EXPECT_EQ(with([](Scene& s) { s.output.directory = "elsewhere"; }), f);
  EXPECT_EQ(with([](Scene& s) { s.study.through_contact = true; }), f);
  EXPECT_EQ(with([](Scene& s) { s.physics.contact = true; }), f);
  // Each model section changes it, and so does the floor that "auto" resolves to.
  EXPECT_NE(with([](Scene& s) { s.thickness = ConstantThickness{0.03}; }), f);
  EXPECT_NE(with([](Scene& s) { s.material.poisson_ratio = 0.25; }), f);
  EXPECT_NE(with([](Scene& s) { s.material.stretching_law = StretchingLaw::kNeoHookean; }), f);
  EXPECT_NE(with([](Scene& s) { s.growth.smoothing_radius = 0.01; }), f);
  EXPECT_NE(with([](Scene& s) {
              s.growth.smoothing_radius = 0.01;
              s.growth.smoothing_profile = GrowthSmoothingProfile::Gaussian;
            }),
            with([](Scene& s) { s.growth.smoothing_radius = 0.01; }));
  EXPECT_NE(with([](Scene& s) { s.mesh.size_slope = 0.07; }), f);
  EXPECT_NE(with([](Scene& s) { s.geometry.radius = 2.0; }), f);
  // States saved before growth.smoothing_profile existed carry this fingerprint of the default
  // scene (a442f29); the default profile must keep it.
  EXPECT_EQ(f, 4494488817278316686ull);
  Scene explicit_floor = base;
  explicit_floor.mesh.min_spacing = resolved_min_spacing(base);
  EXPECT_EQ(scene_model_fingerprint(explicit_floor), f);
}

TEST(Scene, EveryShippedSceneReadsAndValidates) {
  // The scenes a user runs as they are: examples/scenes/ and the paper's, scenes/paper/.
  int read = 0;
  for (const char* folder : {"examples/scenes", "scenes/paper"}) {
    for (const auto& entry : fs::directory_iterator(repo_root() / folder)) {
      if (entry.path().extension() != ".json") continue;
      SCOPED_TRACE(entry.path().string());
      const Scene scene = read_scene(entry.path().string());
      EXPECT_NO_THROW(validate_scene(scene));
      ++read;
    }
  }
  EXPECT_GE(read, 4);
  const Scene fig4 = read_scene((repo_root() / "scenes/paper/fig4_econe_contact_h004.json").string());
  EXPECT_EQ(fig4.study.kind, StudyKind::EconeContact);
  EXPECT_EQ(resolved_exclusion_radius(fig4), 8 * 0.04);  // the default apex model
}

TEST(Scene, ExampleFileIsTheDefaultSceneInFull) {
  const fs::path example = repo_root() / "examples" / "scenes" / "disc_h002.json";
  std::ifstream in(example);
  ASSERT_TRUE(in) << example;
  std::stringstream text;
  text << in.rdbuf();
  // Byte-equal: the example is regenerated whenever a default changes.
  EXPECT_EQ(text.str(), scene_to_json(default_scene()));
  EXPECT_EQ(scene_to_json(read_scene(example.string())), scene_to_json(default_scene()));
}

TEST(Scene, DocsDescribeEveryKey) {
  std::ifstream in(repo_root() / "docs" / "scenes.md");
  ASSERT_TRUE(in);
  std::stringstream text;
  text << in.rdbuf();
  for (const std::string& key : scene_keys())
    EXPECT_NE(text.str().find("`" + key + "`"), std::string::npos) << key;
}

// ---- Validation: each message names its key and range ------------------------------------

TEST(SceneValidation, PoissonRatioBounds) {
  Scene s = default_scene();
  s.material.poisson_ratio = 0.5;
  EXPECT_EQ(error_of([&] { validate_scene(s); }), "material.poisson_ratio = 0.5 must be in (-1, 0.5)");
  s.material.poisson_ratio = -1.0;
  EXPECT_EQ(error_of([&] { validate_scene(s); }), "material.poisson_ratio = -1 must be in (-1, 0.5)");
  // Just inside the bound passes; just outside prints all digits, not a rounded "0.5".
  s.material.poisson_ratio = std::nextafter(0.5, 0.0);
  EXPECT_NO_THROW(validate_scene(s));
  s.material.poisson_ratio = std::nextafter(0.5, 1.0);
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("0.5000000000000001 must be in (-1, 0.5)"),
            std::string::npos);
}

TEST(SceneValidation, ThicknessMustBePositive) {
  Scene s = default_scene();
  s.thickness = ConstantThickness{-0.1};
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("thickness = -0.1 must be"), std::string::npos);
  s.thickness = ConstantThickness{0.0};
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("thickness = 0 must be finite and > 0"),
            std::string::npos);
  s.thickness = LinearThickness{0.02, 0.0};
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("thickness.rim = 0 must be"), std::string::npos);
  s.thickness = LinearThickness{-1.0, 0.02};
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("thickness.center = -1 must be"), std::string::npos);
}

// A thin sheet: at most a quarter of its width thick (R for a disc, R - R_i for a ring),
// wherever the profile is thickest.
TEST(SceneValidation, ThicknessIsAtMostAQuarterOfTheWidth) {
  Scene s = default_scene();
  s.thickness = ConstantThickness{0.25};
  EXPECT_NO_THROW(validate_scene(s));
  s.thickness = ConstantThickness{2.0};
  EXPECT_EQ(error_of([&] { validate_scene(s); }),
            "thickness 2 must be at most 0.25 times the sheet's width 1 (R): the shell energy is "
            "that of a thin sheet");
  s.thickness = LinearThickness{0.02, 0.3};  // thickest at the rim
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("thickness 0.3 must be at most"),
            std::string::npos);
  s.thickness = ConstantThickness{0.2};
  s.geometry.shape = SceneShape::Ring;
  s.geometry.inner_radius = 0.5;
  EXPECT_EQ(error_of([&] { validate_scene(s); }),
            "thickness 0.2 must be at most 0.25 times the sheet's width 0.5 (R - R_i): the shell "
            "energy is that of a thin sheet");
  s.thickness = ConstantThickness{0.1};
  EXPECT_NO_THROW(validate_scene(s));
}

TEST(SceneValidation, InnerRadiusOfARing) {
  Scene s = default_scene();
  s.geometry.shape = SceneShape::Ring;
  s.geometry.inner_radius = 1.2;
  EXPECT_EQ(error_of([&] { validate_scene(s); }),
            "geometry.inner_radius = 1.2 must be in (0, geometry.radius = 1)");
  s.geometry.inner_radius = 1.0;
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("geometry.inner_radius = 1 must be in (0, "),
            std::string::npos);
  s.geometry.inner_radius = 0.0;
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("geometry.inner_radius = 0 must be in (0, "),
            std::string::npos);
  s.geometry.inner_radius = -0.5;
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("geometry.inner_radius = -0.5"), std::string::npos);
  // A disc ignores the inner radius.
  s.geometry.shape = SceneShape::Disc;
  EXPECT_NO_THROW(validate_scene(s));
}

TEST(SceneValidation, MeshAndContinuationRanges) {
  const auto message = [](auto change) {
    Scene s = default_scene();
    change(s);
    return error_of([&] { validate_scene(s); });
  };
  EXPECT_EQ(message([](Scene& s) { s.mesh.rings = 1; }), "mesh.rings = 1 must be >= 2");
  EXPECT_EQ(message([](Scene& s) { s.mesh.quadrature_degree = 7; }),
            "mesh.quadrature_degree = 7 must be in {1, ..., 6}");
  EXPECT_EQ(message([](Scene& s) { s.mesh.quadrature_degree = 0; }),
            "mesh.quadrature_degree = 0 must be in {1, ..., 6}");
  EXPECT_EQ(message([](Scene& s) { s.mesh.grading_exponent = 0.5; }),
            "mesh.grading_exponent = 0.5 must be finite and >= 1");
  EXPECT_EQ(message([](Scene& s) { s.mesh.min_spacing = -0.01; }),
            "mesh.min_spacing = -0.01 must be finite and >= 0");
  EXPECT_EQ(message([](Scene& s) { s.mesh.radial_layers = 0; }), "mesh.radial_layers = 0 must be >= 1");
  EXPECT_EQ(message([](Scene& s) { s.material.youngs_modulus = 0.0; }),
            "material.youngs_modulus = 0 must be finite and > 0");
  EXPECT_EQ(message([](Scene& s) { s.geometry.radius = -1.0; }),
            "geometry.radius = -1 must be finite and > 0");
  EXPECT_EQ(message([](Scene& s) { s.physics.contact_distance = 0.0; }),
            "physics.contact_distance = 0 must be finite and > 0");
  EXPECT_EQ(message([](Scene& s) { s.continuation.mode = 1; }), "continuation.mode = 1 must be >= 2");
  EXPECT_EQ(message([](Scene& s) { s.continuation.max_step = 0.0; }),
            "continuation.max_step = 0 must be finite and > 0");
  EXPECT_EQ(message([](Scene& s) { s.continuation.min_step = 0.2; }),
            "continuation.min_step = 0.2 must be in (0, continuation.max_step = 0.1]");
  EXPECT_EQ(message([](Scene& s) { s.continuation.phi_start = 4.0; }),
            "continuation.phi_start = 4 must be in [continuation.phi_min = 0, continuation.phi_max = 3.73]");
  EXPECT_EQ(message([](Scene& s) { s.continuation.phi_max = 0.0; }),
            "continuation.phi_min = 0 must be < continuation.phi_max = 0");
  EXPECT_EQ(message([](Scene& s) { s.continuation.perturbation_amplitude = -1e-3; }),
            "continuation.perturbation_amplitude = -0.001 must be finite and >= 0");
  EXPECT_EQ(message([](Scene& s) { s.output.snapshot_every = -1; }), "output.snapshot_every = -1 must be >= 0");
  EXPECT_EQ(message([](Scene& s) { s.output.directory.clear(); }), "output.directory must not be empty");
  EXPECT_EQ(message([](Scene& s) { s.growth.center.y() = NAN; }), "growth.center[1] = nan must be finite");
}

TEST(SceneValidation, StudyRanges) {
  const auto message = [](auto change) {
    Scene s = default_scene();
    change(s);
    return error_of([&] { validate_scene(s); });
  };
  EXPECT_EQ(message([](Scene& s) { s.study.tolerance = 0.0; }),
            "study.tolerance = 0 must be finite and > 0");
  EXPECT_EQ(message([](Scene& s) { s.study.max_tangent_angle = 3.2; }),
            "study.max_tangent_angle = 3.2 must be in (0, pi)");
  EXPECT_EQ(message([](Scene& s) { s.study.max_tangent_angle = 0.0; }),
            "study.max_tangent_angle = 0 must be in (0, pi)");
  EXPECT_EQ(message([](Scene& s) { s.study.eigenmodes = -1; }), "study.eigenmodes = -1 must be >= 0");
  EXPECT_EQ(message([](Scene& s) { s.study.symmetry_threshold = -1e-3; }),
            "study.symmetry_threshold = -0.001 must be finite and > 0");
  EXPECT_EQ(message([](Scene& s) { s.study.core_radius = -0.1; }),
            "study.core_radius = -0.1 must be finite and >= 0");
}

TEST_F(SceneFileTest, StudyKeysAreReadCheckedAndNamed) {
  const auto e = [&](const std::string& text) { return error_of([&] { read_scene(write("s.json", text)); }); };
  EXPECT_NE(e(R"({"study": {"kind": "cone"}})").find("study.kind = \"cone\" must be one of \"cone_branch\""),
            std::string::npos);
  EXPECT_NE(e(R"({"study": {"tolerance": -1}})").find("study.tolerance = -1 must be finite and > 0"),
            std::string::npos);
  EXPECT_NE(e(R"({"study": {"through_contact": 1}})").find("study.through_contact must be true or false"),
            std::string::npos);
  EXPECT_NE(e(R"({"study": {"tolerence": 1e-6}})").find("unknown key 'study.tolerence'"), std::string::npos);
  const Scene s = read_scene(write("ok.json", R"({"study": {"kind": "cone_branch", "eigenmodes": 0}})"));
  EXPECT_EQ(s.study.eigenmodes, 0);
  Scene o = default_scene();
  apply_override(o, "study.symmetric_subspace", "true");
  apply_override(o, "study.kind", "cone_branch");
  EXPECT_TRUE(o.study.symmetric_subspace);
}

// ---- Reading errors ----------------------------------------------------------------------

TEST_F(SceneFileTest, RangeErrorsInAFileNameTheFileAndKey) {
  const std::string path = write("nu.json", R"({"material": {"poisson_ratio": 0.5}})");
  const std::string e = error_of([&] { read_scene(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("material.poisson_ratio = 0.5 must be in (-1, 0.5)"), std::string::npos) << e;

  const std::string ring = write("ring.json", R"({"geometry": {"shape": "ring", "inner_radius": 1.2}})");
  EXPECT_NE(error_of([&] { read_scene(ring); }).find("geometry.inner_radius = 1.2 must be in (0, geometry.radius = 1)"),
            std::string::npos);
  const std::string rings = write("rings.json", R"({"mesh": {"rings": 1}})");
  EXPECT_NE(error_of([&] { read_scene(rings); }).find("mesh.rings = 1 must be >= 2"), std::string::npos);
}

TEST_F(SceneFileTest, UnknownKeysAreErrors) {
  const std::string e = error_of([&] { read_scene(write("u.json", R"({"mesh": {"ringz": 20}})")); });
  EXPECT_NE(e.find("unknown key 'mesh.ringz'"), std::string::npos) << e;
  EXPECT_NE(e.find("rings, radial_layers"), std::string::npos) << e;  // lists the allowed keys
  EXPECT_NE(error_of([&] { read_scene(write("t.json", R"({"meshes": {}})")); }).find("unknown key 'meshes'"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read_scene(write("l.json", R"({"thickness": {"profile": "linear", "center": 0.02, "rim": 0.01, "slope": 1}})"));
            }).find("unknown key 'thickness.slope'"),
            std::string::npos);
}

TEST_F(SceneFileTest, WrongTypesAreErrors) {
  const auto e = [&](const std::string& text) { return error_of([&] { read_scene(write("w.json", text)); }); };
  EXPECT_NE(e(R"({"mesh": {"rings": "24"}})").find("mesh.rings must be an integer"), std::string::npos);
  EXPECT_NE(e(R"({"mesh": {"rings": 24.5}})").find("mesh.rings must be an integer"), std::string::npos);
  EXPECT_NE(e(R"({"mesh": {"rings": 3000000000}})").find("mesh.rings = 3000000000 must fit"), std::string::npos);
  EXPECT_NE(e(R"({"mesh": 3})").find("mesh must be an object"), std::string::npos);
  EXPECT_NE(e(R"({"material": {"poisson_ratio": "0.3"}})").find("material.poisson_ratio must be a number"),
            std::string::npos);
  EXPECT_NE(e(R"({"physics": {"contact": 1}})").find("physics.contact must be true or false"), std::string::npos);
  EXPECT_NE(e(R"({"growth": {"center": [0]}})").find("growth.center must be an array of two numbers"),
            std::string::npos);
  EXPECT_NE(e(R"({"geometry": {"shape": "square"}})").find(R"(geometry.shape = "square" must be one of "disc", "ring")"),
            std::string::npos);
  EXPECT_NE(e(R"({"continuation": {"seed": -1}})").find("continuation.seed must be an integer in [0, 4294967295]"),
            std::string::npos);
  EXPECT_NE(e(R"({"thickness": "thin"})").find("thickness must be a number or an object"), std::string::npos);
  EXPECT_NE(e(R"({"thickness": {"profile": "linear", "center": 0.02}})").find("thickness.rim is required"),
            std::string::npos);
  EXPECT_NE(e(R"({"thickness": {"profile": "cubic"}})").find(R"(thickness.profile = "cubic" must be one of)"),
            std::string::npos);
  EXPECT_NE(e(R"([1, 2])").find("top level must be a JSON object"), std::string::npos);
}

TEST_F(SceneFileTest, MalformedJsonNamesFileAndPosition) {
  const std::string path = write("bad.json", "{\n  \"mesh\": {\"rings\": 20,}\n}\n");
  const std::string e = error_of([&] { read_scene(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("malformed JSON"), std::string::npos) << e;
  EXPECT_NE(e.find("line 2"), std::string::npos) << e;  // nlohmann's position of the error
}

TEST_F(SceneFileTest, MissingFileNamesThePath) {
  const std::string path = (dir_ / "no_such_scene.json").string();
  const std::string e = error_of([&] { read_scene(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("no such file"), std::string::npos) << e;
}

// ---- Overrides ---------------------------------------------------------------------------

TEST(SceneOverride, SetsTypedValuesFromText) {
  Scene s = default_scene();
  apply_override(s, "thickness", "0.005");
  apply_override(s, "geometry.shape", "ring");
  apply_override(s, "geometry.inner_radius", "0.4");
  apply_override(s, "continuation.phi_max", "7.5");
  apply_override(s, "continuation.mode", "3");
  apply_override(s, "continuation.direction", "backward");
  apply_override(s, "mesh.rings", "16");
  apply_override(s, "physics.contact", "true");
  apply_override(s, "growth.center", "[0.1, -0.2]");
  apply_override(s, "output.directory", "123");  // a string key keeps digits as text
  EXPECT_EQ(std::get<ConstantThickness>(s.thickness).value, 0.005);
  EXPECT_EQ(s.geometry.shape, SceneShape::Ring);
  EXPECT_EQ(s.geometry.inner_radius, 0.4);
  EXPECT_EQ(s.continuation.phi_max, 7.5);
  EXPECT_EQ(s.continuation.mode, 3);
  EXPECT_EQ(s.continuation.direction, ContinuationDirection::Backward);
  EXPECT_EQ(s.mesh.rings, 16);
  EXPECT_TRUE(s.physics.contact);
  EXPECT_EQ(s.growth.center, Eigen::Vector2d(0.1, -0.2));
  EXPECT_EQ(s.output.directory, "123");
  EXPECT_NO_THROW(validate_scene(s));

  apply_override(s, "thickness", R"({"profile": "linear", "center": 0.02, "rim": 0.01})");
  ASSERT_TRUE(std::holds_alternative<LinearThickness>(s.thickness));
  EXPECT_EQ(std::get<LinearThickness>(s.thickness).rim, 0.01);
}

TEST(SceneOverride, ErrorsNameTheKey) {
  Scene s = default_scene();
  EXPECT_NE(error_of([&] { apply_override(s, "mesh.ringz", "3"); }).find("unknown key 'mesh.ringz'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { apply_override(s, "mesh", "3"); }).find("'mesh' is a section"), std::string::npos);
  EXPECT_NE(error_of([&] { apply_override(s, "mesh.rings", "abc"); }).find("mesh.rings must be an integer"),
            std::string::npos);
  EXPECT_NE(error_of([&] { apply_override(s, "mesh.rings", "2.5"); }).find("mesh.rings must be an integer"),
            std::string::npos);
  EXPECT_NE(error_of([&] { apply_override(s, "continuation.direction", "sideways"); })
                .find("continuation.direction = \"sideways\" must be one of \"forward\", \"backward\""),
            std::string::npos);
  // Ranges are checked afterwards, by validate_scene.
  EXPECT_NO_THROW(apply_override(s, "material.poisson_ratio", "0.5"));
  EXPECT_NE(error_of([&] { validate_scene(s); }).find("material.poisson_ratio"), std::string::npos);
}

// ---- Builders ----------------------------------------------------------------------------

TEST(SceneBuilders, LinearThicknessProfileEndValues) {
  Scene s = default_scene();
  s.geometry.radius = 2.0;
  s.thickness = LinearThickness{0.03, 0.01};
  s.growth.center = {0.5, 0.0};  // the profile is about the sheet's centre, not the growth's
  const ThicknessField h = scene_model_settings(s).thickness;
  // h0 + (h1 - h0) r / R; tolerance: a few roundings of O(0.03) numbers.
  EXPECT_NEAR(h(Eigen::Vector3d(0.0, 0.0, 0.0)), 0.03, 1e-15);
  EXPECT_NEAR(h(Eigen::Vector3d(0.0, 2.0, 0.0)), 0.01, 1e-15);
  EXPECT_NEAR(h(Eigen::Vector3d(-0.6, 0.8, 0.0)), 0.02, 1e-15);  // r = 1 = R/2: the mean
  EXPECT_NEAR(h(Eigen::Vector3d(2.1, 0.0, 0.0)), 0.01, 1e-15);    // clamped beyond the rim
  EXPECT_NEAR(thickness_at_radius(s.thickness, 1.0, 2.0), 0.02, 1e-15);
  EXPECT_EQ(resolved_min_spacing(s), 0.0075);  // a quarter of the centre thickness (rings)
}

TEST(SceneBuilders, SmallDiscSceneBuildsAValidShellModel) {
  Scene s = default_scene();
  s.mesh.family = MeshFamily::Lattice;
  s.mesh.rings = 4;
  s.material.youngs_modulus = 2e4;
  s.growth.center = {0.0, 0.0};
  const TriangleMesh mesh = scene_mesh(s);
  // make_disc_mesh counts: 1 + 3 (N+1)(N+2) vertices including the ghost ring.
  EXPECT_EQ(mesh.vertices.rows(), 1 + 3 * 5 * 6);
  ShellModel model(mesh, scene_model_settings(s));
  EXPECT_EQ(model.num_elements(), 6 * 4 * 4);
  EXPECT_EQ(model.settings().material.youngs_modulus, 2e4);
  EXPECT_EQ(model.settings().quadrature_degree, 2);
  // The flat, ungrown reference is stress-free.
  const Eigen::VectorXd x = model.reference_positions();
  EXPECT_NEAR(model.energy_breakdown(x, 0.0).total(), 0.0, 1e-20);
  // Grown by phi_e but held flat, every point has abar = diag(1, lambda^2) and a = diag(1, 1)
  // in its (e_r, e_phi) frame, so eps = diag(0, (1 - lambda^2) / (2 lambda^2)) and U_s = eps^2
  // exactly, and E_s = Y h / (2 (1 - nu^2)) eps^2 (grown area) with grown area = lambda times
  // the current one. That checks that Y, nu, h and the growth centre reached the model; both
  // identities hold pointwise, so only rounding (relative 1e-12) separates the sides.
  const double phi = 0.5;
  const ShellEnergyBreakdown e = model.energy_breakdown(x, phi);
  const double lambda = circumferential_stretch(phi);
  const double eps = (1.0 - lambda * lambda) / (2.0 * lambda * lambda);
  const double expected = 2e4 * 0.02 / (2.0 * (1.0 - 0.09)) * eps * eps * e.grown_area;
  EXPECT_NEAR(e.stretching / expected, 1.0, 1e-12) << e.stretching;
  EXPECT_NEAR(e.grown_area / e.current_area, lambda, 1e-12);
  EXPECT_NEAR(e.bending, 0.0, 1e-20);
}

TEST(SceneBuilders, SmallRingSceneBuildsAValidShellModel) {
  Scene s = default_scene();
  s.geometry.shape = SceneShape::Ring;
  s.geometry.inner_radius = 0.5;
  s.mesh.family = MeshFamily::Lattice;
  s.mesh.radial_layers = 3;
  s.thickness = LinearThickness{0.02, 0.01};
  const TriangleMesh mesh = scene_mesh(s);
  const int m = annulus_vertices_per_ring({0.5, 1.0, 3, Eigen::Vector2d::Zero()});
  EXPECT_EQ(mesh.vertices.rows(), m * (3 + 3));
  // Inner rim vertices (ring 0) lie on r = R_i to rounding.
  for (int i = 0; i < m; ++i) EXPECT_NEAR(mesh.vertices.row(m + i).head<2>().norm(), 0.5, 1e-14);
  ShellModel model(mesh, scene_model_settings(s));
  EXPECT_EQ(model.num_elements(), 2 * m * 3);
  // The model's thickness at every quadrature point is the profile at that point's radius
  // (0.02 + (0.01 - 0.02) r, r in [0.5, 1]), so it spans (0.01, 0.015) strictly inside.
  const ReferenceQuadrature& q = model.reference();
  double h_min = 1.0, h_max = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    const double r = q.position(i).head<2>().norm();
    EXPECT_NEAR(q.thickness(i), 0.02 - 0.01 * std::min(r, 1.0), 1e-15) << i;
    h_min = std::min(h_min, q.thickness(i));
    h_max = std::max(h_max, q.thickness(i));
  }
  EXPECT_GT(h_min, 0.01);
  EXPECT_LT(h_max, 0.015);
}

TEST(SceneBuilders, InvalidSceneIsRejectedByTheBuilders) {
  Scene s = default_scene();
  s.mesh.quadrature_degree = 7;
  EXPECT_NE(error_of([&] { scene_model_settings(s); }).find("mesh.quadrature_degree"), std::string::npos);
  EXPECT_NE(error_of([&] { scene_mesh(s); }).find("mesh.quadrature_degree"), std::string::npos);
}

}  // namespace
}  // namespace growshell

namespace growshell {
namespace {

TEST(Scene, ThicknessSeriesReadsItsThicknessesAndRefusesBadLists) {
  const Scene s = parse_scene(
      R"({"study": {"kind": "thickness_series", "thicknesses": [0.04, 0.02, 0.01]}})", "test");
  EXPECT_EQ(s.study.kind, StudyKind::ThicknessSeries);
  ASSERT_EQ(s.study.thicknesses.size(), 3u);
  EXPECT_EQ(s.study.thicknesses[1], 0.02);
  EXPECT_EQ(s.study.phi_max_limit, 2.57);
  // It survives the round trip through scene_to_json.
  const Scene again = parse_scene(scene_to_json(s), "round trip");
  EXPECT_EQ(again.study.thicknesses, s.study.thicknesses);
  EXPECT_EQ(study_kind_name(again.study.kind), "thickness_series");

  using test_support::error_of;
  const auto parse = [](const std::string& text) { return [text] { parse_scene(text, "t"); }; };
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "thickness_series", "thicknesses": [0.04]}})"))
                .find("at least two"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "thickness_series", "thicknesses": [0.04, -0.02]}})"))
                .find("study.thicknesses[1]"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "thickness_series", "thicknesses": [0.04, 0.04]}})"))
                .find("listed twice"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "thickness_series", "thicknesses": [0.04, "x"]}})"))
                .find("array of numbers"),
            std::string::npos);
  // The cone_branch study takes its thickness from `thickness`; a list would be ignored.
  EXPECT_NE(error_of(parse(R"({"study": {"thicknesses": [0.04, 0.02]}})")).find("only by"),
            std::string::npos);
  Scene over = default_scene();
  apply_override(over, "study.kind", "thickness_series");
  apply_override(over, "study.thicknesses", "[0.03,0.015]");
  EXPECT_NO_THROW(validate_scene(over));
  EXPECT_EQ(over.study.thicknesses.back(), 0.015);
}

TEST(Scene, SeriesReadsItsKeysAndRefusesBadOnesByName) {
  const Scene s = parse_scene(
      R"({"geometry": {"shape": "ring"},
          "study": {"kind": "series", "series_key": "geometry.inner_radius",
                    "series_values": [0.1, 0.3], "series_of": "econe_contact",
                    "series_report": ["phi_kiss", "phi_crit_stability"]}})",
      "test");
  EXPECT_EQ(s.study.kind, StudyKind::Series);
  EXPECT_EQ(s.study.series_key, "geometry.inner_radius");
  EXPECT_EQ(s.study.series_values, (std::vector<double>{0.1, 0.3}));
  EXPECT_EQ(s.study.series_of, StudyKind::EconeContact);
  EXPECT_EQ(s.study.series_report, (std::vector<std::string>{"phi_kiss", "phi_crit_stability"}));
  const Scene again = parse_scene(scene_to_json(s), "round trip");
  EXPECT_EQ(again.study.series_key, s.study.series_key);
  EXPECT_EQ(again.study.series_values, s.study.series_values);
  EXPECT_EQ(again.study.series_of, s.study.series_of);
  EXPECT_EQ(again.study.series_report, s.study.series_report);
  EXPECT_EQ(study_kind_name(again.study.kind), "series");

  using test_support::error_of;
  const auto series = [](const std::string& study) {
    return [study] {
      parse_scene(R"({"study": {"kind": "series", "series_of": "cone_branch", )" + study + "}}", "t");
    };
  };
  const std::string good_values = R"("series_values": [0.02, 0.04], "series_report": ["phi_max"])";
  const auto has = [](const std::string& error, const std::string& part) {
    return error.find(part) != std::string::npos;
  };
  EXPECT_TRUE(has(error_of(series(good_values)), "study.series_key must name"));
  EXPECT_TRUE(has(error_of(series(R"("series_key": "output.directory", )" + good_values)),
                  "study.series_key = \"output.directory\""));
  EXPECT_TRUE(has(error_of(series(R"("series_key": "study.series_values", )" + good_values)),
                  "other than study.kind"));
  EXPECT_TRUE(has(error_of(series(R"("series_key": "no.such", )" + good_values)),
                  "study.series_key = \"no.such\""));
  EXPECT_TRUE(has(error_of(series(R"("series_key": "thickness", "series_values": [], "series_report": ["phi_max"])")),
                  "study.series_values must list"));
  EXPECT_TRUE(has(error_of(series(R"("series_key": "thickness", "series_values": [0.02, 0.02], "series_report": ["phi_max"])")),
                  "study.series_values[1] = 0.02 is listed twice"));
  EXPECT_TRUE(has(error_of(series(R"("series_key": "thickness", "series_values": [0.02], "series_report": [])")),
                  "study.series_report must list"));
  EXPECT_TRUE(has(error_of(series(R"("series_key": "thickness", "series_values": [0.02], "series_report": ["a", "a"])")),
                  "study.series_report[1] = \"a\" is listed twice"));
  EXPECT_TRUE(has(error_of([] {
                    parse_scene(R"({"study": {"kind": "series", "series_key": "thickness",
                                    "series_values": [0.02], "series_report": ["phi_max"],
                                    "series_of": "thickness_series"}})", "t");
                  }),
                  "study.series_of = \"thickness_series\" must be"));
  // Another study would ignore them: refused.
  EXPECT_TRUE(has(error_of([] { parse_scene(R"({"study": {"series_key": "thickness"}})", "t"); }),
                  "read only by study.kind = \"series\""));
}

TEST(Scene, WindToIsTheEconeStudysAbovePhiMaxWithItsShapesBetween) {
  const Scene s = parse_scene(
      R"({"continuation": {"phi_max": 7.3},
          "study": {"kind": "econe_contact", "wind_to": 12.566, "wind_shapes_at": [9.0, 11.0]}})",
      "test");
  ASSERT_TRUE(s.study.wind_to.has_value());
  EXPECT_EQ(*s.study.wind_to, 12.566);
  EXPECT_EQ(s.study.wind_shapes_at, (std::vector<double>{9.0, 11.0}));
  const Scene back = parse_scene(scene_to_json(s), "round trip");
  EXPECT_EQ(back.study.wind_to, s.study.wind_to);
  EXPECT_EQ(back.study.wind_shapes_at, s.study.wind_shapes_at);
  // Off by default, and null turns it off.
  EXPECT_FALSE(default_scene().study.wind_to.has_value());
  EXPECT_FALSE(parse_scene(R"({"study": {"kind": "econe_contact", "wind_to": null}})", "t")
                   .study.wind_to.has_value());
  EXPECT_TRUE(mentions(refusal(R"({"continuation": {"phi_max": 7.3},
                                     "study": {"kind": "econe_contact", "wind_to": 7.0}})"),
                  "study.wind_to = 7 must be finite and above continuation.phi_max = 7.3"));
  EXPECT_TRUE(mentions(refusal(R"({"study": {"kind": "econe_contact", "wind_to": "auto"}})"),
                  "study.wind_to must be a number or null"));
  EXPECT_TRUE(mentions(refusal(R"({"continuation": {"phi_max": 7.3},
                                     "study": {"kind": "econe_contact", "wind_to": 9,
                                               "wind_shapes_at": [8, 9.5]}})"),
                  "study.wind_shapes_at[1] = 9.5 must lie in"));
  EXPECT_TRUE(mentions(refusal(R"({"continuation": {"phi_max": 7.3},
                                     "study": {"kind": "econe_contact", "wind_to": 9,
                                               "wind_shapes_at": [8, 8]}})"),
                  "study.wind_shapes_at[1] = 8 is listed twice"));
  EXPECT_TRUE(mentions(refusal(R"({"study": {"kind": "econe_contact", "wind_shapes_at": [8]}})"),
                  "study.wind_to is null"));
  EXPECT_TRUE(mentions(refusal(R"({"study": {"wind_to": 9}})"),
                  "read only by the econe_contact study"));
}

TEST(Scene, CompareModesAreTheEconeStudysModesAboveTwo) {
  const Scene s =
      parse_scene(R"({"study": {"kind": "econe_contact", "compare_modes": [3, 4]}})", "test");
  EXPECT_EQ(s.study.compare_modes, (std::vector<int>{3, 4}));
  EXPECT_EQ(parse_scene(scene_to_json(s), "round trip").study.compare_modes,
            s.study.compare_modes);
  EXPECT_TRUE(default_scene().study.compare_modes.empty());
  EXPECT_TRUE(mentions(refusal(R"({"study": {"kind": "econe_contact", "compare_modes": [2]}})"),
                  "study.compare_modes[0] = 2 must be at least 3"));
  EXPECT_TRUE(mentions(refusal(R"({"study": {"kind": "econe_contact", "compare_modes": [3, 3]}})"),
                  "study.compare_modes[1] = 3 is listed twice"));
  EXPECT_TRUE(mentions(refusal(R"({"study": {"kind": "econe_contact", "compare_modes": [3.5]}})"),
                  "study.compare_modes[0] must be an integer"));
  EXPECT_TRUE(mentions(refusal(R"({"study": {"compare_modes": [3]}})"),
                  "read only by the econe_contact study"));
}

TEST(Scene, HardContactAtIsTheEconeStudysAndBadListsAreRefusedByName) {
  const Scene s = parse_scene(
      R"({"study": {"kind": "econe_contact", "hard_contact_at": [6.8, 7.0]}})", "test");
  EXPECT_EQ(s.study.hard_contact_at, (std::vector<double>{6.8, 7.0}));
  EXPECT_EQ(parse_scene(scene_to_json(s), "round trip").study.hard_contact_at,
            s.study.hard_contact_at);
  // A series of econe_contact studies passes it on.
  EXPECT_NO_THROW(parse_scene(
      R"({"study": {"kind": "series", "series_key": "thickness", "series_values": [0.04],
                    "series_of": "econe_contact", "series_report": ["phi_kiss"],
                    "hard_contact_at": [7.0]}})", "test"));
  using test_support::error_of;
  const auto parse = [](const std::string& text) { return [text] { parse_scene(text, "t"); }; };
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "econe_contact", "hard_contact_at": [7.0, -1]}})"))
                .find("study.hard_contact_at[1]"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "econe_contact", "hard_contact_at": [7.0, 7.0]}})"))
                .find("listed twice"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"hard_contact_at": [7.0]}})"))
                .find("read only by the econe_contact study"),
            std::string::npos);
}

TEST(Scene, HardContactBranchesNameTracedBranchesOnceEach) {
  EXPECT_EQ(default_scene().study.hard_contact_branches,
            (std::vector<std::string>{"turned", "symmetric"}));
  const Scene s = parse_scene(
      R"({"study": {"kind": "econe_contact", "hard_contact_at": [7.1],
                    "hard_contact_branches": ["skewed", "turned"]}})",
      "test");
  EXPECT_EQ(s.study.hard_contact_branches, (std::vector<std::string>{"skewed", "turned"}));
  EXPECT_EQ(parse_scene(scene_to_json(s), "round trip").study.hard_contact_branches,
            s.study.hard_contact_branches);
  using test_support::error_of;
  const auto parse = [](const std::string& text) { return [text] { parse_scene(text, "t"); }; };
  EXPECT_NE(
      error_of(parse(R"({"study": {"kind": "econe_contact",
                                         "hard_contact_branches": ["turned", "wound"]}})"))
          .find(
              R"(study.hard_contact_branches[1] = "wound" must be "turned", "symmetric" or "skewed")"),
      std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "econe_contact",
                                         "hard_contact_branches": ["skewed", "skewed"]}})"))
                .find(R"(study.hard_contact_branches[1] = "skewed" is listed twice)"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "econe_contact", "hard_contact_branches": []}})"))
                .find("study.hard_contact_branches must list at least one"),
            std::string::npos);
}

TEST(Scene, ContactStepControlKeysHaveTheirDefaultsAndBadCountsAreRefused) {
  EXPECT_EQ(default_scene().study.contact_max_corrector_iterations, 8);
  EXPECT_EQ(default_scene().study.contact_stall_iterations, 0);
  EXPECT_EQ(default_scene().study.contact_growth_pause, 0);
  const Scene s = parse_scene(
      R"({"study": {"kind": "econe_contact", "contact_stall_iterations": 8,
                    "contact_growth_pause": 3, "contact_max_corrector_iterations": 12}})",
      "test");
  EXPECT_EQ(s.study.contact_max_corrector_iterations, 12);
  EXPECT_EQ(s.study.contact_stall_iterations, 8);
  EXPECT_EQ(s.study.contact_growth_pause, 3);
  const Scene back = parse_scene(scene_to_json(s), "round trip");
  EXPECT_EQ(back.study.contact_stall_iterations, 8);
  EXPECT_EQ(back.study.contact_growth_pause, 3);
  EXPECT_EQ(back.study.contact_max_corrector_iterations, 12);
  using test_support::error_of;
  const auto parse = [](const std::string& text) { return [text] { parse_scene(text, "t"); }; };
  EXPECT_NE(
      error_of(parse(R"({"study": {"kind": "econe_contact", "contact_stall_iterations": -1}})"))
          .find("study.contact_stall_iterations"),
      std::string::npos);
  EXPECT_NE(
      error_of(
          parse(R"({"study": {"kind": "econe_contact", "contact_max_corrector_iterations": 0}})"))
          .find("study.contact_max_corrector_iterations"),
      std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "econe_contact", "contact_growth_pause": -2}})"))
                .find("study.contact_growth_pause"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"kind": "econe_contact", "contact_growth_pause": 1.5}})"))
                .find("study.contact_growth_pause"),
            std::string::npos);
}

TEST(Scene, ContactProxySegmentsIsReadRoundTripsAndOutOfRangeCountsAreRefused) {
  EXPECT_EQ(default_scene().study.contact_proxy_segments, 1);
  const Scene s =
      parse_scene(R"({"study": {"kind": "econe_contact", "contact_proxy_segments": 3}})", "test");
  EXPECT_EQ(s.study.contact_proxy_segments, 3);
  EXPECT_EQ(parse_scene(scene_to_json(s), "round trip").study.contact_proxy_segments, 3);
  using test_support::error_of;
  for (const char* bad : {"0", "-1", "9", "1.5", "\"two\""}) {
    std::string text = R"({"study": {"kind": "econe_contact", "contact_proxy_segments": )";
    text += bad;
    text += "}}";
    EXPECT_NE(error_of([&] { parse_scene(text, "t"); }).find("study.contact_proxy_segments"),
              std::string::npos)
        << bad;
  }
}

TEST(Scene, ContactVertexTrianglesIsReadRoundTripsAndABadNameIsRefused) {
  EXPECT_EQ(default_scene().study.contact_vertex_triangles,
            SceneContactVertexTriangles::NearestAtBuild);
  const Scene s = parse_scene(
      R"({"study": {"kind": "econe_contact", "contact_vertex_triangles": "every_near_triangle"}})",
      "test");
  EXPECT_EQ(s.study.contact_vertex_triangles, SceneContactVertexTriangles::EveryNearTriangle);
  EXPECT_EQ(parse_scene(scene_to_json(s), "round trip").study.contact_vertex_triangles,
            SceneContactVertexTriangles::EveryNearTriangle);
  using test_support::error_of;
  const std::string error = error_of([] {
    parse_scene(R"({"study": {"kind": "econe_contact", "contact_vertex_triangles": "nearest"}})",
                "t");
  });
  EXPECT_NE(error.find("study.contact_vertex_triangles"), std::string::npos) << error;
  EXPECT_NE(error.find("every_near_triangle"), std::string::npos) << error;
}

TEST(Scene, ContactSurfaceIsReadRoundTripsAndABadNameIsRefused) {
  EXPECT_EQ(default_scene().study.contact_surface, SceneContactSurface::ProxyTriangles);
  const Scene s = parse_scene(
      R"({"study": {"kind": "econe_contact", "contact_surface": "limit_surface"}})", "test");
  EXPECT_EQ(s.study.contact_surface, SceneContactSurface::LimitSurface);
  EXPECT_EQ(parse_scene(scene_to_json(s), "round trip").study.contact_surface,
            SceneContactSurface::LimitSurface);
  using test_support::error_of;
  const std::string error = error_of([] {
    parse_scene(R"({"study": {"kind": "econe_contact", "contact_surface": "smooth"}})", "t");
  });
  EXPECT_NE(error.find("study.contact_surface"), std::string::npos) << error;
  EXPECT_NE(error.find("limit_surface"), std::string::npos) << error;
}

TEST(Scene, OrientationCheckTurnsAreReadAndBadListsRefusedByName) {
  EXPECT_EQ(default_scene().study.orientation_check_turns, std::vector<double>{22.5});
  const Scene s = parse_scene(
      R"({"study": {"kind": "econe_contact", "orientation_check_turns": [11.25, -22.5]}})", "test");
  EXPECT_EQ(s.study.orientation_check_turns, (std::vector<double>{11.25, -22.5}));
  EXPECT_EQ(parse_scene(scene_to_json(s), "round trip").study.orientation_check_turns,
            s.study.orientation_check_turns);
  EXPECT_TRUE(parse_scene(R"({"study": {"orientation_check_turns": []}})", "t")
                  .study.orientation_check_turns.empty());  // no check

  using test_support::error_of;
  const auto parse = [](const std::string& text) { return [text] { parse_scene(text, "t"); }; };
  for (const char* bad : {"[0]", "[90]", "[-95]", "[22.5, -90]"})
    EXPECT_NE(error_of(parse(std::string(R"({"study": {"orientation_check_turns": )") + bad + "}}"))
                  .find("study.orientation_check_turns"),
              std::string::npos)
        << bad;
  EXPECT_NE(error_of(parse(R"({"study": {"orientation_check_turns": [10, 10]}})")).find("listed twice"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"study": {"orientation_check_turns": 22.5}})")).find("array of numbers"),
            std::string::npos);
}

}  // namespace
}  // namespace growshell
