// contact_profile: where and when a traced e-cone first touches itself, by radial band.
//
// Reads a trace_disc output directory (scene.json and states/) and, for every saved state,
// measures the smallest distance between non-neighbouring parts of the mid-surface restricted
// to samples at reference radius >= b for each band b (b = 0: the whole sheet), and whether
// the mid-surface passes through itself. On an n = 2 cone the two lobe tips close along a
// whole generator, so the gap grows with the radius (about 0.34 r per unit of phi_e short of
// contact for h -> 0): the band tells which part touches first. Writes DIR/contact_profile.csv
// and prints, per band, the phi_e where the gap first reaches the contact distance (linear
// interpolation between the two bracketing states) and the bracket of the first mid-surface
// crossing.
#include <cmath>
#include <cstdio>
#include <algorithm>
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
#include "libshell/analysis/core_radius.hpp"
#include "libshell/analysis/self_distance.hpp"
#include "libshell/analysis/self_intersection.hpp"
#include "libshell/io/scene.hpp"

namespace {

using namespace growshell;

const char* kUsage = R"(usage: contact_profile RUN_DIR [options]
  --bands B1,B2,...   reference radii (m) below which samples are ignored, one gap per band
                      (default 0,0.2,0.5,0.9)
  --distance D        contact distance (default: the scene's, i.e. the thickness h)
  --exclusion-radius R  pairs closer than R (m) in the reference are neighbours (default: the
                      scene's physics.contact_exclusion_radius, auto = 8 h). At a cone's
                      apex the closest pair straddles the apex at reference distance R, so the
                      band r >= 0 measures where that cut-off lies (docs/contact.md)
  --from P            skip states with phi_e < P (default 0)
  --samples N         limit-surface samples per element edge (default 2)
Writes RUN_DIR/contact_profile.csv: phi_e, then per band gap_<b> and radius_<b> (mean
reference radius of the closest pair), then crosses (1 if the mid-surface passes through
itself outside the first band).
)";

struct Row {
  double phi = 0.0;
  std::vector<double> gap, radius;
  bool crosses = false;
  double crossing_radius_a = 0.0, crossing_radius_b = 0.0;  // reference radii of the pair
};

int run(const std::string& dir, examples::CommandLine& cl) {
  const std::vector<double> bands = cl.number_list("--bands", "0,0.2,0.5,0.9");
  for (const double b : bands)
    if (!(b >= 0.0)) throw std::invalid_argument("--bands: a band starts at a radius >= 0");
  const double distance_option = cl.number("--distance", -1.0);
  const double from = cl.number("--from", 0.0);
  const int samples = cl.integer("--samples", 2);
  const std::string exclusion_text = cl.text("--exclusion-radius", "");
  cl.reject_unknown();

  Scene scene = read_scene(dir + "/scene.json");
  if (!exclusion_text.empty())
    apply_override(scene, "physics.contact_exclusion_radius", exclusion_text);
  validate_scene(scene);
  const double exclusion_radius = resolved_exclusion_radius(scene);
  ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  const double contact_distance =
      distance_option > 0.0 ? distance_option : scene.physics.contact_distance.value_or(h);
  const std::vector<std::filesystem::path> files = examples::saved_point_files(dir);

  std::ofstream csv(dir + "/contact_profile.csv");
  csv << std::setprecision(10) << "phi_e";
  for (const double b : bands) csv << ",gap_" << b << ",radius_" << b;
  csv << ",crosses\n";
  std::vector<Row> rows;
  for (const auto& file : files) {
    const BranchSample s = examples::load_point(file.string(), model.dimension());
    if (s.parameter < from) continue;
    Row row;
    row.phi = s.parameter;
    for (const double b : bands) {
      SelfDistanceOptions o;
      o.exclusion_radius = exclusion_radius;
      o.samples_per_edge = samples;
      o.core_radius = b;
      o.core_center = model.settings().growth.center;
      const SelfDistance d = smallest_self_distance(model, s.x, o);
      row.gap.push_back(d.distance);
      row.radius.push_back(0.5 * ((d.reference_a - o.core_center).head<2>().norm() +
                                  (d.reference_b - o.core_center).head<2>().norm()));
    }
    SelfIntersectionOptions so;
    so.exclusion_radius = exclusion_radius;
    so.samples_per_edge = samples;
    so.core_radius = bands.front();
    so.core_center = model.settings().growth.center;
    const SelfIntersection crossing = find_self_intersection(model, s.x, so);
    row.crosses = crossing.intersects;
    if (row.crosses) {
      row.crossing_radius_a = element_reference_radius(model, crossing.element_a, model.settings().growth.center);
      row.crossing_radius_b = element_reference_radius(model, crossing.element_b, model.settings().growth.center);
    }
    csv << row.phi;
    for (std::size_t k = 0; k < bands.size(); ++k) csv << ',' << row.gap[k] << ',' << row.radius[k];
    csv << ',' << (row.crosses ? 1 : 0) << '\n';
    csv.flush();
    rows.push_back(std::move(row));
  }
  std::printf("# %s: %zu states, contact distance %g, exclusion radius %g\n", dir.c_str(),
              rows.size(), contact_distance, exclusion_radius);
  for (std::size_t k = 0; k < bands.size(); ++k) {
    bool found = false;
    for (std::size_t i = 1; i < rows.size() && !found; ++i) {
      const double g0 = rows[i - 1].gap[k] - contact_distance, g1 = rows[i].gap[k] - contact_distance;
      if (g0 > 0.0 && g1 <= 0.0 && rows[i].phi > rows[i - 1].phi) {
        const double t = g0 / (g0 - g1);
        std::printf("band r >= %-5g gap = %g at phi_e = %.5f (states %.5f .. %.5f, at radius %.3f)\n",
                    bands[k], contact_distance, rows[i - 1].phi + t * (rows[i].phi - rows[i - 1].phi),
                    rows[i - 1].phi, rows[i].phi, rows[i].radius[k]);
        found = true;
      }
    }
    if (!found) std::printf("band r >= %-5g gap never reaches %g\n", bands[k], contact_distance);
  }
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (!rows[i - 1].crosses && rows[i].crosses) {
      std::printf("mid-surface first crosses itself between phi_e = %.5f and %.5f (elements at "
                  "reference radius %.3f and %.3f)\n",
                  rows[i - 1].phi, rows[i].phi, rows[i].crossing_radius_a, rows[i].crossing_radius_b);
      break;
    }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::directory_main("contact_profile", kUsage, run, argc, argv);
}
