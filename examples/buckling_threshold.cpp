// buckling_threshold: the excess angles at which the flat disc (or ring) loses stability to
// the n = 2, 3, ... fold modes, for a list of thicknesses and mesh resolutions (size slopes of
// the rings and gmsh families, rings of the lattice family).
//
// The flat branch is followed by pseudo-arclength continuation; each change of the negative
// eigenvalue count of the Hessian (a double branch point: the cos/sin pair of an n-fold mode)
// is located to 1e-8 in phi_e. Prints one line per (h, resolution) and writes a CSV.
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "examples/support/command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/scene_command_line.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace {

using namespace growshell;

int run(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  examples::CommandLine cl(argc, argv);
  if (cl.help()) {
    std::puts("usage: buckling_threshold [--h 0.04,0.02,0.01] [--mesh rings|gmsh|gmsh_d4|lattice]\n"
              "                          [--size-slope 0.25,0.1 | --rings 12,24] [--modes 2]\n"
              "                          [--inner-radius RI] [--out FILE.csv]\n"
              "  --size-slope: resolutions of the rings (default) and gmsh families;\n"
              "  --rings: of the lattice family (rings of a disc, radial layers of a ring)");
    return 0;
  }
  const std::vector<double> hs = cl.number_list("--h", "0.04,0.02,0.01");
  const std::string family = cl.text("--mesh", "rings");
  Scene base = default_scene();
  apply_override(base, "mesh.family", family);
  const bool lattice = base.mesh.family == MeshFamily::Lattice;
  for (const char* option : {"--size-slope", "--rings"}) {
    const std::string value = cl.text(option, "");
    if (!value.empty()) examples::require_family_reads(base, option, value);
  }
  const std::vector<double> resolutions =
      lattice ? cl.number_list("--rings", "12,24") : cl.number_list("--size-slope", "0.25,0.1");
  const int modes = cl.integer("--modes", 2);
  const std::string inner = cl.text("--inner-radius", "");
  const std::string out_path = cl.text("--out", "buckling_threshold.csv");
  cl.reject_unknown();
  std::ofstream csv(out_path);
  const char* resolution_name = lattice ? "rings" : "size_slope";
  csv << "h," << resolution_name << ",branch_point,phi_e,multiplicity,phi_e_over_h2\n";
  std::printf("%8s %10s %4s %14s %5s %12s\n", "h", resolution_name, "k", "phi_e", "mult",
              "phi_e/h^2");
  for (double h : hs) {
    for (double r : resolutions) {
      Scene scene = base;
      apply_override(scene, "thickness", std::to_string(h));
      if (!inner.empty()) {
        apply_override(scene, "geometry.shape", "ring");
        apply_override(scene, "geometry.inner_radius", inner);
      }
      std::ostringstream value;
      value << std::setprecision(17) << r;
      if (!lattice)
        apply_override(scene, "mesh.size_slope", value.str());
      else
        apply_override(scene, inner.empty() ? "mesh.rings" : "mesh.radial_layers",
                       std::to_string(static_cast<int>(r)));
      validate_scene(scene);
      ShellModel model(scene_mesh(scene), scene_model_settings(scene));
      const Eigen::VectorXd& X = model.reference_positions();
      const Eigen::MatrixX3d P =
          Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
      const auto pinned = rigid_motion_pinned_dofs(P, model.sheet_vertices());
      ArclengthOptions o;
      o.initial_step = 1e-4 * (h / 0.02) * (h / 0.02) * 10;
      o.max_step = 5 * o.initial_step;  // small enough to separate neighbouring branch points
      o.min_step = 1e-9;
      o.gradient_tolerance = 1e-9 * model.natural_force_scale();
      o.special_point_tolerance = 1e-8;
      o.max_special_points = modes;
      const BranchTrace trace = trace_branch(model, X, 0.0, +1, pinned, o);
      int k = 0;
      for (const SpecialPoint& sp : trace.special_points) {
        ++k;
        std::printf("%8.4f %10g %4d %14.9f %5d %12.4f\n", h, r, k, sp.parameter,
                    sp.multiplicity, sp.parameter / (h * h));
        csv << h << ',' << r << ',' << k << ',' << std::setprecision(12) << sp.parameter << ','
            << sp.multiplicity << ',' << sp.parameter / (h * h) << '\n';
      }
      if (static_cast<int>(trace.special_points.size()) < modes)
        std::printf("%8.4f %10g: only %zu branch points found (%s)\n", h, r,
                    trace.special_points.size(), trace.message.c_str());
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("buckling_threshold", run, argc, argv);
}
