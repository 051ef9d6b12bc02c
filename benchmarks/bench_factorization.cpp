// Cost of the linear algebra of one Newton step: CHOLMOD symbolic analysis, numeric
// factorisation and one solve of the shell Hessian on discs of about 2k, 20k and 80k control
// vertices, METIS against AMD ordering; and one Newton-iteration-like sequence (Hessian
// assembly + factorisation + solve). Results: docs/performance.md.
//
// Matrix: the Hessian of the saddle state z += 0.2 (x^2 - y^2) of the unit disc at phi_e = 1,
// h = 0.02 m (the state of bench_assembly). The free sheet has six rigid-body null modes and
// the grown saddle is not a minimum, so the matrix is indefinite; it is factorised with the
// smallest shift sigma = c * mean|diag|, c in {1e-8, 1e-4, 0.01, 0.1, 0.3, 1}, that makes
// H + sigma I positive definite (counter shift_rel = c; the strong compression of the grown
// saddle needs c ~ 1). The supernodal factorisation does the same work for every successful
// shift, so the timings do not depend on that choice.
#include <benchmark/benchmark.h>
#include <dlfcn.h>

#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/newton/cholmod_factorization.hpp"

namespace growshell {
namespace {

/// The excess angle phi_e (radians) at which every benchmark state is evaluated.
constexpr double kExcessAngle = 1.0;

constexpr int kSmallRings = 25;   // 2,107 control vertices
constexpr int kMediumRings = 81;  // 20,419
constexpr int kLargeRings = 162;  // 80,197

/// A model at the saddle state with its assembled Hessian and the shift that factorises it.
struct Scene {
  std::unique_ptr<ShellModel> model;
  Eigen::VectorXd x;
  Eigen::VectorXd gradient;
  Eigen::SparseMatrix<double> hessian;
  double shift = 0.0;
  double shift_rel = 0.0;
};

// One scene per mesh size, built on first use and shared by all benchmarks of this program.
Scene& scene(int rings) {
  static std::map<int, Scene> cache;
  auto it = cache.find(rings);
  if (it != cache.end()) return it->second;

  DiscMeshOptions mesh;
  mesh.radius = 1.0;
  mesh.rings = rings;
  ShellModelSettings settings;
  settings.thickness = constant_thickness(0.02);
  settings.threads = 0;  // OpenMP default: what a Newton solver would use
  Scene s;
  s.model = std::make_unique<ShellModel>(make_disc_mesh(mesh), settings);
  s.x = s.model->reference_positions();
  for (Eigen::Index v = 0; v < s.x.size() / 3; ++v) {
    const double X = s.x(3 * v), Y = s.x(3 * v + 1);
    s.x(3 * v + 2) += 0.2 * (X * X - Y * Y);
  }
  s.hessian = s.model->hessian_pattern();
  s.model->evaluate(s.x, kExcessAngle, &s.gradient, &s.hessian);

  double mean_abs_diag = 0.0;
  for (Eigen::Index j = 0; j < s.hessian.cols(); ++j) mean_abs_diag += std::abs(s.hessian.coeff(j, j));
  mean_abs_diag /= static_cast<double>(s.hessian.cols());
  CholmodFactorization probe;
  probe.analyze(s.hessian);
  for (double c : {1e-8, 1e-4, 1e-2, 1e-1, 0.3, 1.0}) {
    if (probe.factorize(s.hessian, c * mean_abs_diag).positive_definite) {
      s.shift_rel = c;
      s.shift = c * mean_abs_diag;
      return cache.emplace(rings, std::move(s)).first->second;
    }
  }
  throw std::runtime_error("no shift up to mean|diag| makes the Hessian positive definite");
}

FillReducingOrdering ordering_of(const benchmark::State& state) {
  return state.range(1) == 0 ? FillReducingOrdering::Metis : FillReducingOrdering::Amd;
}

void add_factor_counters(benchmark::State& state, const Scene& s,
                         const CholmodFactorization& factor) {
  state.counters["n"] = static_cast<double>(s.hessian.rows());
  state.counters["nnz(H_upper)"] = static_cast<double>(s.hessian.nonZeros());
  state.counters["nnz(L)"] = factor.factor_nonzeros();
  state.counters["flops"] = factor.factorization_flops();
  state.counters["shift_rel"] = s.shift_rel;
  state.SetLabel(to_string(factor.ordering()));
}

// Arguments: {rings, ordering (0 = METIS, 1 = AMD)}.
void BM_Analyze(benchmark::State& state) {
  Scene& s = scene(static_cast<int>(state.range(0)));
  CholmodFactorization factor(CholmodOptions{ordering_of(state)});
  for (auto _ : state) factor.analyze(s.hessian);
  add_factor_counters(state, s, factor);
}

void BM_Factorize(benchmark::State& state) {
  Scene& s = scene(static_cast<int>(state.range(0)));
  CholmodFactorization factor(CholmodOptions{ordering_of(state)});
  factor.analyze(s.hessian);
  for (auto _ : state) {
    if (!factor.factorize(s.hessian, s.shift).positive_definite) {
      state.SkipWithError("shifted Hessian not positive definite");
      break;
    }
  }
  add_factor_counters(state, s, factor);
  state.counters["flop/s"] = benchmark::Counter(factor.factorization_flops(),
                                                benchmark::Counter::kIsIterationInvariantRate);
}

void BM_Solve(benchmark::State& state) {
  Scene& s = scene(static_cast<int>(state.range(0)));
  CholmodFactorization factor(CholmodOptions{ordering_of(state)});
  factor.analyze(s.hessian);
  if (!factor.factorize(s.hessian, s.shift).positive_definite) {
    state.SkipWithError("shifted Hessian not positive definite");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(factor.solve(s.gradient));
  add_factor_counters(state, s, factor);
}

// One Newton iteration without the line search: energy + gradient + Hessian assembly, numeric
// factorisation (pattern analysed once, outside the loop, as a Newton solver does) and one
// solve. Run it under different OMP_WAIT_POLICY / OPENBLAS_NUM_THREADS settings to see how
// OpenMP's and OpenBLAS's threads share the cores. Arguments: {rings}; METIS ordering.
void BM_NewtonIteration(benchmark::State& state) {
  Scene& s = scene(static_cast<int>(state.range(0)));
  CholmodFactorization factor(CholmodOptions{FillReducingOrdering::Metis});
  factor.analyze(s.hessian);
  for (auto _ : state) {
    s.model->evaluate(s.x, kExcessAngle, &s.gradient, &s.hessian);
    if (!factor.factorize(s.hessian, s.shift).positive_definite) {
      state.SkipWithError("shifted Hessian not positive definite");
      break;
    }
    benchmark::DoNotOptimize(factor.solve(s.gradient));
  }
  add_factor_counters(state, s, factor);
}

// CHOLMOD's supernodal factorisation (SuiteSparse 5.x) opens OpenMP regions with a thread
// count fixed when CHOLMOD was built (four threads appear even with OMP_NUM_THREADS=1) around
// short loops; on two cores their start-up and spin-waiting cost more than the loops. This
// guard makes every OpenMP region inactive (max-active-levels 0) while it lives, so CHOLMOD
// runs those loops serially while OpenBLAS keeps its own threads. It is looked up at run time
// because the benchmark does not link libgomp itself (the library does, privately).
class SerialOpenMpRegions {
 public:
  SerialOpenMpRegions()
      : get_(reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"))),
        set_(reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"))) {
    if (!get_ || !set_) throw std::runtime_error("libgomp's max-active-levels API not found");
    saved_ = get_();
    set_(0);
  }
  ~SerialOpenMpRegions() { set_(saved_); }
  SerialOpenMpRegions(const SerialOpenMpRegions&) = delete;
  SerialOpenMpRegions& operator=(const SerialOpenMpRegions&) = delete;

 private:
  int (*get_)();
  void (*set_)(int);
  int saved_ = 1;
};

// BM_NewtonIteration with CHOLMOD's OpenMP regions made serial during factorize() only (the
// assembly keeps its threads): what the iteration would cost if CholmodFactorization did this.
void BM_NewtonIterationSerialCholmodOpenMp(benchmark::State& state) {
  Scene& s = scene(static_cast<int>(state.range(0)));
  CholmodFactorization factor(CholmodOptions{FillReducingOrdering::Metis});
  factor.analyze(s.hessian);
  for (auto _ : state) {
    s.model->evaluate(s.x, kExcessAngle, &s.gradient, &s.hessian);
    bool positive_definite = false;
    {
      const SerialOpenMpRegions serial;
      positive_definite = factor.factorize(s.hessian, s.shift).positive_definite;
    }
    if (!positive_definite) {
      state.SkipWithError("shifted Hessian not positive definite");
      break;
    }
    benchmark::DoNotOptimize(factor.solve(s.gradient));
  }
  add_factor_counters(state, s, factor);
}

// BM_Factorize (METIS) with CHOLMOD's OpenMP regions made serial.
void BM_FactorizeSerialCholmodOpenMp(benchmark::State& state) {
  Scene& s = scene(static_cast<int>(state.range(0)));
  CholmodFactorization factor(CholmodOptions{FillReducingOrdering::Metis});
  factor.analyze(s.hessian);
  const SerialOpenMpRegions serial;
  for (auto _ : state) {
    if (!factor.factorize(s.hessian, s.shift).positive_definite) {
      state.SkipWithError("shifted Hessian not positive definite");
      break;
    }
  }
  add_factor_counters(state, s, factor);
}

void size_and_ordering_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"rings", "amd"});
  for (int rings : {kSmallRings, kMediumRings, kLargeRings})
    for (int ordering : {0, 1}) b->Args({rings, ordering});
  // CHOLMOD runs BLAS on OpenBLAS's own threads: wall time is what a solver waits for.
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Analyze)->Apply(size_and_ordering_args);
BENCHMARK(BM_Factorize)->Apply(size_and_ordering_args);
BENCHMARK(BM_Solve)
    ->ArgNames({"rings", "amd"})
    ->Args({kSmallRings, 0})
    ->Args({kMediumRings, 0})
    ->Args({kLargeRings, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
void size_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"rings"});
  for (int rings : {kSmallRings, kMediumRings, kLargeRings}) b->Args({rings});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_FactorizeSerialCholmodOpenMp)->Apply(size_args);
BENCHMARK(BM_NewtonIteration)->Apply(size_args);
BENCHMARK(BM_NewtonIterationSerialCholmodOpenMp)->Apply(size_args);

}  // namespace
}  // namespace growshell

BENCHMARK_MAIN();
