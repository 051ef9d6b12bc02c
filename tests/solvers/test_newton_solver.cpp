#include "solvers/newton/newton_solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/sparse_objective.hpp"
#include "support/dense_symmetric.hpp"

namespace growshell {
namespace {

using test_support::dense_symmetric;

// Base for toy objectives coupling neighbours of a chain: upper-triangular tridiagonal
// pattern, with helpers that write the values in place.
class ChainObjective : public SparseObjective {
 public:
  explicit ChainObjective(Eigen::Index n) : n_(n) {}
  Eigen::Index dimension() const override { return n_; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    std::vector<Eigen::Triplet<double>> t;
    for (Eigen::Index i = 0; i < n_; ++i) {
      t.emplace_back(i, i, 0.0);
      if (i + 1 < n_) t.emplace_back(i, i + 1, 0.0);
    }
    Eigen::SparseMatrix<double> h(n_, n_);
    h.setFromTriplets(t.begin(), t.end());
    h.makeCompressed();
    return h;
  }

 protected:
  Eigen::Index n_;
};

// Dense symmetric matrix from an upper triangle, for eigenvalue checks.
// f = 1/2 x^T A x - b^T x with A = tridiag(-1, 4, -1) (eigenvalues in [2, 6]).
class TridiagonalQuadratic : public ChainObjective {
 public:
  TridiagonalQuadratic(Eigen::Index n, Eigen::VectorXd b) : ChainObjective(n), b_(std::move(b)) {}
  Eigen::SparseMatrix<double> matrix() const {
    Eigen::SparseMatrix<double> a = hessian_pattern();
    fill(&a);
    return a;
  }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* h) override {
    Eigen::VectorXd ax = 4.0 * x;
    ax.head(n_ - 1) -= x.tail(n_ - 1);
    ax.tail(n_ - 1) -= x.head(n_ - 1);
    if (g) *g = ax - b_;
    if (h) fill(h);
    return 0.5 * x.dot(ax) - b_.dot(x);
  }

 private:
  static void fill(Eigen::SparseMatrix<double>* h) {
    for (int col = 0; col < h->outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(*h, col); it; ++it) {
        it.valueRef() = it.row() == it.col() ? 4.0 : -1.0;
      }
    }
  }
  Eigen::VectorXd b_;
};

// f = sum (x_i^2 - 1)^2 + c sum (x_{i+1} - x_i)^2: non-convex (Hessian -4 + 4c... at x = 0),
// minima near x_i = +-1.
class DoubleWellChain : public ChainObjective {
 public:
  DoubleWellChain(Eigen::Index n, double c) : ChainObjective(n), c_(c) {}
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* h) override {
    double f = 0.0;
    if (g) g->setZero(n_);
    for (Eigen::Index i = 0; i < n_; ++i) {
      f += std::pow(x[i] * x[i] - 1.0, 2);
      if (g) (*g)[i] += 4.0 * x[i] * (x[i] * x[i] - 1.0);
      if (i + 1 < n_) {
        const double d = x[i + 1] - x[i];
        f += c_ * d * d;
        if (g) {
          (*g)[i + 1] += 2.0 * c_ * d;
          (*g)[i] -= 2.0 * c_ * d;
        }
      }
    }
    if (h) {
      for (int col = 0; col < h->outerSize(); ++col) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(*h, col); it; ++it) {
          if (it.row() != it.col()) {
            it.valueRef() = -2.0 * c_;
          } else {
            const Eigen::Index i = it.row();
            const int neighbours = (i > 0) + (i + 1 < n_);
            it.valueRef() = 12.0 * x[i] * x[i] - 4.0 + 2.0 * c_ * neighbours;
          }
        }
      }
    }
    return f;
  }

 private:
  double c_;
};

// The double well with a stiff one-sided wall at x_i = 0.9 (a contact penalty in miniature):
// f = sum (x_i^2 - 1)^2 + c (x_{i+1} - x_i)^2 + k/2 max(0, x_i - 0.9)^2. Its Hessian jumps by
// k where a coordinate crosses the wall, so the quadratic model of a step that crosses it
// fails and the line search cuts the step.
class WalledDoubleWellChain : public DoubleWellChain {
 public:
  WalledDoubleWellChain(Eigen::Index n, double c, double k) : DoubleWellChain(n, c), k_(k) {}
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* h) override {
    double f = DoubleWellChain::evaluate(x, g, h);
    for (Eigen::Index i = 0; i < n_; ++i) {
      const double over = x[i] - kWall;
      if (over <= 0.0) continue;
      f += 0.5 * k_ * over * over;
      if (g) (*g)[i] += k_ * over;
      if (h) h->coeffRef(i, i) += k_;
    }
    return f;
  }
  static constexpr double kWall = 0.9;

 private:
  double k_;
};

// Nonlinear springs between neighbours: f = sum phi(x_{i+1} - x_i), phi(d) = d^2/2 + d^4/4.
// Singular without fixed dofs (translation invariant).
class SpringChain : public ChainObjective {
 public:
  using ChainObjective::ChainObjective;
  static double force(double d) { return d + d * d * d; }  // phi'(d)
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* h) override {
    double f = 0.0;
    if (g) g->setZero(n_);
    if (h) std::fill(h->valuePtr(), h->valuePtr() + h->nonZeros(), 0.0);
    for (Eigen::Index i = 0; i + 1 < n_; ++i) {
      const double d = x[i + 1] - x[i];
      f += 0.5 * d * d + 0.25 * d * d * d * d;
      if (g) {
        (*g)[i + 1] += force(d);
        (*g)[i] -= force(d);
      }
      if (h) {
        const double k = 1.0 + 3.0 * d * d;
        h->coeffRef(i, i) += k;
        h->coeffRef(i + 1, i + 1) += k;
        h->coeffRef(i, i + 1) -= k;
      }
    }
    return f;
  }
};

// f = sum sqrt(1 + (x_i - t_i)^2) + 0.01 sum (x_{i+1} - x_i)^2, undefined (NaN) outside
// |x|_inf <= 5. From |x - t| = 2 the full Newton step of the pseudo-Huber term overshoots to
// |x - t| ~ 8, i.e. into the NaN region, so the line search must backtrack.
class NanOutsideBox : public ChainObjective {
 public:
  explicit NanOutsideBox(Eigen::Index n) : ChainObjective(n), t_(n) {
    for (Eigen::Index i = 0; i < n; ++i) t_[i] = 0.5 * std::sin(static_cast<double>(i));
  }
  const Eigen::VectorXd& target() const { return t_; }
  int nan_evaluations = 0;
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* h) override {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (x.lpNorm<Eigen::Infinity>() > 5.0) {
      ++nan_evaluations;
      if (g) g->setConstant(n_, nan);
      if (h) std::fill(h->valuePtr(), h->valuePtr() + h->nonZeros(), nan);
      return nan;
    }
    const double c = 0.01;
    double f = 0.0;
    if (g) g->setZero(n_);
    if (h) std::fill(h->valuePtr(), h->valuePtr() + h->nonZeros(), 0.0);
    for (Eigen::Index i = 0; i < n_; ++i) {
      const double d = x[i] - t_[i];
      const double s = std::sqrt(1.0 + d * d);
      f += s;
      if (g) (*g)[i] += d / s;
      if (h) h->coeffRef(i, i) += 1.0 / (s * s * s);
      if (i + 1 < n_) {
        const double e = x[i + 1] - x[i];
        f += c * e * e;
        if (g) {
          (*g)[i + 1] += 2.0 * c * e;
          (*g)[i] -= 2.0 * c * e;
        }
        if (h) {
          h->coeffRef(i, i) += 2.0 * c;
          h->coeffRef(i + 1, i + 1) += 2.0 * c;
          h->coeffRef(i, i + 1) -= 2.0 * c;
        }
      }
    }
    return f;
  }

 private:
  Eigen::VectorXd t_;
};

// NaN everywhere.
class AlwaysNan : public ChainObjective {
 public:
  using ChainObjective::ChainObjective;
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>&, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>*) override {
    if (g) g->setZero(n_);
    return std::numeric_limits<double>::quiet_NaN();
  }
};

Eigen::VectorXd near_saddle(Eigen::Index n) {
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = 1e-3 * std::sin(1.7 * static_cast<double>(i) + 0.3);
  return x;
}

// Right-hand side of the convex quadratic tests: b_i = cos(0.3 i).
Eigen::VectorXd cosine_load(Eigen::Index n) {
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = std::cos(0.3 * static_cast<double>(i));
  return b;
}

TEST(NewtonSolver, ConvexQuadraticConvergesInOneIteration) {
  const Eigen::Index n = 50;
  const Eigen::VectorXd b = cosine_load(n);
  TridiagonalQuadratic q(n, b);
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;  // cond(A) <= 3: the exact solve leaves ~1e-15
  NewtonSolver solver(options);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(n, 3.0);
  const Eigen::VectorXd x0_copy = x0;
  const NewtonResult r = solver.minimize(q, x0);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_EQ(r.iterations, 1);
  EXPECT_EQ(r.factorizations, 1);
  ASSERT_EQ(r.log.size(), 1u);
  EXPECT_EQ(r.log[0].step_length, 1.0);
  EXPECT_EQ(r.log[0].shift, 0.0);
  const Eigen::VectorXd exact = Eigen::MatrixXd(dense_symmetric(q.matrix())).ldlt().solve(b);
  EXPECT_LT((r.x - exact).norm() / exact.norm(), 1e-13);
  EXPECT_EQ(x0, x0_copy);
}

TEST(NewtonSolver, AlreadyConvergedAtX0TakesNoIteration) {
  TridiagonalQuadratic q(10, Eigen::VectorXd::Zero(10));
  const NewtonResult r = NewtonSolver().minimize(q, Eigen::VectorXd::Zero(10));
  EXPECT_TRUE(r.converged());
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.factorizations, 0);
  EXPECT_TRUE(r.log.empty());
}

TEST(NewtonSolver, NonConvexDoubleWellReachesAStableMinimumWithShifts) {
  const Eigen::Index n = 20;
  DoubleWellChain f(n, 0.1);
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  std::vector<NewtonIterate> seen;
  const NewtonResult r = NewtonSolver(options).minimize(
      f, near_saddle(n), {}, [&](const NewtonIterate& it) { seen.push_back(it); });
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_EQ(seen.size(), r.log.size());
  RecordProperty("iterations", r.iterations);
  RecordProperty("factorizations", r.factorizations);

  // At x ~ 0 the Hessian is -4 + O(c) on the diagonal: the first iteration must shift.
  ASSERT_FALSE(r.log.empty());
  EXPECT_GT(r.log.front().shift, 0.0);
  EXPECT_GT(r.log.front().factorization_attempts, 1);
  // The shift decays by shift_growth per iteration once the Hessian is definite; at the end
  // it is negligible against the minimum's diagonal (~8), and the steps are full.
  EXPECT_LT(r.log.back().shift, 1e-4);
  EXPECT_EQ(r.log.back().step_length, 1.0);
  for (std::size_t k = 1; k < r.log.size(); ++k) {
    EXPECT_LE(r.log[k].energy, r.log[k - 1].energy);
  }

  Eigen::SparseMatrix<double> h = f.hessian_pattern();
  Eigen::VectorXd g(n);
  f.evaluate(r.x, &g, &h);
  EXPECT_LE(g.lpNorm<Eigen::Infinity>(), 1e-10);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense_symmetric(h));
  // At x_i ~ +-1 the diagonal is ~8 and the coupling 2c = 0.2 shifts eigenvalues by <= 0.8
  // even across a domain wall, so a true minimum has all eigenvalues well above 1.
  EXPECT_GT(eig.eigenvalues().minCoeff(), 1.0);
  // Each x_i sits in a well; a domain wall between +1 and -1 segments pulls its two
  // neighbours in by O(c) = O(0.1) (0.89 measured), hence the 0.2.
  for (Eigen::Index i = 0; i < n; ++i) EXPECT_NEAR(std::abs(r.x[i]), 1.0, 0.2);

  // Quadratic convergence over the final run of full steps with decreasing gradient (the
  // saddle escape before it has growing gradients): g_{k+1} <= C g_k^2 with
  // C ~ |H^-1| |D^3 f| / 2 ~ (1/7) * 24 / 2 < 2 near x = +-1; allow C = 10.
  std::size_t tail = r.log.size() - 1;
  while (tail > 0 && r.log[tail].step_length == 1.0 &&
         r.log[tail].gradient_inf_norm < r.log[tail - 1].gradient_inf_norm) {
    --tail;
  }
  int checked = 0;
  for (std::size_t k = tail + 1; k < r.log.size(); ++k) {
    const double prev = r.log[k - 1].gradient_inf_norm;
    const double next = r.log[k].gradient_inf_norm;
    if (prev < 1e-1) {
      EXPECT_LE(next, 10.0 * prev * prev) << "iteration " << r.log[k].iteration;
      RecordProperty("quadratic_ratio_iteration_" + std::to_string(r.log[k].iteration),
                     std::to_string(next / (prev * prev)));
      ++checked;
    }
  }
  EXPECT_GE(checked, 2);
}

// NewtonOptions::adaptive_shift on a nonconvex energy with a stiff wall, against the default
// schedule: both end at a strict minimum with every coordinate in a well (those of the upper
// well held at the wall); with the option every iteration after a step the line search cut
// below 1/4 starts from a shift shift_growth times the last one, and after a cut to between
// 1/4 and 1 from the last one, so its shift never falls there, while the default schedule
// lowers it after every step.
TEST(NewtonSolver, AdaptiveShiftRaisesTheShiftAfterShortStepsAndStillReachesTheMinimum) {
  const Eigen::Index n = 20;
  WalledDoubleWellChain f(n, 0.1, 1e4);
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  options.max_iterations = 500;
  NewtonOptions adaptive = options;
  adaptive.adaptive_shift = true;
  const NewtonResult plain = NewtonSolver(options).minimize(f, near_saddle(n));
  const NewtonResult fast = NewtonSolver(adaptive).minimize(f, near_saddle(n));
  for (const NewtonResult* r : {&plain, &fast}) {
    ASSERT_TRUE(r->converged()) << r->message;
    Eigen::SparseMatrix<double> h = f.hessian_pattern();
    Eigen::VectorXd g(n);
    f.evaluate(r->x, &g, &h);
    EXPECT_LE(g.lpNorm<Eigen::Infinity>(), 1e-10);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense_symmetric(h));
    EXPECT_GT(eig.eigenvalues().minCoeff(), 1.0);
    for (Eigen::Index i = 0; i < n; ++i) {
      // Upper well: at the wall, pressed in by about the well's pull over k (< 1e-3).
      if (r->x[i] > 0.0)
        EXPECT_NEAR(r->x[i], WalledDoubleWellChain::kWall, 1e-3) << "x_" << i;
      else
        EXPECT_NEAR(r->x[i], -1.0, 0.2) << "x_" << i;
    }
  }
  // Iterations after a cut step whose shift fell below the rule's start.
  const auto fallen_after_cut_steps = [&](const NewtonResult& r) {
    int fallen = 0, cut = 0;
    for (std::size_t k = 1; k < r.log.size(); ++k) {
      const NewtonIterate& before = r.log[k - 1];
      if (before.step_length >= 1.0 || before.shift == 0.0) continue;
      ++cut;
      const double start = before.step_length < 0.25 ? options.shift_growth * before.shift
                                                      : before.shift;
      fallen += r.log[k].shift < start * (1.0 - 1e-12);
    }
    EXPECT_GT(cut, 3);  // the wall cuts steps on both schedules
    return fallen;
  };
  EXPECT_EQ(fallen_after_cut_steps(fast), 0);
  EXPECT_GT(fallen_after_cut_steps(plain), 0);
}

TEST(NewtonSolver, FixedDofsStayPutAndReportReactions) {
  const Eigen::Index n = 21;
  SpringChain f(n);
  Eigen::VectorXd x0(n);
  for (Eigen::Index i = 0; i < n; ++i) x0[i] = 0.1 * std::cos(static_cast<double>(i));
  x0[0] = 0.3;
  x0[10] = 1.0;
  x0[20] = 2.3;
  NewtonOptions options;
  options.gradient_tolerance = 1e-12;
  const NewtonResult r = NewtonSolver(options).minimize(f, x0, {0, 10, 20});
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_EQ(r.x[0], 0.3);
  EXPECT_EQ(r.x[10], 1.0);
  EXPECT_EQ(r.x[20], 2.3);
  // Equal springs under equal force: uniform spacing in each segment.
  const double d1 = 0.07;
  const double d2 = 0.13;
  for (Eigen::Index i = 0; i <= 10; ++i) EXPECT_NEAR(r.x[i], 0.3 + d1 * i, 1e-12);
  for (Eigen::Index i = 10; i <= 20; ++i) EXPECT_NEAR(r.x[i], 1.0 + d2 * (i - 10), 1e-12);
  // Reactions: the full gradient at the fixed dofs is the net spring force there.
  // Forces are O(0.1) and the free gradient is <= 1e-12, so 1e-11 absolute is safe.
  EXPECT_NEAR(r.gradient[0], -SpringChain::force(d1), 1e-11);
  EXPECT_NEAR(r.gradient[10], SpringChain::force(d1) - SpringChain::force(d2), 1e-11);
  EXPECT_NEAR(r.gradient[20], SpringChain::force(d2), 1e-11);
  EXPECT_GT(std::abs(r.gradient[10]), 1e-2);  // the check above is not vacuous
}

TEST(NewtonSolver, NanRegionIsNeverAccepted) {
  const Eigen::Index n = 30;
  NanOutsideBox f(n);
  const Eigen::VectorXd x0 = f.target() + Eigen::VectorXd::Constant(n, 2.0);
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  bool all_finite = true;
  const NewtonResult r = NewtonSolver(options).minimize(f, x0, {}, [&](const NewtonIterate& it) {
    all_finite = all_finite && std::isfinite(it.energy) && std::isfinite(it.gradient_inf_norm);
  });
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_GT(f.nan_evaluations, 0);  // the full Newton step really left the domain
  EXPECT_TRUE(all_finite);
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_LT(r.log.front().step_length, 1.0);
  EXPECT_LE(r.gradient.lpNorm<Eigen::Infinity>(), 1e-10);
  // Within 2c/(1/s^3) of the pseudo-Huber target t (the coupling shifts the minimum).
  EXPECT_LT((r.x - f.target()).lpNorm<Eigen::Infinity>(), 0.1);
}

TEST(NewtonSolver, NanAtStartIsReported) {
  AlwaysNan f(5);
  const Eigen::VectorXd x0 = Eigen::VectorXd::LinSpaced(5, 0.0, 1.0);
  const NewtonResult r = NewtonSolver().minimize(f, x0);
  EXPECT_EQ(r.status, NewtonStatus::NonFiniteValue);
  EXPECT_FALSE(r.converged());
  EXPECT_NE(r.message.find("x0"), std::string::npos) << r.message;
  EXPECT_EQ(r.x, x0);
  EXPECT_EQ(r.iterations, 0);
}

TEST(NewtonSolver, MaxIterationsReturnsBestIterate) {
  const Eigen::Index n = 20;
  DoubleWellChain f(n, 0.1);
  NewtonOptions options;
  options.max_iterations = 1;
  const Eigen::VectorXd x0 = near_saddle(n);
  const double e0 = f.evaluate(x0, nullptr, nullptr);
  const NewtonResult r = NewtonSolver(options).minimize(f, x0);
  EXPECT_EQ(r.status, NewtonStatus::MaxIterations);
  EXPECT_EQ(r.iterations, 1);
  ASSERT_EQ(r.log.size(), 1u);
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_LT(r.energy, e0);
  EXPECT_EQ(r.energy, r.log[0].energy);
  Eigen::VectorXd g(n);
  EXPECT_EQ(f.evaluate(r.x, &g, nullptr), r.energy);  // x, energy, gradient belong together
  EXPECT_EQ(g, r.gradient);
  EXPECT_NE(r.message.find("max_iterations"), std::string::npos) << r.message;
}

// max_travel: the quadratic's minimiser is about 3 away from x0 = 3 (|x*| < 1); with steps
// capped at 0.4 and max_travel 1 the solve stops after the third step (travel 1.2), reporting
// TravelLimit with the current iterate, which lies 1.2 from x0 along the first steps' line.
TEST(NewtonSolver, TravelLimitStopsAfterTheStepThatReachesIt) {
  const Eigen::Index n = 50;
  TridiagonalQuadratic q(n, cosine_load(n));
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  options.max_step_inf_norm = 0.4;
  options.max_travel = 1.0;
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(n, 3.0);
  const NewtonResult r = NewtonSolver(options).minimize(q, x0);
  EXPECT_EQ(r.status, NewtonStatus::TravelLimit) << r.message;
  EXPECT_FALSE(r.converged());
  EXPECT_EQ(r.iterations, 3);
  EXPECT_NEAR((r.x - x0).lpNorm<Eigen::Infinity>(), 1.2, 1e-12);
  EXPECT_LT(r.energy, q.evaluate(x0, nullptr, nullptr));
  EXPECT_STREQ(to_string(NewtonStatus::TravelLimit), "TravelLimit");
  // Without the limit the same solve converges.
  options.max_travel = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(NewtonSolver(options).minimize(q, x0).converged());
}

TEST(NewtonSolver, InvalidInputThrows) {
  TridiagonalQuadratic q(10, Eigen::VectorXd::Ones(10));
  NewtonSolver solver;
  EXPECT_THROW(solver.minimize(q, Eigen::VectorXd::Zero(9)), std::invalid_argument);
  EXPECT_THROW(solver.minimize(q, Eigen::VectorXd::Zero(10), {10}), std::invalid_argument);
  EXPECT_THROW(solver.minimize(q, Eigen::VectorXd::Zero(10), {-1}), std::invalid_argument);
  EXPECT_THROW(solver.minimize(q, Eigen::VectorXd::Zero(10), {3, 3}), std::invalid_argument);
  NewtonOptions bad;
  bad.gradient_tolerance = 0.0;
  EXPECT_THROW(NewtonSolver{bad}, std::invalid_argument);
  bad = {};
  bad.shift_growth = 1.0;
  EXPECT_THROW(NewtonSolver{bad}, std::invalid_argument);
  bad = {};
  bad.max_travel = 0.0;
  EXPECT_THROW(NewtonSolver{bad}, std::invalid_argument);
  EXPECT_STREQ(to_string(NewtonStatus::LineSearchFailed), "LineSearchFailed");
}

}  // namespace
}  // namespace growshell
