// apex_strain: the elastic stretches near the cone's apex along a traced branch.
//
// Reads a study's output directory (scene.json and states/) and, for every saved state in
// [--from, --to], evaluates at each quadrature point within --radius of the growth centre the
// principal elastic stretches: the square roots of the eigenvalues of abar^-1 a, with a the
// current metric and abar the grown target metric at the state's phi_e. Prints and writes
// DIR/apex_strain.csv: phi_e, then the smallest principal stretch over those points with the
// other stretch there and its reference radius, then the largest with the same. The
// Saint Venant-Kirchhoff law loses ellipticity when a stretch falls below about 0.65 (the other
// near 1, nu = 0.3; docs/shell_energy.md), which is what this lets one check at an instability.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "examples/support/directory_command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/saved_point.hpp"
#include "libshell/analysis/elastic_stretches.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/scene.hpp"
#include "studies/atomic_file.hpp"

namespace growshell {
namespace {

const char* kUsage = R"(usage: apex_strain RUN_DIR [--radius R] [--from P] [--to Q]
  --radius R  quadrature points within R (m) of the growth centre (default 2 h)
  --from P    first excess angle (default 0)
  --to Q      last excess angle (default: the last state)
Writes RUN_DIR/apex_strain.csv: phi_e, min_stretch, min_partner, min_radius, max_stretch,
max_partner, max_radius (principal elastic stretches of abar^-1 a near the apex).
)";

int run(const std::string& dir, examples::CommandLine& cl) {
  const Scene scene = read_scene(dir + "/scene.json");
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  const double radius = cl.number("--radius", 2.0 * h);
  const double from = cl.number("--from", 0.0);
  const double to = cl.number("--to", std::numeric_limits<double>::infinity());
  cl.reject_unknown();
  if (!(radius > 0.0)) throw std::invalid_argument("--radius must be > 0");
  if (!(from <= to)) throw std::invalid_argument("--from must not exceed --to");

  const ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  std::ostringstream csv;
  csv << std::setprecision(10)
      << "phi_e,min_stretch,min_partner,min_radius,max_stretch,max_partner,max_radius\n";
  int rows = 0;
  for (const auto& file : examples::saved_point_files(dir)) {
    const BranchSample s = examples::load_point(file.string(), model.dimension());
    if (s.parameter < from || s.parameter > to) continue;
    PointStretches low{0.0, std::numeric_limits<double>::infinity(), 0.0}, high;
    for (const PointStretches& p : elastic_stretches(model, s.x, s.parameter, radius)) {
      if (p.smaller < low.smaller) low = p;
      if (p.larger > high.larger) high = p;
    }
    csv << s.parameter << ',' << low.smaller << ',' << low.larger << ',' << low.radius << ','
        << high.larger << ',' << high.smaller << ',' << high.radius << '\n';
    std::printf("%9.5f  min %.4f (other %.4f) at r = %.2e   max %.4f (other %.4f) at r = %.2e\n",
                s.parameter, low.smaller, low.larger, low.radius, high.larger, high.smaller,
                high.radius);
    ++rows;
  }
  const std::string path = dir + "/apex_strain.csv";
  write_file_atomically(path, csv.str());
  std::printf("# wrote %s (%d states)\n", path.c_str(), rows);
  return 0;
}

}  // namespace
}  // namespace growshell

int main(int argc, char** argv) {
  return growshell::examples::directory_main("apex_strain", growshell::kUsage, growshell::run, argc, argv);
}
