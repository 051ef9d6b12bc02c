// branch_eigenvalues: the lowest eigenvalues along a traced branch.
//
// Reads a trace_disc output directory (scene.json and states/) and, for every saved state in
// [--from, --to], computes the --count lowest eigenvalues of the Hessian with the trace's rigid
// pins removed (N/m; the pins are trace_disc's, on the mesh's mirror axes). On a disc the
// lowest is the nearly free turn of the fold pattern about the axis (zero on a perfect disc);
// the next ones are the softest shape modes, whose sign decides stability. For each mode it also
// gives the reference radius where its displacement is largest. Writes DIR/eigenvalues.csv
// (written whole, then renamed into place).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "examples/support/directory_command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/saved_point.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"

namespace {

using namespace growshell;

const char* kUsage = R"(usage: branch_eigenvalues RUN_DIR [options]
  --count K     number of lowest eigenvalues per state (default 4)
  --from P      first excess angle (default 0)
  --to Q        last excess angle (default: the last state)
Writes RUN_DIR/eigenvalues.csv: phi_e, lambda_1..K (N/m, Hessian with trace_disc's rigid pins
removed), and peak_radius_1..K: the reference radius (m) of the sheet vertex where each mode's
displacement is largest (where on the sheet the mode lives: at the apex core or out at the folds).
)";

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

  std::ostringstream csv;
  csv << std::setprecision(10) << "phi_e";
  for (int k = 1; k <= count; ++k) csv << ",lambda_" << k;
  for (int k = 1; k <= count; ++k) csv << ",peak_radius_" << k;
  csv << '\n';
  int rows = 0;
  for (const auto& file : files) {
    const BranchSample s = examples::load_point(file.string(), model.dimension());
    if (s.parameter < from || s.parameter > to) continue;
    model.set_excess_angle(s.parameter);
    EigenpairOptions options;
    options.count = count;
    const Eigenpairs pairs = lowest_eigenpairs(model, s.x, pinned, options);
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
    csv << '\n';
    std::printf("\n");
    ++rows;
  }
  const std::string path = dir + "/eigenvalues.csv";
  const std::string partial = path + ".partial";
  std::ofstream(partial) << csv.str();
  std::filesystem::rename(partial, path);
  std::printf("# wrote %s (%d states)\n", path.c_str(), rows);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("branch_eigenvalues", run, argc, argv);
}
