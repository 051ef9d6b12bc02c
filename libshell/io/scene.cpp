#include "libshell/io/scene.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <sstream>
#include <numbers>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/content_hash.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/ghost_layer.hpp"
#include "libshell/mesh/gmsh_disc_mesh.hpp"
#include "libshell/mesh/msh_io.hpp"
#include "libshell/mesh/obj_io.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"

namespace growshell {
namespace {

// ordered_json keeps the members in file order, so the first error reported is the first
// one in the file and scene_to_json writes the sections in the order of the field table.
using Json = nlohmann::ordered_json;

[[noreturn]] void fail(const std::string& message) { throw std::invalid_argument(message); }

/// The thickest a sheet may be, as a fraction of its width (R, or R - R_i for a ring).
constexpr double kMaxThicknessFraction = 0.25;
/// Largest study.contact_proxy_segments: 64 proxy triangles per element, about 50 times the
/// pairs of the default (1) and beyond what a trace can afford on a mesh of the default size.
constexpr int kMaxSceneProxySegments = 8;

/// Shortest text that reads back as the same double, so that error messages never show a
/// rejected value rounded onto its bound (0.50000001 printed as "0.5").
std::string format(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

/// Fails with "KEY = SHOWN is listed twice" if entry i of a list equals an earlier one: every
/// list key of a scene names each value once.
template <class T>
void require_not_listed_before(const std::vector<T>& values, std::size_t i, const std::string& key,
                               const std::string& shown) {
  for (std::size_t j = 0; j < i; ++j)
    if (values[j] == values[i]) fail(key + " = " + shown + " is listed twice");
}

// ---- Names of the enumerations -----------------------------------------------------------

template <class Enum>
using NameTable = std::initializer_list<std::pair<Enum, std::string_view>>;

const NameTable<SceneShape> kShapeNames = {{SceneShape::Disc, "disc"}, {SceneShape::Ring, "ring"}};
const NameTable<MeshFamily> kMeshFamilyNames = {{MeshFamily::Lattice, "lattice"},
                                                {MeshFamily::Rings, "rings"},
                                                {MeshFamily::Gmsh, "gmsh"},
                                                {MeshFamily::GmshD4, "gmsh_d4"},
                                                {MeshFamily::File, "file"}};
const NameTable<StretchingLaw> kStretchingLawNames = {
    {StretchingLaw::kNeoHookean, "neo_hookean"},
    {StretchingLaw::kSaintVenantKirchhoff, "saint_venant_kirchhoff"}};
const NameTable<GrowthLaw> kLawNames = {{GrowthLaw::Circumferential, "circumferential"}};
const NameTable<GrowthSmoothingProfile> kSmoothingProfileNames = {
    {GrowthSmoothingProfile::Rational, "rational"}, {GrowthSmoothingProfile::Gaussian, "gaussian"}};
const NameTable<ContinuationDirection> kDirectionNames = {
    {ContinuationDirection::Forward, "forward"}, {ContinuationDirection::Backward, "backward"}};
const NameTable<SceneCorrector> kCorrectorNames = {{SceneCorrector::Newton, "newton"},
                                                   {SceneCorrector::Chord, "chord"}};
const NameTable<SceneContactSurface> kContactSurfaceNames = {
    {SceneContactSurface::ProxyTriangles, "proxy_triangles"},
    {SceneContactSurface::LimitSurface, "limit_surface"}};
const NameTable<SceneContactVertexTriangles> kContactVertexTriangleNames = {
    {SceneContactVertexTriangles::NearestAtBuild, "nearest_at_build"},
    {SceneContactVertexTriangles::EveryNearTriangle, "every_near_triangle"}};
const NameTable<StudyKind> kStudyKindNames = {{StudyKind::ConeBranch, "cone_branch"},
                                              {StudyKind::ThicknessSeries, "thickness_series"},
                                              {StudyKind::EconeContact, "econe_contact"},
                                              {StudyKind::Series, "series"}};

template <class Enum>
std::string enum_name(const NameTable<Enum>& names, Enum value) {
  for (const auto& [v, name] : names)
    if (v == value) return std::string(name);
  throw std::logic_error("enumeration value without a name");
}

template <class Enum>
std::string allowed_names(const NameTable<Enum>& names) {
  std::string list;
  for (const auto& [v, name] : names) list += (list.empty() ? "\"" : ", \"") + std::string(name) + "\"";
  return list;
}

// ---- Typed reads of JSON values ----------------------------------------------------------

double read_number(const Json& v, const std::string& key) {
  if (!v.is_number()) fail(key + " must be a number (got " + v.dump() + ")");
  return v.get<double>();
}

int read_int(const Json& v, const std::string& key) {
  if (!v.is_number_integer()) fail(key + " must be an integer (got " + v.dump() + ")");
  // Large positive literals are stored unsigned; get<std::int64_t> would wrap them.
  if (v.is_number_unsigned() ? v.get<std::uint64_t>() > static_cast<std::uint64_t>(INT_MAX)
                             : (v.get<std::int64_t>() < INT_MIN || v.get<std::int64_t>() > INT_MAX))
    fail(key + " = " + v.dump() + " must fit in a 32-bit integer");
  return static_cast<int>(v.get<std::int64_t>());
}

std::vector<int> read_int_list(const Json& v, const std::string& key) {
  if (!v.is_array()) fail(key + " must be an array of integers (got " + v.dump() + ")");
  std::vector<int> values;
  for (std::size_t i = 0; i < v.size(); ++i)
    values.push_back(read_int(v[i], key + "[" + std::to_string(i) + "]"));
  return values;
}

bool read_bool(const Json& v, const std::string& key) {
  if (!v.is_boolean()) fail(key + " must be true or false (got " + v.dump() + ")");
  return v.get<bool>();
}

std::string read_string(const Json& v, const std::string& key) {
  if (!v.is_string()) fail(key + " must be a string (got " + v.dump() + ")");
  return v.get<std::string>();
}

template <class Enum>
Enum read_enum(const Json& v, const std::string& key, const NameTable<Enum>& names) {
  if (!v.is_string()) fail(key + " must be one of " + allowed_names(names) + " (got " + v.dump() + ")");
  const std::string text = v.get<std::string>();
  for (const auto& [value, name] : names)
    if (text == name) return value;
  fail(key + " = \"" + text + "\" must be one of " + allowed_names(names));
}

/// A number, or the string "auto" (unset: the program derives the value).
std::optional<double> read_number_or_auto(const Json& v, const std::string& key) {
  if (v.is_string() && v.get<std::string>() == "auto") return std::nullopt;
  if (!v.is_number()) fail(key + " must be a number or \"auto\" (got " + v.dump() + ")");
  return v.get<double>();
}

Json write_number_or_auto(const std::optional<double>& value) {
  return value ? Json(*value) : Json("auto");
}

/// A number, or null (unset: the step it asks for is not run).
std::optional<double> read_number_or_null(const Json& v, const std::string& key) {
  if (v.is_null()) return std::nullopt;
  if (!v.is_number()) fail(key + " must be a number or null (got " + v.dump() + ")");
  return v.get<double>();
}

Json write_number_or_null(const std::optional<double>& value) {
  return value ? Json(*value) : Json(nullptr);
}

Eigen::Vector2d read_point2(const Json& v, const std::string& key) {
  if (!(v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()))
    fail(key + " must be an array of two numbers [x, y] (got " + v.dump() + ")");
  return {v[0].get<double>(), v[1].get<double>()};
}

std::vector<double> read_number_list(const Json& v, const std::string& key) {
  if (!v.is_array()) fail(key + " must be an array of numbers (got " + v.dump() + ")");
  std::vector<double> values;
  for (const Json& e : v) {
    if (!e.is_number()) fail(key + " must be an array of numbers (got " + v.dump() + ")");
    values.push_back(e.get<double>());
  }
  return values;
}

std::vector<std::string> read_string_list(const Json& v, const std::string& key) {
  if (!v.is_array()) fail(key + " must be an array of strings (got " + v.dump() + ")");
  std::vector<std::string> values;
  for (const Json& e : v) {
    if (!e.is_string()) fail(key + " must be an array of strings (got " + v.dump() + ")");
    values.push_back(e.get<std::string>());
  }
  return values;
}

std::uint32_t read_seed(const Json& v, const std::string& key) {
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > UINT32_MAX)
    fail(key + " must be an integer in [0, 4294967295] (got " + v.dump() + ")");
  return static_cast<std::uint32_t>(v.get<std::uint64_t>());
}

// ---- Thickness profiles ------------------------------------------------------------------

/// "thickness" is a number (constant) or an object {"profile": name, ...profile's keys}.
ThicknessProfile read_thickness(const Json& v, const std::string& key) {
  if (v.is_number()) return ConstantThickness{v.get<double>()};
  if (!v.is_object())
    fail(key + " must be a number or an object with a \"profile\" (got " + v.dump() + ")");
  if (!v.contains("profile")) fail(key + ".profile is missing (allowed: \"linear\")");
  const std::string profile = read_string(v.at("profile"), key + ".profile");
  const auto required_number = [&](const char* name) {
    if (!v.contains(name)) fail(key + "." + name + " is required for profile \"" + profile + "\"");
    return read_number(v.at(name), key + "." + name);
  };
  const auto only_keys = [&](std::initializer_list<std::string_view> allowed) {
    for (const auto& item : v.items())
      if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end())
        fail("unknown key '" + key + "." + item.key() + "' for profile \"" + profile + "\"");
  };
  if (profile == "linear") {
    only_keys({"profile", "center", "rim"});
    return LinearThickness{required_number("center"), required_number("rim")};
  }
  fail(key + ".profile = \"" + profile + "\" must be one of \"linear\" (or give a number)");
}

Json write_thickness(const ThicknessProfile& profile) {
  struct Writer {
    Json operator()(const ConstantThickness& p) const { return p.value; }
    Json operator()(const LinearThickness& p) const {
      Json j;
      j["profile"] = "linear";
      j["center"] = p.center;
      j["rim"] = p.rim;
      return j;
    }
  };
  return std::visit(Writer{}, profile);
}

// ---- The field table: one row per key drives reading, writing and overrides -------------

struct Field {
  std::string_view key;
  void (*set)(Scene&, const Json&, const std::string& key);
  Json (*get)(const Scene&);
  /// Command-line values of string keys are taken verbatim (a directory named "1" must not
  /// become a number); others are parsed as JSON first.
  bool verbatim = false;
};

// clang-format off
const Field kFields[] = {
  {"geometry.shape",
   [](Scene& s, const Json& v, const std::string& k) { s.geometry.shape = read_enum(v, k, kShapeNames); },
   [](const Scene& s) { return Json(enum_name(kShapeNames, s.geometry.shape)); }, true},
  {"geometry.radius",
   [](Scene& s, const Json& v, const std::string& k) { s.geometry.radius = read_number(v, k); },
   [](const Scene& s) { return Json(s.geometry.radius); }},
  {"geometry.inner_radius",
   [](Scene& s, const Json& v, const std::string& k) { s.geometry.inner_radius = read_number(v, k); },
   [](const Scene& s) { return Json(s.geometry.inner_radius); }},
  {"thickness",
   [](Scene& s, const Json& v, const std::string& k) { s.thickness = read_thickness(v, k); },
   [](const Scene& s) { return write_thickness(s.thickness); }},
  {"material.youngs_modulus",
   [](Scene& s, const Json& v, const std::string& k) { s.material.youngs_modulus = read_number(v, k); },
   [](const Scene& s) { return Json(s.material.youngs_modulus); }},
  {"material.poisson_ratio",
   [](Scene& s, const Json& v, const std::string& k) { s.material.poisson_ratio = read_number(v, k); },
   [](const Scene& s) { return Json(s.material.poisson_ratio); }},
  {"material.stretching_law",
   [](Scene& s, const Json& v, const std::string& k) { s.material.stretching_law = read_enum(v, k, kStretchingLawNames); },
   [](const Scene& s) { return Json(enum_name(kStretchingLawNames, s.material.stretching_law)); }, true},
  {"growth.law",
   [](Scene& s, const Json& v, const std::string& k) { s.growth.law = read_enum(v, k, kLawNames); },
   [](const Scene& s) { return Json(enum_name(kLawNames, s.growth.law)); }, true},
  {"growth.center",
   [](Scene& s, const Json& v, const std::string& k) { s.growth.center = read_point2(v, k); },
   [](const Scene& s) { return Json::array({s.growth.center.x(), s.growth.center.y()}); }},
  {"growth.smoothing_radius",
   [](Scene& s, const Json& v, const std::string& k) { s.growth.smoothing_radius = read_number(v, k); },
   [](const Scene& s) { return Json(s.growth.smoothing_radius); }},
  {"growth.smoothing_profile",
   [](Scene& s, const Json& v, const std::string& k) { s.growth.smoothing_profile = read_enum(v, k, kSmoothingProfileNames); },
   [](const Scene& s) { return Json(enum_name(kSmoothingProfileNames, s.growth.smoothing_profile)); }, true},
  {"mesh.family",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.family = read_enum(v, k, kMeshFamilyNames); },
   [](const Scene& s) { return Json(enum_name(kMeshFamilyNames, s.mesh.family)); }, true},
  {"mesh.rings",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.rings = read_int(v, k); },
   [](const Scene& s) { return Json(s.mesh.rings); }},
  {"mesh.radial_layers",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.radial_layers = read_int(v, k); },
   [](const Scene& s) { return Json(s.mesh.radial_layers); }},
  {"mesh.grading_exponent",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.grading_exponent = read_number(v, k); },
   [](const Scene& s) { return Json(s.mesh.grading_exponent); }},
  {"mesh.min_spacing",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.min_spacing = read_number_or_auto(v, k); },
   [](const Scene& s) { return write_number_or_auto(s.mesh.min_spacing); }},
  {"mesh.size_slope",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.size_slope = read_number(v, k); },
   [](const Scene& s) { return Json(s.mesh.size_slope); }},
  {"mesh.size_max",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.size_max = read_number_or_auto(v, k); },
   [](const Scene& s) { return write_number_or_auto(s.mesh.size_max); }},
  {"mesh.file",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.file = read_string(v, k); },
   [](const Scene& s) { return Json(s.mesh.file); }, true},
  {"mesh.quadrature_degree",
   [](Scene& s, const Json& v, const std::string& k) { s.mesh.quadrature_degree = read_int(v, k); },
   [](const Scene& s) { return Json(s.mesh.quadrature_degree); }},
  {"physics.contact",
   [](Scene& s, const Json& v, const std::string& k) { s.physics.contact = read_bool(v, k); },
   [](const Scene& s) { return Json(s.physics.contact); }},
  {"physics.contact_distance",
   [](Scene& s, const Json& v, const std::string& k) { s.physics.contact_distance = read_number_or_auto(v, k); },
   [](const Scene& s) { return write_number_or_auto(s.physics.contact_distance); }},
  {"physics.contact_exclusion_radius",
   [](Scene& s, const Json& v, const std::string& k) { s.physics.contact_exclusion_radius = read_number_or_auto(v, k); },
   [](const Scene& s) { return write_number_or_auto(s.physics.contact_exclusion_radius); }},
  {"continuation.phi_start",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.phi_start = read_number(v, k); },
   [](const Scene& s) { return Json(s.continuation.phi_start); }},
  {"continuation.phi_min",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.phi_min = read_number(v, k); },
   [](const Scene& s) { return Json(s.continuation.phi_min); }},
  {"continuation.phi_max",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.phi_max = read_number(v, k); },
   [](const Scene& s) { return Json(s.continuation.phi_max); }},
  {"continuation.max_step",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.max_step = read_number(v, k); },
   [](const Scene& s) { return Json(s.continuation.max_step); }},
  {"continuation.min_step",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.min_step = read_number(v, k); },
   [](const Scene& s) { return Json(s.continuation.min_step); }},
  {"continuation.direction",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.direction = read_enum(v, k, kDirectionNames); },
   [](const Scene& s) { return Json(enum_name(kDirectionNames, s.continuation.direction)); }, true},
  {"continuation.corrector",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.corrector = read_enum(v, k, kCorrectorNames); },
   [](const Scene& s) { return Json(enum_name(kCorrectorNames, s.continuation.corrector)); }, true},
  {"continuation.mode",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.mode = read_int(v, k); },
   [](const Scene& s) { return Json(s.continuation.mode); }},
  {"continuation.perturbation_amplitude",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.perturbation_amplitude = read_number(v, k); },
   [](const Scene& s) { return Json(s.continuation.perturbation_amplitude); }},
  {"continuation.seed",
   [](Scene& s, const Json& v, const std::string& k) { s.continuation.seed = read_seed(v, k); },
   [](const Scene& s) { return Json(s.continuation.seed); }},
  {"output.directory",
   [](Scene& s, const Json& v, const std::string& k) { s.output.directory = read_string(v, k); },
   [](const Scene& s) { return Json(s.output.directory); }, true},
  {"output.snapshot_every",
   [](Scene& s, const Json& v, const std::string& k) { s.output.snapshot_every = read_int(v, k); },
   [](const Scene& s) { return Json(s.output.snapshot_every); }},
  {"output.write_vtk",
   [](Scene& s, const Json& v, const std::string& k) { s.output.write_vtk = read_bool(v, k); },
   [](const Scene& s) { return Json(s.output.write_vtk); }},
  {"study.kind",
   [](Scene& s, const Json& v, const std::string& k) { s.study.kind = read_enum(v, k, kStudyKindNames); },
   [](const Scene& s) { return Json(enum_name(kStudyKindNames, s.study.kind)); }, true},
  {"study.through_contact",
   [](Scene& s, const Json& v, const std::string& k) { s.study.through_contact = read_bool(v, k); },
   [](const Scene& s) { return Json(s.study.through_contact); }},
  {"study.tolerance",
   [](Scene& s, const Json& v, const std::string& k) { s.study.tolerance = read_number(v, k); },
   [](const Scene& s) { return Json(s.study.tolerance); }},
  {"study.max_tangent_angle",
   [](Scene& s, const Json& v, const std::string& k) { s.study.max_tangent_angle = read_number(v, k); },
   [](const Scene& s) { return Json(s.study.max_tangent_angle); }},
  {"study.eigenmodes",
   [](Scene& s, const Json& v, const std::string& k) { s.study.eigenmodes = read_int(v, k); },
   [](const Scene& s) { return Json(s.study.eigenmodes); }},
  {"study.symmetric_subspace",
   [](Scene& s, const Json& v, const std::string& k) { s.study.symmetric_subspace = read_bool(v, k); },
   [](const Scene& s) { return Json(s.study.symmetric_subspace); }},
  {"study.half_turn_subspace",
   [](Scene& s, const Json& v, const std::string& k) { s.study.half_turn_subspace = read_bool(v, k); },
   [](const Scene& s) { return Json(s.study.half_turn_subspace); }},
  {"study.index_excludes_pattern_turn",
   [](Scene& s, const Json& v, const std::string& k) { s.study.index_excludes_pattern_turn = read_bool(v, k); },
   [](const Scene& s) { return Json(s.study.index_excludes_pattern_turn); }},
  {"study.phase_condition",
   [](Scene& s, const Json& v, const std::string& k) { s.study.phase_condition = read_bool(v, k); },
   [](const Scene& s) { return Json(s.study.phase_condition); }},
  {"study.symmetry_threshold",
   [](Scene& s, const Json& v, const std::string& k) { s.study.symmetry_threshold = read_number(v, k); },
   [](const Scene& s) { return Json(s.study.symmetry_threshold); }},
  {"study.core_radius",
   [](Scene& s, const Json& v, const std::string& k) { s.study.core_radius = read_number(v, k); },
   [](const Scene& s) { return Json(s.study.core_radius); }},
  {"study.thicknesses",
   [](Scene& s, const Json& v, const std::string& k) { s.study.thicknesses = read_number_list(v, k); },
   [](const Scene& s) { return Json(s.study.thicknesses); }},
  {"study.phi_max_limit",
   [](Scene& s, const Json& v, const std::string& k) { s.study.phi_max_limit = read_number(v, k); },
   [](const Scene& s) { return Json(s.study.phi_max_limit); }},
  {"study.series_key",
   [](Scene& s, const Json& v, const std::string& k) { s.study.series_key = read_string(v, k); },
   [](const Scene& s) { return Json(s.study.series_key); }},
  {"study.series_values",
   [](Scene& s, const Json& v, const std::string& k) { s.study.series_values = read_number_list(v, k); },
   [](const Scene& s) { return Json(s.study.series_values); }},
  {"study.series_of",
   [](Scene& s, const Json& v, const std::string& k) { s.study.series_of = read_enum(v, k, kStudyKindNames); },
   [](const Scene& s) { return Json(enum_name(kStudyKindNames, s.study.series_of)); }},
  {"study.series_report",
   [](Scene& s, const Json& v, const std::string& k) { s.study.series_report = read_string_list(v, k); },
   [](const Scene& s) { return Json(s.study.series_report); }},
  {"study.skew_search_at",
   [](Scene& s, const Json& v, const std::string& k) { s.study.skew_search_at = read_number_or_auto(v, k); },
   [](const Scene& s) { return write_number_or_auto(s.study.skew_search_at); }},
  {"study.contact_max_step",
   [](Scene& s, const Json& v, const std::string& k) { s.study.contact_max_step = read_number(v, k); },
   [](const Scene& s) { return Json(s.study.contact_max_step); }},
  {"study.contact_max_corrector_iterations",
   [](Scene& s, const Json& v, const std::string& k) { s.study.contact_max_corrector_iterations = read_int(v, k); },
   [](const Scene& s) { return Json(s.study.contact_max_corrector_iterations); }},
  {"study.contact_stall_iterations",
   [](Scene& s, const Json& v, const std::string& k) { s.study.contact_stall_iterations = read_int(v, k); },
   [](const Scene& s) { return Json(s.study.contact_stall_iterations); }},
  {"study.contact_growth_pause",
   [](Scene& s, const Json& v, const std::string& k) { s.study.contact_growth_pause = read_int(v, k); },
   [](const Scene& s) { return Json(s.study.contact_growth_pause); }},
  {"study.contact_vertex_triangles",
   [](Scene& s, const Json& v, const std::string& k) { s.study.contact_vertex_triangles = read_enum(v, k, kContactVertexTriangleNames); },
   [](const Scene& s) { return Json(enum_name(kContactVertexTriangleNames, s.study.contact_vertex_triangles)); }},
  {"study.contact_proxy_segments",
   [](Scene& s, const Json& v, const std::string& k) { s.study.contact_proxy_segments = read_int(v, k); },
   [](const Scene& s) { return Json(s.study.contact_proxy_segments); }},
  {"study.contact_surface",
   [](Scene& s, const Json& v, const std::string& k) { s.study.contact_surface = read_enum(v, k, kContactSurfaceNames); },
   [](const Scene& s) { return Json(enum_name(kContactSurfaceNames, s.study.contact_surface)); }},
  {"study.penalty_stiffness_factor",
   [](Scene& s, const Json& v, const std::string& k) { s.study.penalty_stiffness_factor = read_number(v, k); },
   [](const Scene& s) { return Json(s.study.penalty_stiffness_factor); }},
  {"study.orientation_check_turns",
   [](Scene& s, const Json& v, const std::string& k) {
     s.study.orientation_check_turns = read_number_list(v, k);
   },
   [](const Scene& s) { return Json(s.study.orientation_check_turns); }},
  {"study.orientation_check_at",
   [](Scene& s, const Json& v, const std::string& k) {
     s.study.orientation_check_at = read_number_or_auto(v, k);
   },
   [](const Scene& s) { return write_number_or_auto(s.study.orientation_check_at); }},
  {"study.ipopt_check",
   [](Scene& s, const Json& v, const std::string& k) { s.study.ipopt_check = read_bool(v, k); },
   [](const Scene& s) { return Json(s.study.ipopt_check); }},
  {"study.hard_contact_at",
   [](Scene& s, const Json& v, const std::string& k) { s.study.hard_contact_at = read_number_list(v, k); },
   [](const Scene& s) { return Json(s.study.hard_contact_at); }},
  {"study.hard_contact_branches",
   [](Scene& s, const Json& v, const std::string& k) { s.study.hard_contact_branches = read_string_list(v, k); },
   [](const Scene& s) { return Json(s.study.hard_contact_branches); }},
  {"study.wind_to",
   [](Scene& s, const Json& v, const std::string& k) { s.study.wind_to = read_number_or_null(v, k); },
   [](const Scene& s) { return write_number_or_null(s.study.wind_to); }},
  {"study.wind_shapes_at",
   [](Scene& s, const Json& v, const std::string& k) { s.study.wind_shapes_at = read_number_list(v, k); },
   [](const Scene& s) { return Json(s.study.wind_shapes_at); }},
  {"study.compare_modes",
   [](Scene& s, const Json& v, const std::string& k) { s.study.compare_modes = read_int_list(v, k); },
   [](const Scene& s) { return Json(s.study.compare_modes); }},
};
// clang-format on

const Field* find_field(std::string_view key) {
  for (const Field& f : kFields)
    if (f.key == key) return &f;
  return nullptr;
}

/// The keys directly below `section` ("" for the top level), e.g. "rings, radial_layers, ...".
std::string keys_below(const std::string& section) {
  const std::string prefix = section.empty() ? "" : section + ".";
  std::vector<std::string> names;
  for (const Field& f : kFields) {
    if (f.key.substr(0, prefix.size()) != prefix) continue;
    std::string rest(f.key.substr(prefix.size()));
    rest = rest.substr(0, rest.find('.'));
    if (std::find(names.begin(), names.end(), rest) == names.end()) names.push_back(rest);
  }
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

bool is_section(const std::string& key) {
  const std::string prefix = key + ".";
  return std::any_of(std::begin(kFields), std::end(kFields),
                     [&](const Field& f) { return f.key.substr(0, prefix.size()) == prefix; });
}

[[noreturn]] void unknown_key(const std::string& key) {
  const std::size_t dot = key.rfind('.');
  const std::string section = dot == std::string::npos ? "" : key.substr(0, dot);
  fail("unknown key '" + key + "' (allowed " + (section.empty() ? "at the top level" : "in " + section) +
       ": " + keys_below(section) + ")");
}

void apply_object(Scene& scene, const Json& object, const std::string& prefix) {
  for (const auto& item : object.items()) {
    const std::string key = prefix.empty() ? item.key() : prefix + "." + item.key();
    if (const Field* field = find_field(key)) {
      field->set(scene, item.value(), key);
    } else if (is_section(key)) {
      if (!item.value().is_object()) fail(key + " must be an object (got " + item.value().dump() + ")");
      apply_object(scene, item.value(), key);
    } else {
      unknown_key(key);
    }
  }
}

// ---- Range checks ------------------------------------------------------------------------

void require_positive(double value, const std::string& key) {
  if (!(std::isfinite(value) && value > 0.0)) fail(key + " = " + format(value) + " must be finite and > 0");
}

void require_nonnegative(double value, const std::string& key) {
  if (!(std::isfinite(value) && value >= 0.0)) fail(key + " = " + format(value) + " must be finite and >= 0");
}

void require_finite(double value, const std::string& key) {
  if (!std::isfinite(value)) fail(key + " = " + format(value) + " must be finite");
}

void require_at_least(int value, int minimum, const std::string& key) {
  if (value < minimum) fail(key + " = " + std::to_string(value) + " must be >= " + std::to_string(minimum));
}

void validate_thickness(const ThicknessProfile& profile) {
  struct Check {
    void operator()(const ConstantThickness& p) const { require_positive(p.value, "thickness"); }
    void operator()(const LinearThickness& p) const {
      // h is linear in the clamped r, so positive ends mean positive everywhere.
      require_positive(p.center, "thickness.center");
      require_positive(p.rim, "thickness.rim");
    }
  };
  std::visit(Check{}, profile);
}

}  // namespace

Scene default_scene() { return Scene{}; }

namespace {

/// study.wind_to and study.wind_shapes_at (econe_contact only, beyond continuation.phi_max),
/// and study.compare_modes (econe_contact only, modes 3 and up).
void validate_winding(const Scene& scene) {
  const SceneStudy& st = scene.study;
  const bool econe = st.kind == StudyKind::EconeContact ||
                     (st.kind == StudyKind::Series && st.series_of == StudyKind::EconeContact);
  if (!st.compare_modes.empty() && !econe)
    fail("study.compare_modes is read only by the econe_contact study (this scene's study is \"" +
         enum_name(kStudyKindNames, st.kind) + "\")");
  for (std::size_t i = 0; i < st.compare_modes.size(); ++i) {
    const std::string key = "study.compare_modes[" + std::to_string(i) + "]";
    if (st.compare_modes[i] < 3)
      fail(key + " = " + std::to_string(st.compare_modes[i]) +
           " must be at least 3: the two-fold cone is the study's own");
    require_not_listed_before(st.compare_modes, i, key, std::to_string(st.compare_modes[i]));
  }
  if ((st.wind_to || !st.wind_shapes_at.empty()) && !econe)
    fail("study.wind_to and study.wind_shapes_at are read only by the econe_contact study (this "
         "scene's study is \"" + enum_name(kStudyKindNames, st.kind) + "\")");
  if (!st.wind_shapes_at.empty() && !st.wind_to)
    fail("study.wind_shapes_at is set but study.wind_to is null: the winding is not run");
  if (!st.wind_to) return;
  const double top = scene.continuation.phi_max;
  if (!(std::isfinite(*st.wind_to) && *st.wind_to > top))
    fail("study.wind_to = " + format(*st.wind_to) + " must be finite and above continuation.phi_max = " +
         format(top) + ": the winding starts where the skewed branch ends");
  for (std::size_t i = 0; i < st.wind_shapes_at.size(); ++i) {
    const std::string key = "study.wind_shapes_at[" + std::to_string(i) + "]";
    const double at = st.wind_shapes_at[i];
    if (!(at > top && at <= *st.wind_to))
      fail(key + " = " + format(at) + " must lie in (continuation.phi_max, study.wind_to] = (" +
           format(top) + ", " + format(*st.wind_to) + "]");
    require_not_listed_before(st.wind_shapes_at, i, key, format(at));
  }
}

/// The series keys: complete for study.kind series, absent for every other study.
void validate_series(const SceneStudy& st) {
  if (st.kind != StudyKind::Series) {
    if (!st.series_key.empty() || !st.series_values.empty() || !st.series_report.empty() ||
        st.series_of != StudyKind::ConeBranch)
      fail("study.series_key, series_values, series_of and series_report are read only by "
           "study.kind = \"series\" (this scene's study is \"" +
           enum_name(kStudyKindNames, st.kind) + "\")");
    return;
  }
  if (st.series_key.empty()) fail("study.series_key must name the scene key the series varies");
  const bool own = st.series_key == "study.kind" || st.series_key.rfind("study.series_", 0) == 0 ||
                   st.series_key.rfind("output.", 0) == 0;
  if (own || !find_field(st.series_key))
    fail("study.series_key = \"" + st.series_key + "\" must be a scene key of docs/scenes.md other "
         "than study.kind, study.series_* and output.*");
  if (st.series_values.empty()) fail("study.series_values must list at least one value");
  for (std::size_t i = 0; i < st.series_values.size(); ++i) {
    const std::string key = "study.series_values[" + std::to_string(i) + "]";
    require_finite(st.series_values[i], key);
    require_not_listed_before(st.series_values, i, key, format(st.series_values[i]));
  }
  if (st.series_of != StudyKind::ConeBranch && st.series_of != StudyKind::EconeContact)
    fail("study.series_of = \"" + enum_name(kStudyKindNames, st.series_of) +
         "\" must be \"cone_branch\" or \"econe_contact\"");
  if (st.series_report.empty())
    fail("study.series_report must list at least one key of the points' results.json");
  for (std::size_t i = 0; i < st.series_report.size(); ++i) {
    const std::string key = "study.series_report[" + std::to_string(i) + "]";
    if (st.series_report[i].empty()) fail(key + " is empty");
    require_not_listed_before(st.series_report, i, key, "\"" + st.series_report[i] + "\"");
  }
}

}  // namespace

void validate_scene(const Scene& scene) {
  const SceneGeometry& g = scene.geometry;
  require_positive(g.radius, "geometry.radius");
  if (g.shape == SceneShape::Ring && !(g.inner_radius > 0.0 && g.inner_radius < g.radius))
    fail("geometry.inner_radius = " + format(g.inner_radius) + " must be in (0, geometry.radius = " +
         format(g.radius) + ")");

  validate_thickness(scene.thickness);
  // A thin sheet: the Kirchhoff-Love energy holds for h << the sheet's width (R, or R - R_i
  // for a ring); a quarter of it is the stated limit.
  {
    const double width = g.shape == SceneShape::Ring ? g.radius - g.inner_radius : g.radius;
    const double thickest = std::max(thickness_at_radius(scene.thickness, 0.0, g.radius),
                                     thickness_at_radius(scene.thickness, g.radius, g.radius));
    if (!(thickest <= kMaxThicknessFraction * width))
      fail("thickness " + format(thickest) + " must be at most " + format(kMaxThicknessFraction) +
           " times the sheet's width " + format(width) + " (R" +
           (g.shape == SceneShape::Ring ? " - R_i" : "") +
           "): the shell energy is that of a thin sheet");
  }

  require_positive(scene.material.youngs_modulus, "material.youngs_modulus");
  const double nu = scene.material.poisson_ratio;
  if (!(nu > -1.0 && nu < 0.5)) fail("material.poisson_ratio = " + format(nu) + " must be in (-1, 0.5)");

  require_finite(scene.growth.center.x(), "growth.center[0]");
  require_finite(scene.growth.center.y(), "growth.center[1]");
  require_nonnegative(scene.growth.smoothing_radius, "growth.smoothing_radius");

  const SceneMesh& m = scene.mesh;
  require_at_least(m.rings, 2, "mesh.rings");
  require_at_least(m.radial_layers, 1, "mesh.radial_layers");
  if (!(std::isfinite(m.grading_exponent) && m.grading_exponent >= 1.0))
    fail("mesh.grading_exponent = " + format(m.grading_exponent) + " must be finite and >= 1");
  if (m.min_spacing) require_nonnegative(*m.min_spacing, "mesh.min_spacing");
  require_positive(m.size_slope, "mesh.size_slope");
  if (m.size_max) require_positive(*m.size_max, "mesh.size_max");
  if (m.family == MeshFamily::File && m.file.empty())
    fail("mesh.family = file needs mesh.file, the path of a .msh or .obj mesh");
  if (m.family != MeshFamily::File && !m.file.empty())
    fail("mesh.file = '" + m.file + "' is read only with mesh.family = file");
  if (m.quadrature_degree < 1 || m.quadrature_degree > 6)
    fail("mesh.quadrature_degree = " + std::to_string(m.quadrature_degree) + " must be in {1, ..., 6}");

  if (scene.physics.contact_distance) require_positive(*scene.physics.contact_distance, "physics.contact_distance");
  if (scene.physics.contact_exclusion_radius) {
    require_positive(*scene.physics.contact_exclusion_radius, "physics.contact_exclusion_radius");
    resolved_exclusion_radius(scene);
  }

  const SceneContinuation& c = scene.continuation;
  require_finite(c.phi_min, "continuation.phi_min");
  require_finite(c.phi_max, "continuation.phi_max");
  require_finite(c.phi_start, "continuation.phi_start");
  if (!(c.phi_min < c.phi_max))
    fail("continuation.phi_min = " + format(c.phi_min) + " must be < continuation.phi_max = " + format(c.phi_max));
  if (!(c.phi_start >= c.phi_min && c.phi_start <= c.phi_max))
    fail("continuation.phi_start = " + format(c.phi_start) + " must be in [continuation.phi_min = " +
         format(c.phi_min) + ", continuation.phi_max = " + format(c.phi_max) + "]");
  require_positive(c.max_step, "continuation.max_step");
  if (!(c.min_step > 0.0 && c.min_step <= c.max_step))
    fail("continuation.min_step = " + format(c.min_step) + " must be in (0, continuation.max_step = " +
         format(c.max_step) + "]");
  require_at_least(c.mode, 2, "continuation.mode");
  require_nonnegative(c.perturbation_amplitude, "continuation.perturbation_amplitude");

  if (scene.output.directory.empty()) fail("output.directory must not be empty");
  require_at_least(scene.output.snapshot_every, 0, "output.snapshot_every");

  const SceneStudy& st = scene.study;
  require_positive(st.tolerance, "study.tolerance");
  if (!(st.max_tangent_angle > 0.0 && st.max_tangent_angle < std::numbers::pi))
    fail("study.max_tangent_angle = " + format(st.max_tangent_angle) + " must be in (0, pi)");
  require_at_least(st.eigenmodes, 0, "study.eigenmodes");
  require_positive(st.symmetry_threshold, "study.symmetry_threshold");
  require_nonnegative(st.core_radius, "study.core_radius");
  require_finite(st.phi_max_limit, "study.phi_max_limit");
  if (st.skew_search_at) require_positive(*st.skew_search_at, "study.skew_search_at");
  if (st.orientation_check_at) require_positive(*st.orientation_check_at, "study.orientation_check_at");
  if (st.orientation_check_at && st.orientation_check_turns.empty())
    fail("study.orientation_check_at is set but study.orientation_check_turns is empty: no turn to check");
  if (st.orientation_check_at && scene.continuation.mode != 2)
    fail("study.orientation_check_at measures the two-fold cone's S4 symmetry: it needs "
         "continuation.mode = 2 (got " + std::to_string(scene.continuation.mode) + ")");
  require_positive(st.contact_max_step, "study.contact_max_step");
  require_at_least(st.contact_max_corrector_iterations, 1,
                   "study.contact_max_corrector_iterations");
  require_at_least(st.contact_stall_iterations, 0, "study.contact_stall_iterations");
  require_at_least(st.contact_growth_pause, 0, "study.contact_growth_pause");
  require_positive(st.penalty_stiffness_factor, "study.penalty_stiffness_factor");
  if (st.contact_proxy_segments < 1 || st.contact_proxy_segments > kMaxSceneProxySegments)
    fail("study.contact_proxy_segments = " + std::to_string(st.contact_proxy_segments) +
         " must be in [1, " + std::to_string(kMaxSceneProxySegments) +
         "]: segments per element edge of the contact proxy (n^2 proxy triangles per element)");
  for (std::size_t i = 0; i < st.orientation_check_turns.size(); ++i) {
    const std::string key = "study.orientation_check_turns[" + std::to_string(i) + "]";
    const double turn = st.orientation_check_turns[i];
    if (!(std::isfinite(turn) && turn > -90.0 && turn < 90.0 && turn != 0.0))
      fail(key + " = " + format(turn) + " must be a turn in degrees in (-90, 90) other than 0");
    require_not_listed_before(st.orientation_check_turns, i, key, format(turn));
  }
  if (st.kind == StudyKind::ThicknessSeries) {
    if (st.thicknesses.size() < 2)
      fail("study.thicknesses must list at least two thicknesses for study.kind = "
           "\"thickness_series\" (got " + std::to_string(st.thicknesses.size()) + ")");
    for (std::size_t i = 0; i < st.thicknesses.size(); ++i) {
      const std::string key = "study.thicknesses[" + std::to_string(i) + "]";
      require_positive(st.thicknesses[i], key);
      require_not_listed_before(st.thicknesses, i, key, format(st.thicknesses[i]));
    }
  } else if (!st.thicknesses.empty()) {
    fail("study.thicknesses is read only by study.kind = \"thickness_series\"; the study \"" +
         enum_name(kStudyKindNames, st.kind) + "\" takes its thickness from the key thickness");
  }
  validate_series(st);
  for (std::size_t i = 0; i < st.hard_contact_at.size(); ++i) {
    const std::string key = "study.hard_contact_at[" + std::to_string(i) + "]";
    require_positive(st.hard_contact_at[i], key);
    require_not_listed_before(st.hard_contact_at, i, key, format(st.hard_contact_at[i]));
  }
  if (st.hard_contact_branches.empty())
    fail(
        "study.hard_contact_branches must list at least one of \"turned\", \"symmetric\" and "
        "\"skewed\"");
  for (std::size_t i = 0; i < st.hard_contact_branches.size(); ++i) {
    const std::string key = "study.hard_contact_branches[" + std::to_string(i) + "]";
    const std::string& b = st.hard_contact_branches[i];
    if (b != "turned" && b != "symmetric" && b != "skewed")
      fail(key + " = \"" + b + "\" must be \"turned\", \"symmetric\" or \"skewed\"");
    require_not_listed_before(st.hard_contact_branches, i, key, "\"" + b + "\"");
  }
  if (!st.hard_contact_at.empty() && st.kind != StudyKind::EconeContact &&
      !(st.kind == StudyKind::Series && st.series_of == StudyKind::EconeContact))
    fail("study.hard_contact_at is read only by the econe_contact study (this scene's study is \"" +
         enum_name(kStudyKindNames, st.kind) + "\")");
  validate_winding(scene);
}

Scene read_scene(const std::string& path) {
  const std::string where = "scene file '" + path + "': ";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(where + "no such file");
  if (std::filesystem::is_directory(path, ec)) fail(where + "is a directory, not a file");
  std::ifstream in(path);
  if (!in) fail(where + "cannot be opened for reading");
  std::stringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), "scene file '" + path + "'");
}

Scene parse_scene(const std::string& text, const std::string& origin) {
  const std::string where = origin + ": ";
  Json document;
  try {
    document = Json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const Json::exception& e) {
    // parse_error, and out_of_range for a number beyond double (e.g. 1e400): found by
    // fuzz/fuzz_scene_parser.
    fail(where + "malformed JSON: " + e.what());
  }
  if (!document.is_object()) fail(where + "the top level must be a JSON object (got " + document.type_name() + ")");
  Scene scene = default_scene();
  try {
    apply_object(scene, document, "");
    validate_scene(scene);
  } catch (const std::invalid_argument& e) {
    fail(where + e.what());
  }
  return scene;
}

void apply_override(Scene& scene, const std::string& key, const std::string& value) {
  const Field* field = find_field(key);
  if (!field) {
    if (is_section(key)) fail("'" + key + "' is a section, not a key; its keys: " + keys_below(key));
    unknown_key(key);
  }
  Json parsed;
  if (field->verbatim) {
    parsed = value;
  } else {
    // Text that is not JSON ("abc", "auto") is kept as a string, so the field's own type
    // check reports it the way a file would.
    parsed = Json::parse(value, nullptr, /*allow_exceptions=*/false);
    if (parsed.is_discarded()) parsed = value;
  }
  field->set(scene, parsed, key);
}

std::string scene_to_json(const Scene& scene) {
  Json document = Json::object();
  for (const Field& field : kFields) {
    const std::string key(field.key);
    const std::size_t dot = key.find('.');
    if (dot == std::string::npos)
      document[key] = field.get(scene);
    else
      document[key.substr(0, dot)][key.substr(dot + 1)] = field.get(scene);
  }
  return document.dump(2) + "\n";
}

std::uint64_t scene_model_fingerprint(const Scene& scene) {
  validate_scene(scene);
  const Json document = Json::parse(scene_to_json(scene));
  Json model = Json::object();
  for (const char* section : {"geometry", "thickness", "material", "growth", "mesh"})
    model[section] = document.at(section);
  // The floor that "auto" resolves to, so that a change of that rule changes the fingerprint.
  model["mesh"]["min_spacing"] = resolved_min_spacing(scene);
  // The default profile is left out, so that states saved before the key existed still match.
  if (scene.growth.smoothing_profile == GrowthSmoothingProfile::Rational)
    model["growth"].erase("smoothing_profile");
  return fnv1a_64(model.dump());
}

std::vector<std::string> scene_keys() {
  std::vector<std::string> keys;
  for (const Field& field : kFields) keys.emplace_back(field.key);
  return keys;
}

double thickness_at_radius(const ThicknessProfile& profile, double r, double radius) {
  struct Evaluate {
    double r, radius;
    double operator()(const ConstantThickness& p) const { return p.value; }
    double operator()(const LinearThickness& p) const {
      // Clamped so that quadrature points a rounding error outside the rim keep h > 0.
      const double t = std::clamp(r / radius, 0.0, 1.0);
      return p.center + (p.rim - p.center) * t;
    }
  };
  return std::visit(Evaluate{r, radius}, profile);
}

double resolved_min_spacing(const Scene& scene) {
  if (scene.mesh.min_spacing) return *scene.mesh.min_spacing;
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  return (graded_by_size(scene.mesh.family) ? 0.25 : 0.5) * h;
}

double resolved_exclusion_radius(const Scene& scene) {
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  const double distance = scene.physics.contact_distance.value_or(h);
  if (!scene.physics.contact_exclusion_radius) return kApexExclusionThicknesses * h;
  const double radius = *scene.physics.contact_exclusion_radius;
  if (!(radius >= distance))
    fail("physics.contact_exclusion_radius = " + format(radius) +
         " must be >= the contact distance " + format(distance) +
         " (physics.contact_distance, or the thickness at the centre if auto)");
  return radius;
}

ThicknessField scene_thickness_field(const Scene& scene) {
  return [profile = scene.thickness, radius = scene.geometry.radius](const Eigen::Vector3d& X) {
    return thickness_at_radius(profile, std::hypot(X.x(), X.y()), radius);
  };
}

std::string mesh_family_name(MeshFamily family) { return enum_name(kMeshFamilyNames, family); }

bool graded_by_size(MeshFamily family) {
  return family == MeshFamily::Rings || family == MeshFamily::Gmsh ||
         family == MeshFamily::GmshD4;
}

std::string study_kind_name(StudyKind kind) { return enum_name(kStudyKindNames, kind); }

TriangleMesh scene_mesh(const Scene& scene) {
  validate_scene(scene);
  const SceneMesh& m = scene.mesh;
  const bool ring = scene.geometry.shape == SceneShape::Ring;
  const double size_max = m.size_max.value_or(std::numeric_limits<double>::infinity());
  switch (m.family) {
    case MeshFamily::Lattice:
      break;
    case MeshFamily::Rings: {
      RingDiscMeshOptions options;
      options.radius = scene.geometry.radius;
      options.inner_radius = ring ? scene.geometry.inner_radius : 0.0;
      options.size_slope = m.size_slope;
      options.size_floor = resolved_min_spacing(scene);
      options.size_max = size_max;
      return make_ring_disc_mesh(options);
    }
    case MeshFamily::Gmsh:
    case MeshFamily::GmshD4: {
      GmshDiscMeshOptions options;
      options.dihedral_symmetry = m.family == MeshFamily::GmshD4;
      options.radius = scene.geometry.radius;
      options.inner_radius = ring ? scene.geometry.inner_radius : 0.0;
      options.size_slope = m.size_slope;
      options.size_floor = resolved_min_spacing(scene);
      options.size_max = size_max;
      return make_gmsh_disc_mesh(options);
    }
    case MeshFamily::File: {
      const std::filesystem::path path(m.file);
      if (path.extension() == ".msh") return add_ghost_layer(read_msh(m.file));
      if (path.extension() == ".obj") return read_obj(m.file);
      throw std::invalid_argument("mesh.file = '" + m.file +
                                  "': the mesh format is told by the extension, .msh or .obj");
    }
  }
  if (ring) {
    AnnulusMeshOptions options;
    options.inner_radius = scene.geometry.inner_radius;
    options.outer_radius = scene.geometry.radius;
    options.radial_layers = m.radial_layers;
    options.center = Eigen::Vector2d::Zero();
    return make_annulus_mesh(options);
  }
  DiscMeshOptions options;
  options.radius = scene.geometry.radius;
  options.rings = m.rings;
  options.grading_exponent = m.grading_exponent;
  options.min_spacing = resolved_min_spacing(scene);
  options.center = Eigen::Vector2d::Zero();
  options.layout = DiscLayout::Conformal;
  return make_disc_mesh(options);
}

ShellModelSettings scene_model_settings(const Scene& scene) {
  validate_scene(scene);
  ShellModelSettings settings;
  settings.material = scene.material;
  settings.thickness = scene_thickness_field(scene);
  settings.quadrature_degree = scene.mesh.quadrature_degree;
  settings.growth.center = Eigen::Vector3d(scene.growth.center.x(), scene.growth.center.y(), 0.0);
  settings.growth.smoothing_radius = scene.growth.smoothing_radius;
  settings.growth.smoothing_profile = scene.growth.smoothing_profile;
  return settings;
}

}  // namespace growshell
