// branch_eigenvalues: the lowest eigenvalues along a traced branch.
//
// Reads a trace_disc output directory (scene.json and states/) and, for every saved state in
// [--from, --to], computes the --count lowest eigenvalues of H v = lambda M v, with H the
// Hessian, the trace's rigid pins removed (trace_disc's, on the mesh's mirror axes), and M the
// lumped reference area of the control points: lambda = d2E / integral |dx|^2 dA in N/m^3, a
// property of the sheet that converges under mesh refinement (mass_normalized_eigenpairs.hpp).
// On a disc the
// lowest is the nearly free turn of the fold pattern about the axis (zero on a perfect disc);
// the next ones are the softest shape modes, whose sign decides stability. For each mode it also
// gives the reference radius where its displacement is largest and, on a mesh with the mirrors
// x -> -x and y -> -y, its parity under each (the symmetry class: both +1 for the B2 and A
// modes of the two-fold cone, both -1 for B1, mixed for the E pair). Writes DIR/eigenvalues.csv
// (atomically, studies/atomic_file.hpp).
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

#include "examples/support/directory_command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/saved_point.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/mass_normalized_eigenpairs.hpp"
#include "studies/atomic_file.hpp"

namespace {

using namespace growshell;

const char* kUsage = R"(usage: branch_eigenvalues RUN_DIR [options]
  --count K     number of lowest eigenvalues per state (default 4)
  --from P      first excess angle (default 0)
  --to Q        last excess angle (default: the last state)
Writes RUN_DIR/eigenvalues.csv: phi_e, lambda_1..K (N/m^3: the Hessian's second variation per
integral of |dx|^2 over the reference sheet, trace_disc's rigid pins removed), and
peak_radius_1..K: the reference radius (m) of the sheet vertex where each mode's
displacement is largest (where on the sheet the mode lives: at the apex core or out at the folds),
and parity_x_1..K, parity_y_1..K: <v, S v>_M / <v, v>_M for the mesh's mirror S about x = 0 and
y = 0 (+1 symmetric, -1 antisymmetric; nan when the mesh lacks that mirror, as a Gmsh mesh does).
They classify the modes of a state that has the mesh's mirrors (traced with --symmetric-subspace
1); a state whose fold pattern has turned about the axis mixes them.
)";

// The mirror of the reference mesh about x = 0 (axis 0) or y = 0 (axis 1), or nothing when the
// mesh lacks it.
std::optional<VertexSymmetry> mesh_mirror(const Eigen::MatrixX3d& positions, int axis) {
  try {
    return mirror_symmetry(positions, axis, 1e-9 * positions.cwiseAbs().maxCoeff());
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// <v, S v>_M / <v, v>_M for displacement v (3 per vertex) and lumped vertex masses m.
double mirror_parity(const Eigen::VectorXd& v, const Eigen::VectorXd& m,
                     const std::optional<VertexSymmetry>& mirror) {
  if (!mirror) return std::numeric_limits<double>::quiet_NaN();
  double overlap = 0.0, norm = 0.0;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    const auto image = static_cast<Eigen::Index>(mirror->image[static_cast<std::size_t>(i)]);
    overlap += m(i) * v.segment<3>(3 * i).dot(mirror->signs.cwiseProduct(v.segment<3>(3 * image)));
    norm += m(i) * v.segment<3>(3 * i).squaredNorm();
  }
  return overlap / norm;
}

int run(int argc, char** argv) {
  int exit_code = 0;
  auto command_line = examples::read_directory_command_line(argc, argv, kUsage, &exit_code);
  if (!command_line) return exit_code;
  const std::string dir = command_line->directory;
  examples::CommandLine& cl = command_line->options;
  const int count = cl.integer("--count", 4);
  const double from = cl.number("--from", 0.0);
  const double to = cl.number("--to", std::numeric_limits<double>::infinity());
  cl.reject_unknown();
  if (count < 1) throw std::invalid_argument("--count must be >= 1");
  if (!(from <= to)) throw std::invalid_argument("--from must not exceed --to");

  const Scene scene = read_scene(dir + "/scene.json");
  ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::MatrixX3d P =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
  const auto pinned =
      mirror_axis_pinned_dofs(P, model.sheet_vertices(), model.settings().growth.center);
  const std::vector<std::filesystem::path> files = examples::saved_point_files(dir);
  // The lumped reference area of each control point, for each of its three coordinates.
  const Eigen::VectorXd dof_mass =
      model.reference().vertex_areas().replicate(1, 3).transpose().reshaped();

  std::ostringstream csv;
  csv << std::setprecision(10) << "phi_e";
  for (int k = 1; k <= count; ++k) csv << ",lambda_" << k;
  for (int k = 1; k <= count; ++k) csv << ",peak_radius_" << k;
  for (int k = 1; k <= count; ++k) csv << ",parity_x_" << k;
  for (int k = 1; k <= count; ++k) csv << ",parity_y_" << k;
  csv << '\n';
  const std::array<std::optional<VertexSymmetry>, 2> mirrors = {mesh_mirror(P, 0), mesh_mirror(P, 1)};
  int rows = 0;
  for (const auto& file : files) {
    const BranchSample s = examples::load_point(file.string(), model.dimension());
    if (s.parameter < from || s.parameter > to) continue;
    model.set_excess_angle(s.parameter);
    EigenpairOptions options;
    options.count = count;
    const Eigenpairs pairs = lowest_mass_normalized_eigenpairs(model, s.x, dof_mass, pinned, options);
    csv << s.parameter;
    std::printf("%9.5f", s.parameter);
    for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
      csv << ',' << pairs.values(k);
      std::printf(" %12.5e", pairs.values(k));
    }
    for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
      double peak = 0.0, radius = 0.0;
      for (const int v : model.sheet_vertices()) {
        const double a = pairs.vectors.col(k).segment<3>(3 * v).norm();
        if (a > peak) {
          peak = a;
          radius = (X.segment<2>(3 * v) - model.settings().growth.center.head<2>()).norm();
        }
      }
      csv << ',' << radius;
      std::printf(" r=%.3f", radius);
    }
    for (const auto& mirror : mirrors) {
      for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
        const double parity = mirror_parity(pairs.vectors.col(k), model.reference().vertex_areas(), mirror);
        csv << ',' << parity;
        std::printf(" %+.2f", parity);
      }
    }
    csv << '\n';
    std::printf("\n");
    ++rows;
  }
  const std::string path = dir + "/eigenvalues.csv";
  write_file_atomically(path, csv.str());
  std::printf("# wrote %s (%d states)\n", path.c_str(), rows);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("branch_eigenvalues", run, argc, argv);
}
