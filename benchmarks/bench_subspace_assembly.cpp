// Cost of one linearisation in the two-mirror subspace the symmetric cone is traced in, on the
// Fig. 4 scene's default mesh (h = 0.02, rings, 7035 unknowns): the full assembly (energy,
// gradient, Hessian) against the reduced one (the full assembly plus Q^T g and Q^T H Q by
// SubspaceHessianProjection), and the general sparse product Q^T H Q the projection replaced.
// The stability index at that state: the full Hessian's with six pins (HessianNegativeCount)
// against the class-by-class one (SymmetryClassStabilityIndex: one assembly, four projections,
// four factorisations of a quarter of the unknowns).
// The state is a synthetic two-fold cone with both mirrors. One thread (the studies' setting
// for timing: OMP_NUM_THREADS=1). Results: docs/performance.md, "Assembly in the symmetric
// subspace".
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/hessian_negative_count.hpp"
#include "solvers/stability/subspace_hessian_projection.hpp"
#include "solvers/stability/symmetry_class_stability_index.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"
#include "solvers/continuation/symmetric_subspace_family.hpp"

namespace growshell {
namespace {

struct Bench {
  std::unique_ptr<ShellModel> model;
  std::unique_ptr<SymmetricSubspace> subspace;
  Eigen::VectorXd x;  ///< full state with both mirrors
};

Bench& fig4_disc() {
  static Bench b = [] {
    Bench out;
    const Scene scene = parse_scene(R"({"thickness": 0.02})", "bench_subspace_assembly");
    ShellModelSettings settings = scene_model_settings(scene);
    settings.threads = 1;
    out.model = std::make_unique<ShellModel>(scene_mesh(scene), settings);
    out.subspace = std::make_unique<SymmetricSubspace>(two_mirror_subspace(*out.model, 1e-9));
    out.x = out.model->reference_positions();
    for (Eigen::Index v = 0; v < out.x.size() / 3; ++v) {
      const double X = out.x(3 * v), Y = out.x(3 * v + 1), r = std::hypot(X, Y);
      out.x(3 * v + 2) = 0.3 * (X * X - Y * Y) / std::max(r, 1e-12);  // z = 0.3 r cos 2 theta
    }
    return out;
  }();
  return b;
}

void BM_FullAssembly(benchmark::State& state) {
  Bench& b = fig4_disc();
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = b.model->hessian_pattern();
  for (auto _ : state) benchmark::DoNotOptimize(b.model->evaluate(b.x, 3.0, &g, &H));
  state.counters["unknowns"] = static_cast<double>(b.x.size());
}
BENCHMARK(BM_FullAssembly)->Unit(benchmark::kMillisecond);

void BM_SubspaceAssembly(benchmark::State& state) {
  Bench& b = fig4_disc();
  const SymmetricSubspaceFamily family(*b.model, *b.subspace);
  const Eigen::VectorXd y = b.subspace->restrict_to(b.x);
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = family.hessian_pattern();
  for (auto _ : state) benchmark::DoNotOptimize(family.evaluate(y, 3.0, &g, &H));
  state.counters["unknowns"] = static_cast<double>(y.size());
}
BENCHMARK(BM_SubspaceAssembly)->Unit(benchmark::kMillisecond);

/// Q^T H Q as Eigen's sparse products compute it: a full symmetric copy of the upper triangle,
/// then two products.
void BM_GeneralSparseProductQtHQ(benchmark::State& state) {
  Bench& b = fig4_disc();
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = b.model->hessian_pattern();
  b.model->evaluate(b.x, 3.0, &g, &H);
  const Eigen::SparseMatrix<double> Qt = b.subspace->basis().transpose();
  for (auto _ : state) {
    const Eigen::SparseMatrix<double> symmetric = H.selfadjointView<Eigen::Upper>();
    const Eigen::SparseMatrix<double> product = Qt * symmetric * b.subspace->basis();
    benchmark::DoNotOptimize(product.nonZeros());
  }
}
BENCHMARK(BM_GeneralSparseProductQtHQ)->Unit(benchmark::kMillisecond);

void BM_SubspaceHessianProjection(benchmark::State& state) {
  Bench& b = fig4_disc();
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = b.model->hessian_pattern();
  b.model->evaluate(b.x, 3.0, &g, &H);
  const SubspaceHessianProjection projection(H, b.subspace->basis());
  Eigen::SparseMatrix<double> reduced = projection.pattern();
  for (auto _ : state) {
    projection.project(H, reduced);
    benchmark::DoNotOptimize(reduced.valuePtr());
  }
}
BENCHMARK(BM_SubspaceHessianProjection)->Unit(benchmark::kMillisecond);

void BM_FullStabilityIndex(benchmark::State& state) {
  Bench& b = fig4_disc();
  const Eigen::VectorXd& X = b.model->reference_positions();
  const Eigen::MatrixX3d P =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
  HessianNegativeCount count(
      *b.model, mirror_axis_pinned_dofs(P, b.model->sheet_vertices(), Eigen::Vector3d::Zero()));
  for (auto _ : state) benchmark::DoNotOptimize(count.at(b.x, 3.0));
}
BENCHMARK(BM_FullStabilityIndex)->Unit(benchmark::kMillisecond);

void BM_ClassStabilityIndex(benchmark::State& state) {
  Bench& b = fig4_disc();
  SymmetryClassStabilityIndex index(*b.model, b.subspace->group());
  for (auto _ : state) benchmark::DoNotOptimize(index.at(b.x, 3.0));
}
BENCHMARK(BM_ClassStabilityIndex)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace growshell

BENCHMARK_MAIN();
