// Cost of the two-fold cone's symmetry measures per sample (measure_cone_symmetry: S4 defect,
// fold directions and chords) on the default rings disc, whose quarter-turn vertex map gives the
// S4 images directly, and on the Gmsh disc of the same scene, whose images are found on the exact
// limit surface (sheet_state_evaluator: a Newton search per material point), directly and
// through a ConeSymmetryMeter, which locates those points once. The state is a synthetic
// two-fold cone over the reference. Results: docs/performance.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "libshell/analysis/cone_symmetry.hpp"
#include "libshell/analysis/state_evaluator.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/gmsh_disc_mesh.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"

namespace growshell {
namespace {

struct Bench {
  std::unique_ptr<ShellModel> model;
  Eigen::VectorXd x;
};

/// A two-fold cone: z = 0.3 r cos 2 theta, the radius shortened so that generators keep their
/// length.
Bench make_bench(const TriangleMesh& mesh) {
  Bench b;
  b.model = std::make_unique<ShellModel>(mesh, ShellModelSettings{});
  b.x = b.model->reference_positions();
  for (Eigen::Index v = 0; v < b.x.size() / 3; ++v) {
    const double X = b.x(3 * v), Y = b.x(3 * v + 1), r = std::hypot(X, Y);
    const double z = 0.3 * (X * X - Y * Y) / std::max(r, 1e-12);
    const double shrink = r > 0 ? std::sqrt(std::max(r * r - z * z, 0.0)) / r : 1.0;
    b.x.segment<3>(3 * v) << shrink * X, shrink * Y, z;
  }
  return b;
}

Bench rings() {
  RingDiscMeshOptions o;
  o.size_slope = 0.1;
  o.size_floor = 0.01;
  return make_bench(make_ring_disc_mesh(o));
}

Bench gmsh() {
  GmshDiscMeshOptions o;
  o.size_slope = 0.1;
  o.size_floor = 0.01;
  return make_bench(make_gmsh_disc_mesh(o));
}

void BM_ConeSymmetryRingsDisc(benchmark::State& state) {
  static Bench b = rings();
  for (auto _ : state) benchmark::DoNotOptimize(measure_cone_symmetry(*b.model, b.x).s4.defect);
  state.counters["sheet_vertices"] = static_cast<double>(b.model->sheet_vertices().size());
}
BENCHMARK(BM_ConeSymmetryRingsDisc)->Unit(benchmark::kMillisecond);

void BM_ConeSymmetryGmshDisc(benchmark::State& state) {
  static Bench b = gmsh();
  for (auto _ : state) benchmark::DoNotOptimize(measure_cone_symmetry(*b.model, b.x).s4.defect);
  state.counters["sheet_vertices"] = static_cast<double>(b.model->sheet_vertices().size());
}
BENCHMARK(BM_ConeSymmetryGmshDisc)->Unit(benchmark::kMillisecond);

/// The same through a ConeSymmetryMeter, whose quarter-turned points are located once: the
/// whole measure, the S4 defect alone, and the meter's construction.
void BM_ConeSymmetryMeterGmshDisc(benchmark::State& state) {
  static Bench b = gmsh();
  static const ConeSymmetryMeter meter(*b.model);
  for (auto _ : state) benchmark::DoNotOptimize(meter.measure(b.x).s4.defect);
}
BENCHMARK(BM_ConeSymmetryMeterGmshDisc)->Unit(benchmark::kMillisecond);

void BM_ConeSymmetryMeterS4GmshDisc(benchmark::State& state) {
  static Bench b = gmsh();
  static const ConeSymmetryMeter meter(*b.model);
  for (auto _ : state) benchmark::DoNotOptimize(meter.s4(b.x).defect);
}
BENCHMARK(BM_ConeSymmetryMeterS4GmshDisc)->Unit(benchmark::kMillisecond);

void BM_ConeSymmetryMeterS4RingsDisc(benchmark::State& state) {
  static Bench b = rings();
  static const ConeSymmetryMeter meter(*b.model);
  for (auto _ : state) benchmark::DoNotOptimize(meter.s4(b.x).defect);
}
BENCHMARK(BM_ConeSymmetryMeterS4RingsDisc)->Unit(benchmark::kMillisecond);

void BM_ConeSymmetryMeterConstructionGmshDisc(benchmark::State& state) {
  static Bench b = gmsh();
  for (auto _ : state) {
    const ConeSymmetryMeter meter(*b.model);
    benchmark::DoNotOptimize(&meter);
  }
}
BENCHMARK(BM_ConeSymmetryMeterConstructionGmshDisc)->Unit(benchmark::kMillisecond);

/// One evaluation y(X) of the exact limit surface at a material point of the Gmsh disc.
void BM_LimitSurfaceAtAMaterialPoint(benchmark::State& state) {
  static Bench b = gmsh();
  const StateEvaluator y = sheet_state_evaluator(*b.model, b.x);
  int k = 0;
  for (auto _ : state) {
    const double r = 0.9 * std::sqrt((k % 97 + 0.5) / 97.0), t = 2.4 * k;
    benchmark::DoNotOptimize(y(Eigen::Vector3d(r * std::cos(t), r * std::sin(t), 0.0)));
    ++k;
  }
}
BENCHMARK(BM_LimitSurfaceAtAMaterialPoint)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace growshell

BENCHMARK_MAIN();
