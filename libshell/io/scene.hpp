#pragma once
/// \file
/// The scene: everything a branch-tracing program models (geometry, thickness, material,
/// growth, mesh, physics switches, continuation and output settings, the study), read from a
/// JSON file and overridable key by key from the command line. docs/scenes.md documents every
/// key.
///
/// Units: lengths in metres, Young's modulus in pascals, angles in radians. The defaults are
/// the paper's disc (R = 1, h = 0.02, Y = 1e4 Pa, nu = 0.3), so lengths read as units of R.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/energy/material.hpp"
#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell {

/// Which sheet is modelled.
enum class SceneShape {
  Disc,  ///< a disc of radius geometry.radius centred at the origin
  Ring,  ///< an annulus geometry.inner_radius < r < geometry.radius centred at the origin
};

/// Shape and size of the flat, ungrown sheet in the plane z = 0.
struct SceneGeometry {
  SceneShape shape = SceneShape::Disc;
  /// Outer radius R (m), > 0.
  double radius = 1.0;
  /// Inner radius R_i (m) of a ring, in (0, radius); ignored for a disc.
  double inner_radius = 0.25;
};

/// Thickness h (m) equal everywhere; must be > 0.
struct ConstantThickness {
  double value = 0.02;
};

/// Thickness varying linearly with the distance r from the sheet's centre (the origin):
///   h(r) = center + (rim - center) r / R,  r clamped to [0, R],
/// so h is `center` at r = 0 and `rim` at r = R (both m, both > 0, hence h > 0 everywhere).
struct LinearThickness {
  double center = 0.02;
  double rim = 0.02;
};

/// Thickness profile of the sheet. A new profile is a new alternative here plus its cases in
/// thickness_at_radius, validate_scene and the JSON reader/writer (scene.cpp); std::visit
/// makes the compiler point at every place that needs one.
using ThicknessProfile = std::variant<ConstantThickness, LinearThickness>;

/// The growth law.
enum class GrowthLaw {
  /// Growth along circles about `center`: G = diag(1, 1 + phi_e / (2 pi)) (radial,
  /// tangential); see circumferential_growth.hpp.
  Circumferential,
};

/// Growth settings.
struct SceneGrowth {
  GrowthLaw law = GrowthLaw::Circumferential;
  /// Centre (m) of the growth law in the plane z = 0; finite.
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  /// Radius epsilon (m) over which the excess angle rises from 0 at the centre to phi_e
  /// (CircumferentialGrowth::smoothing_radius); 0 = growth singular at the centre; >= 0.
  double smoothing_radius = 0.0;
  /// How the excess angle rises within smoothing_radius (CircumferentialGrowth).
  GrowthSmoothingProfile smoothing_profile = GrowthSmoothingProfile::Rational;
};

/// Which family of control meshes a scene is discretised with.
enum class MeshFamily {
  /// Structured meshes with every interior vertex regular: the hexagonal lattice mapped
  /// conformally onto a disc (rings, grading_exponent, min_spacing), or the log-polar grid of a
  /// ring (radial_layers). The disc has six-fold symmetry, not the two-fold cone's.
  Lattice,
  /// Concentric rings graded towards the centre with the symmetry of the two-fold cone (both
  /// mirrors and the quarter turn), make_ring_disc_mesh: element size
  /// clamp(size_slope r, min_spacing, size_max). Disc or ring. The default.
  Rings,
  /// An unstructured mesh from Gmsh with the same size field (make_gmsh_disc_mesh): shares no
  /// structure with the other families. Disc or ring.
  Gmsh,
  /// Gmsh's unstructured mesh of the sector 0 <= theta <= pi/4, reflected into the whole disc
  /// or ring (make_gmsh_disc_mesh with dihedral_symmetry): the rings family's symmetry group
  /// (both mirrors of the two-fold cone and the quarter turn) without its structure, so that
  /// the mirror subspace and the S4 check apply on a second family.
  GmshD4,
  /// The mesh in `file`: a Gmsh .msh sheet (a ghost layer is added) or an OBJ control mesh
  /// whose outermost layer is already the ghost layer.
  File,
};

/// The family's name in scene files: "lattice", "rings", "gmsh", "gmsh_d4" or "file".
std::string mesh_family_name(MeshFamily family);

/// Whether the family grades its element size as clamp(size_slope r, min_spacing, size_max)
/// (rings, gmsh, gmsh_d4), so that it reads mesh.size_slope and mesh.size_max.
bool graded_by_size(MeshFamily family);

/// Control mesh and quadrature.
struct SceneMesh {
  /// The mesh family; the keys below say which family they belong to.
  MeshFamily family = MeshFamily::Rings;
  /// Number of real rings of the disc mesh (disc only), >= 2.
  int rings = 24;
  /// Number of element layers between the inner and outer rim (ring only), >= 1.
  int radial_layers = 16;
  /// Radial grading exponent p of the disc mesh (disc only), >= 1; 1 is uniform, 3 refines
  /// smoothly towards the centre (see make_disc_mesh).
  double grading_exponent = 3.0;
  /// Smallest spacing (m) of the graded disc mesh at the centre, >= 0. Unset ("auto" in the
  /// file) means a quarter of the thickness at the centre for the rings and gmsh families (the
  /// floor at which the apex core is resolved, docs/results.md) and half of it for the
  /// lattice, resolved by resolved_min_spacing, so that it follows a thickness override.
  std::optional<double> min_spacing;
  /// Element size per unit distance from the centre (rings and gmsh families), > 0: the size
  /// is clamp(size_slope r, min_spacing, size_max). The default 0.1 (64 vertices per ring of
  /// the rings family) puts the mesh error of phi_e^max, of the first branch point and of the
  /// mid-surface contact below 1e-3 (docs/results.md).
  double size_slope = 0.1;
  /// Largest element size (m) of the rings and gmsh families, > 0; unset means no cap.
  std::optional<double> size_max;
  /// Mesh file of the file family (.msh or .obj); relative paths are relative to the working
  /// directory.
  std::string file;
  /// Polynomial exactness of the triangle quadrature rule, in {1, ..., 6}.
  int quadrature_degree = 2;
};

/// Which physics is switched on.
struct ScenePhysics {
  /// Self-contact (gap constraints between mid-surfaces); off by default.
  bool contact = false;
  /// Mid-surface distance (m) at which two parts of the sheet touch, > 0. Unset ("auto")
  /// means the thickness: h for a constant profile, (h_a + h_b) / 2 of the two touching
  /// points for a varying one (resolved by the contact layer).
  std::optional<double> contact_distance;
  /// Pairs of points closer than this (m) to each other in the reference (geodesic distance on
  /// the reference sheet) are neighbours, never contact, >= the contact distance. Unset
  /// ("auto") means 8 h with h the thickness at the centre (kApexExclusionThicknesses,
  /// resolved by resolved_exclusion_radius): the apex model of docs/contact.md.
  std::optional<double> contact_exclusion_radius;
};

/// Direction in which a branch is followed from continuation.phi_start.
enum class ContinuationDirection {
  Forward,   ///< increasing phi_e, up to phi_max
  Backward,  ///< decreasing phi_e, down to phi_min
};

/// What a contact pair measures the distance to (docs/contact.md, "The contact surface").
enum class SceneContactSurface {
  ProxyTriangles,  ///< the flat triangles of the contact proxy (its sampled limit surface)
  LimitSurface,    ///< the limit surface itself, around the pair's triangle
};

/// Which vertex-triangle pairs the contact penalty of a trace holds (docs/contact.md).
enum class SceneContactVertexTriangles {
  NearestAtBuild,     ///< per vertex the triangle nearest where the segment's set was built
  EveryNearTriangle,  ///< every triangle near the vertex, each a pair of the penalty
};

/// The corrector of pseudo-arclength continuation (ArclengthOptions::Corrector).
enum class SceneCorrector {
  Newton,  ///< a Hessian factorisation per corrector iteration
  Chord,   ///< iterations reuse the last factorisation; Newton where they stop contracting
};

/// Continuation in the excess angle phi_e (radians) and the initial perturbation.
struct SceneContinuation {
  /// First excess angle of the path, in [phi_min, phi_max].
  double phi_start = 0.0;
  /// Lower end of the traced interval (where a backward path stops), < phi_max.
  double phi_min = 0.0;
  /// Upper end of the traced interval (where a forward path stops).
  double phi_max = 3.73;
  /// Largest continuation step (rad), > 0.
  double max_step = 0.1;
  /// Smallest continuation step (rad) before giving up, in (0, max_step].
  double min_step = 1e-4;
  ContinuationDirection direction = ContinuationDirection::Forward;
  /// The corrector of the branches traced by pseudo-arclength continuation.
  SceneCorrector corrector = SceneCorrector::Newton;
  /// Fold number n of the branch to follow (2 = the saddle e-cone), >= 2.
  int mode = 2;
  /// Amplitude of the initial out-of-plane perturbation relative to R (dimensionless), >= 0.
  double perturbation_amplitude = 1e-3;
  /// Seed of the perturbation's random generator.
  std::uint32_t seed = 1;
};

/// Where and what the programs write.
struct SceneOutput {
  /// Output directory (relative paths are relative to the working directory); non-empty.
  std::string directory = "out";
  /// Write a shape snapshot every this many accepted continuation steps, >= 0; 0 = only at
  /// the special points and events and at the end (a snapshot at 5.7k unknowns is 1.3 MB).
  int snapshot_every = 0;
  /// Whether snapshots are also written as VTK files.
  bool write_vtk = true;
};

/// Which study `growshell run` performs on a scene.
enum class StudyKind {
  /// The n-fold cone born at the flat sheet's branch point, traced with its special points and
  /// events (studies/cone_branch_study.hpp, docs/guide/cone_branch.md).
  ConeBranch,
  /// The cone_branch study at each of several thicknesses, with phi_e at the first branch
  /// point and phi_e^max fitted as power laws of h (studies/thickness_series_study.hpp,
  /// docs/guide/thickness_series.md).
  ThicknessSeries,
  /// The two-fold cone through self-contact (the paper's Fig. 4): the cone_branch study up to
  /// first contact, then the symmetric branch with the contact penalty, the skewed branch and
  /// phi_e^crit both ways (studies/econe_contact_study.hpp, docs/guide/econe_contact.md).
  EconeContact,
  /// One study (study.series_of) at each value of one scene key (study.series_key,
  /// study.series_values), with chosen key values of its results against it
  /// (studies/series_study.hpp, docs/guide/series.md): e.g. the rings' phi_e^kiss against
  /// their inner radius (the paper's Table 1).
  Series,
};

/// The study's name in scene files: "cone_branch", "thickness_series", "econe_contact" or
/// "series".
std::string study_kind_name(StudyKind kind);

/// The study a scene asks for and those of its settings that change its results (the
/// cone_branch study's; the programs that trace a cone, e.g. trace_disc, read them too).
struct SceneStudy {
  StudyKind kind = StudyKind::ConeBranch;
  /// Trace on past the first contact (gap = contact distance) instead of stopping there.
  bool through_contact = false;
  /// Corrector force tolerance relative to the natural force scale Y h^3 / R, > 0.
  double tolerance = 1e-6;
  /// Largest angle (rad) between successive tangents of an accepted step, in (0, pi).
  double max_tangent_angle = 0.3;
  /// Number of lowest eigenmodes computed (and written) at each special point, >= 0.
  int eigenmodes = 2;
  /// Trace the cone among the states with the mirrors of its folds (docs/continuation.md,
  /// "Symmetric subspace"); the stability index stays the full Hessian's. On by default: the
  /// symmetric branch is then the one with the mirrors, whatever drift the neutral pattern
  /// turn would take in the full space; a mesh without the mirrors (gmsh) is traced in the
  /// full space, with a note.
  bool symmetric_subspace = true;
  /// econe_contact: trace the skewed and the turned cone among the states with the half turn
  /// about the growth axis, which they keep while breaking both mirrors (docs/continuation.md,
  /// "Symmetric subspace"); half the unknowns, and the stability index stays the full
  /// Hessian's. A mesh without the half turn, or a start without it, is traced in the full
  /// space, with a note. Off by default: with the pair sets closed under the half turn the Fig. 4
  /// scene at h = 0.04 gives every key of the full space to 1e-5 with its traces 1.8 times
  /// faster, but on the ctest's coarse scene the turned cone's upward trace ends at a segment
  /// start (7.151) that the full space passes (docs/performance.md, session 38).
  bool half_turn_subspace = false;
  /// Count the stability index without the pattern's turn about the growth axis: the neutral
  /// mode of the axisymmetric sheet that a discrete mesh leaves only nearly neutral, of either
  /// sign (docs/guide/cone_branch.md, "Stability index").
  bool index_excludes_pattern_turn = true;
  /// Where the cone is traced in the full space (a mesh without its mirrors, or
  /// symmetric_subspace off), hold the orientation of its fold pattern about the axis with a
  /// phase condition (docs/continuation.md, "Phase condition"), so that the mesh's weak hold
  /// on the pattern's turn does not steer the branch; branch.csv's phase_force is then the
  /// force that holds it. Off by default: on the gmsh family at the default resolution that
  /// force is about 1e3 times the corrector's tolerance and moves phi_e^max by 0.07
  /// (docs/results.md), so the default trace stays the discrete problem's own equilibria.
  bool phase_condition = false;
  /// S4 defect (dimensionless) above which the event symmetry_lost is reported, > 0.
  double symmetry_threshold = 1e-3;
  /// Radius (m) about the growth centre within which the sheet is left out of the gap and the
  /// mid-surface contact test, >= 0.
  double core_radius = 0.0;
  /// thickness_series only: the thicknesses h (m) of its traces, in the order they run; each
  /// > 0, no two equal, at least two. Each trace is the cone_branch study of this scene with
  /// `thickness` set to h. Must be empty for the other studies.
  std::vector<double> thicknesses;
  /// thickness_series only: the h -> 0 value of phi_e^max (rad) that the fit
  /// phi_e^max - L = A h^p approaches: 2.57, the h -> 0 cone's (../shared/docs/physics.md).
  double phi_max_limit = 2.57;
  /// series only: the scene key that varies (a key of docs/scenes.md other than study.kind,
  /// study.series_* and output.*), e.g. "geometry.inner_radius".
  std::string series_key;
  /// series only: its values, in the order they run; at least one, finite, no two equal.
  std::vector<double> series_values;
  /// series only: the study run at each value: cone_branch or econe_contact.
  StudyKind series_of = StudyKind::ConeBranch;
  /// series only: the keys of each point's results.json (numbers or null) tabulated and
  /// plotted against the varying key; at least one, no two equal.
  std::vector<std::string> series_report;
  /// econe_contact only: the symmetric state pushed along its lowest modes and relaxed to find
  /// the skewed cone is the symmetric branch's first sample at or beyond this phi_e (rad, > 0);
  /// unset ("auto"): its last sample (continuation.phi_max).
  std::optional<double> skew_search_at;
  /// econe_contact only: the largest arclength step of the branches with contact (> 0).
  double contact_max_step = 0.02;
  /// econe_contact only: a corrector of a branch with contact that has not converged in this
  /// many iterations fails, and its step is halved (ArclengthOptions::max_corrector_iterations;
  /// >= 1). Next to the skewed and turned cones' folds a corrector that needs more converges
  /// onto another branch, a snap that the trace would then follow (docs/continuation.md).
  int contact_max_corrector_iterations = 8;
  /// econe_contact only: the branches with contact give a Newton corrector up after this many
  /// iterations if its residual has not fallen to a tenth (ArclengthOptions::stall_iterations;
  /// >= 0, 0 = off: max_corrector_iterations only).
  int contact_stall_iterations = 0;
  /// econe_contact only: after a failed step of a branch with contact, this many accepted
  /// steps keep their length (ArclengthOptions::growth_pause_after_failure; >= 0, 0 = off).
  int contact_growth_pause = 0;
  /// econe_contact only: which vertex-triangle pairs the traces' penalty holds.
  SceneContactVertexTriangles contact_vertex_triangles =
      SceneContactVertexTriangles::NearestAtBuild;
  /// econe_contact only: the penalty stiffness k = F Y l^2 / h, l the contact proxy's spacing
  /// (docs/contact.md, "Penalty stiffness"); this is F (> 0).
  double penalty_stiffness_factor = 10.0;
  /// econe_contact, and cone_branch's orientation check: segments per element edge of the
  /// contact proxy, the sampled limit surface whose vertex-triangle pairs the penalty holds
  /// (make_contact_proxy; in [1, 8]). n segments give n^2 proxy triangles per element and a
  /// spacing l / n, and the stiffness k = F Y (l / n)^2 / h follows it.
  int contact_proxy_segments = 1;
  /// econe_contact, and cone_branch's orientation check: whether the penalty's pairs measure
  /// the distance from a proxy vertex to the flat proxy triangle or to the limit surface around
  /// it (ContactGapOptions::limit_surface). The Ipopt checks keep the proxy triangles.
  SceneContactSurface contact_surface = SceneContactSurface::ProxyTriangles;
  /// econe_contact only: solve the relaxed skewed state again with Ipopt under the hard
  /// constraints gap >= contact distance, and report the difference in results.json. Off by
  /// default: it took over 20 minutes at 5.7k unknowns, and at phi_e^crit by energy both
  /// cones are free of contact, where penalty and hard constraints coincide.
  bool ipopt_check = false;
  /// econe_contact only: at each of these excess angles (rad, > 0, no two equal), the saved
  /// state nearest it of each branch traced with contact (the turned cone, the held symmetric
  /// one) is solved again under Ipopt's hard constraints gap >= contact distance and compared
  /// with the penalty's (studies/hard_contact_check.hpp): the contact solver of record at the
  /// reported points, and gamma from its contact forces. Empty by default.
  std::vector<double> hard_contact_at;
  /// econe_contact only: the branches whose states study.hard_contact_at solves again, in this
  /// order: each of "turned", "symmetric" and "skewed", at least one, no two equal. The
  /// default, {"turned", "symmetric"}, is the pair the energy comparisons use; "skewed" gives
  /// the skewed cone's gamma(phi_e) from the hard constraints (the paper's Fig. 5). A branch the
  /// study did not trace is skipped.
  std::vector<std::string> hard_contact_branches = {"turned", "symmetric"};
  /// econe_contact only: beyond the branches, the sheet is grown on from the highest stable
  /// state that breaks S4 (of the skewed or the turned cone) up to this excess angle (rad, finite, above
  /// continuation.phi_max) by minimisation at every step, so that it drops onto whatever stable
  /// state follows where a branch ends: the wound-up cones (physics.md, item 5). Unset (null,
  /// the default): no winding.
  std::optional<double> wind_to;
  /// econe_contact only: excess angles (rad, in (continuation.phi_max, wind_to], no two equal)
  /// at which the winding stops once and writes the shape (shell and contact proxy, VTU); the
  /// shape at wind_to is always written.
  std::vector<double> wind_shapes_at;
  /// econe_contact only: the n-fold cones (each n >= 3, no two equal) traced from the flat
  /// sheet without contact up to their first contact or continuation.phi_max, beside the
  /// two-fold one, and compared with it (physics.md, item 6: the n = 3 cone lies above). Empty
  /// by default.
  std::vector<int> compare_modes;
  /// econe_contact (at its contact start) and the cone_branch study's check at
  /// orientation_check_at: turns of the fold pattern over the material (degrees, each finite and
  /// in (-90, 90), none 0, no two equal) by which the cone's last contact-free state is turned,
  /// relaxed and compared with the traced one (studies/pattern_orientation_check.hpp;
  /// results.json's orientation_check). Empty: no check. The default 22.5 degrees places the
  /// folds half-way between mirror lines of the gmsh_d4 mesh and on the other mirror family of
  /// the rings mesh.
  std::vector<double> orientation_check_turns = {22.5};
  /// cone_branch and thickness_series: after the trace, the saved state nearest this phi_e
  /// (rad, > 0) is turned by orientation_check_turns, relaxed and compared with the traced one
  /// (results.json's orientation_* keys); unset ("auto"): no check.
  std::optional<double> orientation_check_at;
};

/// Everything a branch-tracing program models. Plain data; see validate_scene for the ranges.
struct Scene {
  SceneGeometry geometry;
  ThicknessProfile thickness = ConstantThickness{};
  /// Young's modulus Y (Pa) > 0 and Poisson ratio nu in (-1, 0.5).
  Material material;
  SceneGrowth growth;
  SceneMesh mesh;
  ScenePhysics physics;
  SceneContinuation continuation;
  SceneOutput output;
  SceneStudy study;
};

/// The paper's disc: R = 1, h = 0.02, Y = 1e4 Pa, nu = 0.3, the rings mesh family with
/// size_slope 0.1 and min_spacing h/4 (auto), quadrature degree 2, phi_e from 0 to 3.73 with steps in
/// [1e-4, 0.1], mode 2, perturbation 1e-3 R with seed 1, output to "out"; the cone_branch
/// study with tolerance 1e-6, tangent angle 0.3, 2 eigenmodes, traced in the mirror subspace
/// where the mesh has the mirrors, the index without the pattern's turn, S4 threshold 1e-3,
/// no core left out, stopping at contact.
Scene default_scene();

/// Throws std::invalid_argument naming the first offending key, its value and the allowed
/// range, e.g. "geometry.inner_radius = 1.2 must be in (0, geometry.radius = 1)".
void validate_scene(const Scene& scene);

/// Reads a JSON scene file: starts from default_scene() and overrides what the file sets
/// (// and /* */ comments are allowed), then validates. Throws std::invalid_argument whose
/// message starts with the path and names the problem: a missing or unreadable file,
/// malformed JSON (with the parser's line and column), an unknown key ("unknown key
/// 'mesh.ringz'"), a wrong type ("mesh.rings must be an integer") or a range error.
Scene read_scene(const std::string& path);

/// The scene that the JSON text `text` describes, read as read_scene reads a file: keys it
/// does not set keep their defaults (so a scene recorded before a key existed reads as that
/// key's default). Error messages start with `origin` (e.g. "scene file 'a.json'").
Scene parse_scene(const std::string& text, const std::string& origin);

/// Fingerprint (FNV-1a, core/content_hash.hpp) of what defines the model and its unknowns:
/// the geometry, thickness, material, growth and mesh keys, with mesh.min_spacing resolved.
/// Two scenes with the same fingerprint build the same ShellModel; a saved state carries it
/// (studies/saved_state.hpp). Validates the scene first (throws as validate_scene).
std::uint64_t scene_model_fingerprint(const Scene& scene);

/// Sets one dotted key (as in the file, e.g. "thickness", "geometry.inner_radius",
/// "continuation.direction") from its command-line text. Numbers, booleans and arrays are
/// written as in JSON ("0.01", "true", "[0.1, 0]"); string-valued keys take the text as is;
/// "thickness" takes a number or a JSON object ('{"profile": "linear", ...}'); "auto" resets
/// mesh.min_spacing and physics.contact_distance. Throws std::invalid_argument for an unknown
/// key or a wrong type. Ranges are not checked: call validate_scene after all overrides.
void apply_override(Scene& scene, const std::string& key, const std::string& value);

/// The scene as a complete JSON document (every key, 2-space indent, trailing newline) that
/// read_scene turns back into the same scene; numbers are written in their shortest
/// round-trip form.
std::string scene_to_json(const Scene& scene);

/// All dotted keys a scene file may set, in file order ("geometry.shape", ..., "thickness",
/// ..., "output.write_vtk").
std::vector<std::string> scene_keys();

/// Thickness h (m) of `profile` at distance r (m) from the centre of a sheet of radius R (m).
double thickness_at_radius(const ThicknessProfile& profile, double r, double radius);

/// The mesh's smallest spacing (m): mesh.min_spacing if set, else a quarter of the thickness
/// at the centre (r = 0) for the rings and gmsh families and half of it for the others.
double resolved_min_spacing(const Scene& scene);

/// The default contact exclusion radius in thicknesses at the centre: the apex model
/// (docs/contact.md, "The apex model"). Two points on opposite sides of a cone's apex are
/// neighbours within reference radius 4 h of it, where the sheet's curvature (about 1/r) is not
/// small against 1/h and the thin shell does not describe it; farther out they are two
/// surfaces that may touch. phi_e^crit by energy does not depend on it from 4 h on.
inline constexpr double kApexExclusionThicknesses = 8.0;

/// The contact exclusion radius (m): physics.contact_exclusion_radius if set, else
/// kApexExclusionThicknesses h with h the thickness at the centre (r = 0). Throws
/// std::invalid_argument naming the key if it is below the contact distance
/// (physics.contact_distance, or that thickness if unset): neighbours on a flat sheet would
/// then count as touching.
double resolved_exclusion_radius(const Scene& scene);

/// Thickness field over reference positions X (m): thickness_at_radius at r = |(X_x, X_y)|.
ThicknessField scene_thickness_field(const Scene& scene);

/// Validates the scene and builds its control mesh, centred at the origin: for the lattice
/// family make_disc_mesh (conformal layout, rings, grading, resolved_min_spacing) for a disc and
/// make_annulus_mesh (radial_layers) for a ring; make_ring_disc_mesh or make_gmsh_disc_mesh
/// (size_slope, resolved_min_spacing as the size floor, size_max) for the rings and gmsh
/// families; the file family reads mesh.file (a .msh sheet gets a ghost layer). Throws
/// std::invalid_argument naming the key for a family the shape has not, and MeshError for an
/// unreadable or invalid mesh file.
TriangleMesh scene_mesh(const Scene& scene);

/// Validates the scene and returns the ShellModel settings it declares: material,
/// scene_thickness_field, quadrature degree and growth centre (z = 0); threads stay 0
/// (OpenMP's default).
ShellModelSettings scene_model_settings(const Scene& scene);

}  // namespace growshell
