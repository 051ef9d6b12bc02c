// Cost of ShellModel::evaluate: energy only, energy + gradient, energy + gradient + Hessian,
// on uniform discs of about 2k, 20k and 80k control vertices, with 1 and 2 assembly threads,
// the cost of the quadrature degree at the middle size, and of the stretching law there.
// Results: docs/performance.md.
//
// State: the flat reference disc (R = 1 m) bent into the saddle z += 0.2 (x^2 - y^2) at
// phi_e = 1, h = 0.02 m: every element is curved and stretched, so no branch of the energy
// density is skipped. Throughput is reported as elements per second (items_per_second).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <tuple>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"

namespace growshell {
namespace {

/// The excess angle phi_e (radians) at which every benchmark state is evaluated.
constexpr double kExcessAngle = 1.0;

/// Disc ring counts giving ~2k, ~20k and ~80k control vertices (1 + 3(N+1)(N+2)).
constexpr int kSmallRings = 25;
constexpr int kMediumRings = 81;
constexpr int kLargeRings = 162;

enum class Mode { Energy, Gradient, Hessian };

/// A model together with the state it is evaluated at and its reusable output buffers.
struct Scene {
  std::unique_ptr<ShellModel> model;
  Eigen::VectorXd x;
  Eigen::VectorXd gradient;
  Eigen::SparseMatrix<double> hessian;
};

// Building an 80k-vertex model takes longer than evaluating it, so scenes are built once per
// (rings, threads, quadrature degree, law) and shared by the benchmarks of this program.
Scene& scene(int rings, int threads, int degree,
             StretchingLaw law = StretchingLaw::kSaintVenantKirchhoff) {
  static std::map<std::tuple<int, int, int, StretchingLaw>, Scene> cache;
  const auto key = std::make_tuple(rings, threads, degree, law);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;

  DiscMeshOptions mesh;
  mesh.radius = 1.0;
  mesh.rings = rings;
  ShellModelSettings settings;
  settings.thickness = constant_thickness(0.02);
  settings.quadrature_degree = degree;
  settings.threads = threads;
  settings.material.stretching_law = law;
  Scene s;
  s.model = std::make_unique<ShellModel>(make_disc_mesh(mesh), settings);
  s.x = s.model->reference_positions();
  for (Eigen::Index v = 0; v < s.x.size() / 3; ++v) {
    const double X = s.x(3 * v), Y = s.x(3 * v + 1);
    s.x(3 * v + 2) += 0.2 * (X * X - Y * Y);
  }
  s.hessian = s.model->hessian_pattern();
  return cache.emplace(key, std::move(s)).first->second;
}

void run(benchmark::State& state, Mode mode, int rings, int threads, int degree,
         StretchingLaw law = StretchingLaw::kSaintVenantKirchhoff) {
  Scene& s = scene(rings, threads, degree, law);
  Eigen::VectorXd* gradient = mode == Mode::Energy ? nullptr : &s.gradient;
  Eigen::SparseMatrix<double>* hessian = mode == Mode::Hessian ? &s.hessian : nullptr;
  for (auto _ : state) benchmark::DoNotOptimize(s.model->evaluate(s.x, kExcessAngle, gradient, hessian));
  const auto elements = static_cast<int64_t>(s.model->num_elements());
  state.SetItemsProcessed(state.iterations() * elements);
  state.counters["vertices"] = static_cast<double>(s.model->dimension() / 3);
  state.counters["elements"] = static_cast<double>(elements);
  state.counters["threads"] = threads;
  state.counters["qdeg"] = degree;
}

// Arguments: {rings, threads}; the quadrature degree is the default 2.
void BM_Energy(benchmark::State& state) {
  run(state, Mode::Energy, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), 2);
}
void BM_Gradient(benchmark::State& state) {
  run(state, Mode::Gradient, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
      2);
}
void BM_Hessian(benchmark::State& state) {
  run(state, Mode::Hessian, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
      2);
}

// Arguments: {quadrature degree}; middle mesh, one thread, so the numbers are per core.
void BM_EnergyQuadrature(benchmark::State& state) {
  run(state, Mode::Energy, kMediumRings, 1, static_cast<int>(state.range(0)));
}
void BM_GradientQuadrature(benchmark::State& state) {
  run(state, Mode::Gradient, kMediumRings, 1, static_cast<int>(state.range(0)));
}
void BM_HessianQuadrature(benchmark::State& state) {
  run(state, Mode::Hessian, kMediumRings, 1, static_cast<int>(state.range(0)));
}

// Argument: {law} (0 Saint Venant-Kirchhoff, 1 neo-Hookean); middle mesh, one thread.
void BM_HessianStretchingLaw(benchmark::State& state) {
  run(state, Mode::Hessian, kMediumRings, 1, 2,
      state.range(0) == 0 ? StretchingLaw::kSaintVenantKirchhoff : StretchingLaw::kNeoHookean);
}

void size_and_thread_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"rings", "threads"});
  for (int rings : {kSmallRings, kMediumRings, kLargeRings})
    for (int threads : {1, 2}) b->Args({rings, threads});
  // Wall time: with OpenMP the work runs on several threads, so the main thread's CPU time
  // would understate the cost.
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

void degree_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"qdeg"});
  for (int degree : {1, 2, 4}) b->Args({degree});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Energy)->Apply(size_and_thread_args);
BENCHMARK(BM_Gradient)->Apply(size_and_thread_args);
BENCHMARK(BM_Hessian)->Apply(size_and_thread_args);
BENCHMARK(BM_EnergyQuadrature)->Apply(degree_args);
BENCHMARK(BM_GradientQuadrature)->Apply(degree_args);
BENCHMARK(BM_HessianQuadrature)->Apply(degree_args);
BENCHMARK(BM_HessianStretchingLaw)->ArgName("law")->Arg(0)->Arg(1)->UseRealTime()->Unit(
    benchmark::kMillisecond);

}  // namespace
}  // namespace growshell

BENCHMARK_MAIN();
