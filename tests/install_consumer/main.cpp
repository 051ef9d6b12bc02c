// Consumer of the installed growshell package: includes public headers by their in-repo paths,
// builds a one-triangle mesh and checks it, and evaluates a small objective through the core
// interface. Exits non-zero if anything is off.
#include <cstdio>
#include <type_traits>

#include "core/objective_at_parameter.hpp"
#include "core/sparse_objective.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/triangle_mesh.hpp"

// The installed libshell headers find the core interfaces they implement.
static_assert(std::is_base_of_v<growshell::ParametrizedObjective, growshell::ShellModel>);
static_assert(std::is_base_of_v<growshell::SparseObjective, growshell::ObjectiveAtParameter>);

namespace {

// E(x) = x^2 / 2 on one unknown.
class HalfSquare final : public growshell::SparseObjective {
 public:
  Eigen::Index dimension() const override { return 1; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    Eigen::SparseMatrix<double> h(1, 1);
    h.insert(0, 0) = 0.0;
    h.makeCompressed();
    return h;
  }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override {
    if (gradient) *gradient = x;
    if (hessian_upper) hessian_upper->coeffRef(0, 0) = 1.0;
    return 0.5 * x(0) * x(0);
  }
};

}  // namespace

int main() {
  growshell::TriangleMesh mesh;
  mesh.vertices.resize(3, 3);
  mesh.vertices << 0.0, 0.0, 0.0,  //
      1.0, 0.0, 0.0,               //
      0.0, 1.0, 0.0;
  mesh.faces.resize(1, 3);
  mesh.faces << 0, 1, 2;

  // Twice the signed area of the triangle: exactly 1 for this right triangle (all inputs are
  // small integers, so the floating-point result is exact).
  const Eigen::RowVector3d e1 = mesh.vertices.row(1) - mesh.vertices.row(0);
  const Eigen::RowVector3d e2 = mesh.vertices.row(2) - mesh.vertices.row(0);
  const double twice_area = e1.x() * e2.y() - e1.y() * e2.x();

  // Exact too: 0.5 * 2 * 2 = 2.
  HalfSquare objective;
  Eigen::SparseMatrix<double> hessian = objective.hessian_pattern();
  Eigen::VectorXd gradient;
  const double energy = objective.evaluate(Eigen::VectorXd::Constant(1, 2.0), &gradient, &hessian);

  const bool ok = mesh.vertices.rows() == 3 && mesh.faces.rows() == 1 &&
                  mesh.faces.maxCoeff() == 2 && twice_area == 1.0 && energy == 2.0 &&
                  gradient.size() == 1 && gradient(0) == 2.0 && hessian.coeff(0, 0) == 1.0;
  std::printf("growshell consumer: %ld vertices, %ld faces, 2*area = %g, E = %g -> %s\n",
              static_cast<long>(mesh.vertices.rows()), static_cast<long>(mesh.faces.rows()),
              twice_area, energy, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
