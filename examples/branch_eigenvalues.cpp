// branch_eigenvalues: the lowest eigenvalues along a traced branch.
//
// Reads a trace_disc or study output directory (scene.json and states/) and, for every saved
// state in [--from, --to], computes the --count lowest eigenvalues of H v = lambda M v, with H
// the Hessian less six rigid-motion pins (the trace's, on the mesh's mirror axes, or pins chosen
// on the state where those have lost their lever arm) and M the lumped reference area of the
// control points: lambda = d2E / integral |dx|^2 dA in N/m^3, a property of the sheet that
// converges under mesh refinement (mass_normalized_eigenpairs.hpp). On a disc the lowest is
// usually the nearly free turn of the fold pattern about the axis (zero on a perfect disc); the
// others are the softest shape modes, whose sign decides stability. For each mode it also gives
// where on the sheet it is largest, how much of it is rigid motion, its parities under the
// mesh's mirrors x -> -x and y -> -y (both +1 for the B2 and A modes of the two-fold cone, both
// -1 for B1 and for the turn, mixed for the E pair) and its overlap with the turn. Writes
// DIR/eigenvalues.csv (atomically, studies/atomic_file.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Cholesky>

#include "core/objective_at_parameter.hpp"
#include "examples/support/directory_command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/mode_symmetry.hpp"
#include "examples/support/saved_point.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/mesh/rigid_motion.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/mass_normalized_eigenpairs.hpp"
#include "studies/atomic_file.hpp"
#include "studies/pattern_rotation.hpp"
#include "studies/turn_free_stability_index.hpp"

namespace {

using namespace growshell;

// Above this pinned_rigid_motion_condition the trace's pins are replaced by pins chosen on the
// state, as the study's stability index does.
constexpr double kMaxPinCondition = TurnFreeStabilityIndex::kDefaultMaxPinCondition;

const char* kUsage = R"(usage: branch_eigenvalues RUN_DIR [options]
  --count K     number of lowest eigenvalues per state (default 4)
  --from P      first excess angle (default 0)
  --to Q        last excess angle (default: the last state)
  --at P1,P2,.. instead of a range, the saved state nearest each of these excess angles
  --out FILE    where to write the table (default RUN_DIR/eigenvalues.csv); an existing file
                is refused, so no earlier table is lost
Writes one row per state:
  phi_e
  lambda_1..K           N/m^3: the Hessian's second variation per integral of |dx|^2 over the
                        reference sheet, with six rigid-motion pins removed: the trace's, or
                        pins chosen on the state where those hold its rigid motions with a
                        condition number above 100
  peak_radius_1..K      reference radius (m) of the sheet vertex where the mode's displacement is
                        largest: at the apex core or out at the folds
  parity_x_1..K, parity_y_1..K, parity_s4_1..K
                        <v, S v>_M / <v, v>_M, v less its rigid part, for the mesh's mirror S
                        about x = 0 and y = 0, and for S4 (the quarter turn about z followed by
                        z -> -z): +1 symmetric, -1 antisymmetric, nan when the mesh lacks that
                        symmetry (the unsymmetric Gmsh mesh). They classify the modes of a state
                        with the mesh's symmetry (traced with --symmetric-subspace 1): B2 is
                        (+1, +1, -1), A1 (+1, +1, +1), the E pair has mixed mirror parities
  elastic_fraction_1..K |v - rigid part of v|_M / |v|_M: near 0 for a rigid motion that the pins
                        barely hold, a pinning artefact, not a mode of the sheet
  turn_overlap_1..K     |<v, t>_M| / (|v|_M |t|_M), both less their rigid parts, t the turn of the
                        fold pattern over the material (studies/pattern_rotation.hpp): 1 for the
                        turn itself, 0 for a mode orthogonal to it
  ghost_fraction_1..K   the part of |v|_M^2 on the ghost layer (the control points outside the
                        sheet that shape its free edge): near 1 for a mode of the edge's
                        representation rather than of the sheet
  pin_condition         how well the trace's pins hold the rigid motions of the state
                        (pinned_rigid_motion_condition): large when they barely do
)";

// A symmetry of the reference mesh (examples/support/mode_symmetry.hpp), or nothing when the
// mesh lacks it (the unsymmetric Gmsh mesh).
template <class Find>
std::optional<LinearVertexSymmetry> if_the_mesh_has(Find find) {
  try {
    return find();
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// v less its M-orthogonal projection onto the rigid motions of the state x (translations, and
// rotations about the point c): the pins add a rigid velocity to every mode so that it vanishes
// at them, and that part does not share the mode's mirror parity.
Eigen::VectorXd without_rigid_motion(const Eigen::VectorXd& v, const Eigen::VectorXd& x,
                                     const Eigen::Vector3d& c, const Eigen::VectorXd& m) {
  const Eigen::MatrixXd rigid = rigid_velocity_fields(x, c);
  const Eigen::MatrixXd weighted = m.asDiagonal() * rigid;
  const Eigen::VectorXd coefficients = (rigid.transpose() * weighted).ldlt().solve(weighted.transpose() * v);
  return v - rigid * coefficients;
}

// |<a, b>_M| / (|a|_M |b|_M) with the per-dof masses m; nan when either vector vanishes.
double mass_weighted_cosine(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                            const Eigen::VectorXd& m) {
  const double norms = std::sqrt(a.cwiseProduct(m).dot(a) * b.cwiseProduct(m).dot(b));
  if (!(norms > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return std::abs(a.cwiseProduct(m).dot(b)) / norms;
}

int run(const std::string& dir, examples::CommandLine& cl) {
  const int count = cl.integer("--count", 4);
  const double from = cl.number("--from", 0.0);
  const double to = cl.number("--to", std::numeric_limits<double>::infinity());
  const std::vector<double> at =
      cl.text("--at", "").empty() ? std::vector<double>{} : cl.number_list("--at", "");
  const std::string path = cl.text("--out", dir + "/eigenvalues.csv");
  cl.reject_unknown();
  if (std::filesystem::exists(path))
    throw std::invalid_argument(path + " exists: name another --out, or move it away");
  if (count < 1) throw std::invalid_argument("--count must be >= 1");
  if (!(from <= to)) throw std::invalid_argument("--from must not exceed --to");

  const Scene scene = read_scene(dir + "/scene.json");
  ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::MatrixX3d P =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
  const auto pinned =
      mirror_axis_pinned_dofs(P, model.sheet_vertices(), model.settings().growth.center);
  // The lumped reference area of each control point, for each of its three coordinates.
  const Eigen::VectorXd dof_mass =
      model.reference().vertex_areas().replicate(1, 3).transpose().reshaped();

  std::ostringstream csv;
  csv << std::setprecision(10) << "phi_e";
  for (int k = 1; k <= count; ++k) csv << ",lambda_" << k;
  for (int k = 1; k <= count; ++k) csv << ",peak_radius_" << k;
  for (int k = 1; k <= count; ++k) csv << ",parity_x_" << k;
  for (int k = 1; k <= count; ++k) csv << ",parity_y_" << k;
  for (int k = 1; k <= count; ++k) csv << ",parity_s4_" << k;
  for (int k = 1; k <= count; ++k) csv << ",elastic_fraction_" << k;
  for (int k = 1; k <= count; ++k) csv << ",turn_overlap_" << k;
  for (int k = 1; k <= count; ++k) csv << ",ghost_fraction_" << k;
  csv << ",pin_condition\n";
  // The columns parity_x, parity_y and parity_s4, and the tag each has on the screen.
  const std::array<std::optional<LinearVertexSymmetry>, 3> symmetries = {
      if_the_mesh_has([&] { return examples::reference_mirror(P, 0); }),
      if_the_mesh_has([&] { return examples::reference_mirror(P, 1); }),
      if_the_mesh_has([&] { return examples::reference_s4(P); })};
  const std::array<const char*, 3> tags = {"", "", "s4"};
  int rows = 0;
  const auto analyse = [&](const BranchSample& s) {
    ObjectiveAtParameter energy(model, s.parameter);
    EigenpairOptions options;
    options.count = count;
    // The trace's pins, unless the state has carried them off their lever arm (a pinned rim
    // vertex moved next to the axis): a rigid motion they barely hold would be a spurious soft
    // mode.
    const auto state_rows =
        Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(s.x.data(), s.x.size() / 3, 3);
    const double condition = pinned_rigid_motion_condition(state_rows, pinned);
    const std::vector<Eigen::Index> pins = analysis_pins(model, s.x, pinned, kMaxPinCondition);
    const Eigenpairs pairs = lowest_mass_normalized_eigenpairs(energy, s.x, dof_mass, pins, options);
    csv << s.parameter;
    std::printf("%9.5f", s.parameter);
    for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
      csv << ',' << pairs.values(k);
      std::printf(" %12.5e", pairs.values(k));
    }
    for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
      const double radius = examples::mode_peak_radius(model, pairs.vectors.col(k));
      csv << ',' << radius;
      std::printf(" r=%.3f", radius);
    }
    std::vector<Eigen::VectorXd> elastic;
    for (Eigen::Index k = 0; k < pairs.values.size(); ++k)
      elastic.push_back(without_rigid_motion(pairs.vectors.col(k), s.x, model.settings().growth.center, dof_mass));
    for (std::size_t j = 0; j < symmetries.size(); ++j) {
      for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
        const double parity =
            symmetries[j] ? examples::mode_parity(elastic[static_cast<std::size_t>(k)],
                                                  model.reference().vertex_areas(), *symmetries[j])
                          : std::numeric_limits<double>::quiet_NaN();
        csv << ',' << parity;
        std::printf(" %s%+.2f", tags[j], parity);
      }
    }
    for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
      const Eigen::VectorXd& e = elastic[static_cast<std::size_t>(k)];
      const Eigen::VectorXd& v = pairs.vectors.col(k);
      const double fraction = std::sqrt(e.cwiseProduct(dof_mass).dot(e) / v.cwiseProduct(dof_mass).dot(v));
      csv << ',' << fraction;
      std::printf(" e=%.3f", fraction);
    }
    const Eigen::VectorXd turn = without_rigid_motion(pattern_rotation(model, s.x, pins), s.x,
                                                      model.settings().growth.center, dof_mass);
    for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
      const double overlap = mass_weighted_cosine(elastic[static_cast<std::size_t>(k)], turn, dof_mass);
      csv << ',' << overlap;
      std::printf(" t=%.3f", overlap);
    }
    for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
      const Eigen::VectorXd& v = pairs.vectors.col(k);
      double sheet_part = 0.0;
      for (const int vertex : model.sheet_vertices())
        sheet_part += v.segment<3>(3 * vertex).cwiseProduct(dof_mass.segment<3>(3 * vertex)).dot(v.segment<3>(3 * vertex));
      const double fraction = 1.0 - sheet_part / v.cwiseProduct(dof_mass).dot(v);
      csv << ',' << fraction;
      std::printf(" g=%.3f", fraction);
    }
    csv << ',' << condition << '\n';
    std::printf(" pins %.3g\n", condition);
    ++rows;
  };
  // The saved states in [from, to], one at a time, or those nearest the excess angles of --at.
  if (at.empty()) {
    for (const auto& file : examples::saved_point_files(dir)) {
      const BranchSample s = examples::load_point(file.string(), model.dimension());
      if (s.parameter >= from && s.parameter <= to) analyse(s);
    }
  } else {
    for (const BranchSample& s : nearest_saved_states(dir, at, model.dimension())) analyse(s);
  }
  write_file_atomically(path, csv.str());
  std::printf("# wrote %s (%d states)\n", path.c_str(), rows);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::directory_main("branch_eigenvalues", kUsage, run, argc, argv);
}
