// cone_mode_sectors: the softest modes of a symmetric two-fold cone, one symmetry class at a
// time.
//
// The symmetric n = 2 cone has the group D2d: the mirrors x -> -x and y -> -y of its folds and
// S4, the quarter turn about z followed by z -> -z. Its second variation does not couple modes
// of different parities, so its eigenproblem H v = lambda M v (M the lumped reference area, as
// branch_eigenvalues) splits into sectors: the modes even under both mirrors (A1, which keeps
// S4, and B2, which breaks it: the up-folds close while the down-folds open), the modes odd
// under both (A2, the turn of the pattern about the axis, and B1), and the modes even under one
// mirror and odd under the other (the E pairs). Each sector is a symmetry class of the group of
// the two mirrors (VertexSymmetryGroup::class_basis, the character the sector's parities); the
// rigid motions in the sector are pinned there (subspace_rigid_motions), so no pin mixes the
// classes, as six pins on the whole sheet do. Within the even-even and odd-odd
// sectors, the S4 parity of each mode tells A1 from B2 and A2 from B1. These are the classes of
// the h -> 0 cone's eigenvalues in ../shared/docs/physics.md, "Stability of the h -> 0 cone".
//
// Reads a cone_branch study's directory traced in the mirror subspace of a mesh with the cone's
// symmetry (rings, gmsh_d4): scene.json and states/. Writes OUT (default
// RUN_DIR/mode_sectors.csv; an existing file is refused) atomically, one row per mode:
//   phi_e, sector (even_even, odd_odd, even_odd), class (A1, B2, A2, B1, E, or ? when the S4
//   parity is neither near +1 nor near -1), lambda (N/m^3), s4_parity, peak_radius (m), and
//   lambda_pinned, the k-th eigenvalue with the sector's rigid motions pinned, nearer zero than
//   the sheet's (solvers/stability/rigid_free_eigenpairs.hpp).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "examples/support/directory_command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/mode_symmetry.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/mesh/rigid_motion.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"
#include "solvers/stability/mass_normalized_eigenpairs.hpp"
#include "solvers/stability/rigid_free_eigenpairs.hpp"
#include "solvers/stability/subspace_hessian_projection.hpp"
#include "solvers/stability/subspace_rigid_motions.hpp"
#include "studies/atomic_file.hpp"
#include "studies/saved_state.hpp"

namespace {

using namespace growshell;

const char* kUsage = R"(usage: cone_mode_sectors RUN_DIR [options]
  --at P1,P2,..  the saved states nearest these excess angles (required)
  --count K      modes per sector (default 3)
  --out FILE     the table (default RUN_DIR/mode_sectors.csv); an existing file is refused
Writes one row per mode: phi_e, sector, class, lambda (N/m^3), s4_parity, peak_radius (m),
lambda_pinned (N/m^3, with the sector's rigid motions pinned: below lambda).
RUN_DIR: a cone_branch study traced in the mirror subspace of a mesh with the cone's
symmetry (mesh.family rings or gmsh_d4).
)";

struct Sector {
  const char* name;
  int sign_x;  // parity under x -> -x
  int sign_y;  // parity under y -> -y
};

std::string mode_class(const Sector& sector, double parity) {
  if (sector.sign_x != sector.sign_y) return "E";
  if (parity > 0.9) return sector.sign_x > 0 ? "A1" : "A2";
  if (parity < -0.9) return sector.sign_x > 0 ? "B2" : "B1";
  return "?";
}

int run(const std::string& dir, examples::CommandLine& cl) {
  if (cl.text("--at", "").empty()) throw std::invalid_argument("--at is required (excess angles)");
  const std::vector<double> at = cl.number_list("--at", "");
  const int count = cl.integer("--count", 3);
  const std::string path = cl.text("--out", dir + "/mode_sectors.csv");
  cl.reject_unknown();
  if (count < 1) throw std::invalid_argument("--count must be >= 1");
  if (std::filesystem::exists(path))
    throw std::invalid_argument(path + " exists: name another --out, or move it away");

  const Scene scene = read_scene(dir + "/scene.json");
  ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::MatrixX3d P =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
  const Eigen::VectorXd& vertex_mass = model.reference().vertex_areas();
  const Eigen::VectorXd dof_mass = vertex_mass.replicate(1, 3).transpose().reshaped();
  const LinearVertexSymmetry s4 = examples::reference_s4(P);
  // Each sector's basis, once: the symmetry class of the mirrors' group with the sector's
  // parities. The even-even one is the cone's own mirror subspace, the frame the states are
  // brought into.
  const double tolerance = 1e-9 * P.cwiseAbs().maxCoeff();
  const SymmetricSubspace frame(P.rows(), {mirror_symmetry(P, 0, tolerance),
                                           mirror_symmetry(P, 1, tolerance)});
  struct SectorSpace {
    Sector sector;
    Eigen::SparseMatrix<double> basis;
    SubspaceHessianProjection projection;  ///< Q^T H Q of the model's Hessian
  };
  const Eigen::SparseMatrix<double> pattern = model.hessian_pattern();
  std::vector<SectorSpace> sectors;
  for (const Sector& sector : {Sector{"even_even", 1, 1}, Sector{"odd_odd", -1, -1},
                               Sector{"even_odd", 1, -1}}) {
    Eigen::SparseMatrix<double> basis = frame.group().class_basis({sector.sign_x, sector.sign_y});
    SubspaceHessianProjection projection(pattern, basis);
    sectors.push_back({sector, std::move(basis), std::move(projection)});
  }

  // The saved state nearest each excess angle asked for, each once.
  const std::vector<BranchSample> samples = nearest_saved_states(dir, at, model.dimension());
  if (samples.empty()) throw std::invalid_argument(dir + "/states holds no saved state");

  std::ostringstream csv;
  csv << std::setprecision(10) << "phi_e,sector,class,lambda,s4_parity,peak_radius,lambda_pinned\n";
  for (const BranchSample& sample : samples) {
    // Into the frame whose coordinate planes are the cone's mirrors.
    const Eigen::VectorXd x = frame.aligning_motion(sample.x).apply(sample.x);
    const double asymmetry = frame.asymmetry(x);
    // The sectors decouple only for a state with both mirrors (a trace in the mirror subspace
    // has them to rounding).
    if (asymmetry > 1e-6 * scene.geometry.radius) {
      std::ostringstream why;
      why << "the state at phi_e = " << sample.parameter << " is " << asymmetry
          << " m from its mirror images: trace the cone in the mirror subspace "
             "(study.symmetric_subspace) on a rings or gmsh_d4 mesh";
      throw std::invalid_argument(why.str());
    }
    ObjectiveAtParameter energy(model, sample.parameter);
    Eigen::SparseMatrix<double> upper = energy.hessian_pattern();
    energy.evaluate(x, nullptr, &upper);
    std::printf("%9.5f  asymmetry %.2e m\n", sample.parameter, asymmetry);
    for (const auto& [sector, Q, projection] : sectors) {
      Eigen::SparseMatrix<double> reduced_upper;
      projection.project(upper, reduced_upper);
      // diag(Q^T M Q): Q's columns are normalised signed sums over orbits of dofs of equal
      // mass, so Q^T M Q is diagonal.
      const Eigen::VectorXd reduced_mass = Q.cwiseAbs2().transpose() * dof_mass;
      // The pins hold the sector's rigid motions; the sheet's eigenpairs are those free of
      // rigid motion (rigid_free_eigenpairs), found on the lowest count + 10 pinned modes (on
      // the trace_disc test's cone the lowest B2 is the same to 1e-5 from count + 8 on, and
      // 0.2 % high from count + 7).
      EigenpairOptions options;
      options.count = count + 10;
      const Eigenpairs pinned = lowest_mass_normalized_eigenpairs_of_matrix(
          reduced_upper, reduced_mass, subspace_rigid_motions(Q, x).pins, options);
      const RigidFreeEigenpairs ritz = rigid_free_eigenpairs(
          pinned, Q.transpose() * rigid_velocity_fields(x), reduced_mass, count);
      for (Eigen::Index k = 0; k < ritz.values.size(); ++k) {
        const Eigen::VectorXd v = Q * ritz.vectors.col(k);
        const double parity = examples::mode_parity(v, vertex_mass, s4);
        const double radius = examples::mode_peak_radius(model, v);
        const std::string cls = mode_class(sector, parity);
        csv << sample.parameter << ',' << sector.name << ',' << cls << ',' << ritz.values(k) << ','
            << parity << ',' << radius << ',' << pinned.values(k) << '\n';
        std::printf("  %-9s %-2s %12.5e  (pinned %12.5e)  S4 %+.3f  peak r %.3f\n", sector.name,
                    cls.c_str(), ritz.values(k), pinned.values(k), parity, radius);
      }
    }
  }
  write_file_atomically(path, csv.str());
  std::printf("# wrote %s\n", path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::directory_main("cone_mode_sectors", kUsage, run, argc, argv);
}
