// Cost of elements with an extraordinary corner against regular ones: Hessian assembly
// (ShellModel::evaluate with gradient and Hessian, one thread) of the hexagonal lattice disc
// (every element regular) and of a Gmsh disc of about the same size (about a third of its
// elements have an extraordinary corner). With n_r regular and n_i irregular elements, time =
// n_r c_r + n_i c_i; the lattice disc gives c_r, the Gmsh disc then c_i. Results:
// docs/performance.md.
#include <benchmark/benchmark.h>

#include <memory>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/gmsh_disc_mesh.hpp"

namespace growshell {
namespace {

/// The excess angle phi_e (radians) at which every benchmark state is evaluated.
constexpr double kExcessAngle = 1.0;

struct Bench {
  std::unique_ptr<ShellModel> model;
  Eigen::VectorXd x, gradient;
  Eigen::SparseMatrix<double> hessian;
};

Bench make_bench(const TriangleMesh& mesh) {
  ShellModelSettings settings;
  settings.thickness = constant_thickness(0.02);
  settings.threads = 1;
  Bench b;
  b.model = std::make_unique<ShellModel>(mesh, settings);
  b.x = b.model->reference_positions();
  for (Eigen::Index v = 0; v < b.x.size() / 3; ++v)
    b.x(3 * v + 2) += 0.2 * (b.x(3 * v) * b.x(3 * v) - b.x(3 * v + 1) * b.x(3 * v + 1));
  b.hessian = b.model->hessian_pattern();
  return b;
}

void run(benchmark::State& state, Bench& b) {
  for (auto _ : state) benchmark::DoNotOptimize(b.model->evaluate(b.x, kExcessAngle, &b.gradient, &b.hessian));
  state.SetItemsProcessed(state.iterations() * b.model->num_elements());
  state.counters["elements"] = static_cast<double>(b.model->num_elements());
  state.counters["irregular"] = static_cast<double>(b.model->patches().num_irregular());
}

void BM_HessianLatticeDisc(benchmark::State& state) {
  static Bench b = make_bench(make_disc_mesh({.rings = 40}));
  run(state, b);
}
BENCHMARK(BM_HessianLatticeDisc)->Unit(benchmark::kMillisecond);

void BM_HessianGmshDisc(benchmark::State& state) {
  static Bench b = [] {
    GmshDiscMeshOptions o;
    o.size_slope = 0.05;
    o.size_floor = 0.01;
    o.size_max = 0.045;
    return make_bench(make_gmsh_disc_mesh(o));
  }();
  run(state, b);
}
BENCHMARK(BM_HessianGmshDisc)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace growshell
BENCHMARK_MAIN();
