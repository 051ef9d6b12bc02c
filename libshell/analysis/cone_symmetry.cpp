#include "libshell/analysis/cone_symmetry.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <optional>
#include <string>
#include <vector>

#include "libshell/mesh/vertex_symmetry.hpp"

namespace growshell {
namespace {

/// Q(J) = Rot_J(+90 deg) (I - 2 J J^T) = [J]_x - J J^T.
Eigen::Matrix3d improper_quarter_turn(const Eigen::Vector3d& J) {
  Eigen::Matrix3d Q;
  Q << 0.0, -J.z(), J.y(), J.z(), 0.0, -J.x(), -J.y(), J.x(), 0.0;
  return Q - J * J.transpose();
}

/// Rq X = (-X_y, X_x, X_z).
Eigen::Vector3d quarter_turned(const Eigen::Vector3d& X) { return {-X.y(), X.x(), X.z()}; }

void check_radius(double radius, const char* caller) {
  if (!(radius > 0.0 && std::isfinite(radius)))
    throw std::invalid_argument(std::string(caller) + ": the radius must be finite and > 0, got " +
                                std::to_string(radius));
}

/// The quadratic q(J) = J^T S J - w.J whose minimum on the unit sphere minimises f(J).
struct SphereQuadratic {
  Eigen::Matrix3d S;
  Eigen::Vector3d w;
  double scale;  // |S| + |w|, for relative tolerances

  double value(const Eigen::Vector3d& J) const { return J.dot(S * J) - w.dot(J); }

  /// Newton on the sphere from J (normalised), with backtracking on q and the gradient
  /// direction where the Riemannian Hessian is not positive definite. Returns the iterations.
  int refine(Eigen::Vector3d& J) const {
    J.normalize();
    int it = 0;
    for (; it < 100; ++it) {
      const Eigen::Vector3d g = 2.0 * S * J - w;
      // Orthonormal tangent basis at J.
      const Eigen::Vector3d seed =
          std::abs(J.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      const Eigen::Vector3d t1 = (seed - seed.dot(J) * J).normalized();
      Eigen::Matrix<double, 3, 2> T;
      T.col(0) = t1;
      T.col(1) = J.cross(t1);
      const Eigen::Vector2d g2 = T.transpose() * g;
      if (g2.norm() <= 1e-15 * scale) break;
      const Eigen::Matrix2d H2 =
          T.transpose() * (2.0 * S) * T - J.dot(g) * Eigen::Matrix2d::Identity();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(H2);
      Eigen::Vector2d s;
      if (eig.eigenvalues()(0) > 1e-12 * scale)
        s = -eig.eigenvectors() * eig.eigenvalues().cwiseInverse().asDiagonal() *
            eig.eigenvectors().transpose() * g2;
      else
        s = -g2 / std::max(eig.eigenvalues().cwiseAbs().maxCoeff(), 1e-300);
      if (s.norm() > 0.5) s *= 0.5 / s.norm();
      const double q0 = value(J);
      Eigen::Vector3d next = (J + T * s).normalized();
      for (int half = 0; half < 60 && value(next) > q0 + 1e-15 * scale; ++half) {
        s *= 0.5;
        next = (J + T * s).normalized();
      }
      J = next;
      if (s.norm() < 1e-15) {
        ++it;
        break;
      }
    }
    return it;
  }

  /// The global minimiser on the sphere: (S - sigma I) J = w / 2 with sigma <= lambda_min(S)
  /// and |J| = 1, sigma by bisection; the hard case (w without a component along the lowest
  /// eigenvectors and too small elsewhere) adds the lowest eigenvector.
  Eigen::Vector3d global_minimiser(int& iterations) const {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
    const Eigen::Vector3d lambda = eig.eigenvalues();  // ascending
    const Eigen::Matrix3d V = eig.eigenvectors();
    const Eigen::Vector3d b = 0.5 * V.transpose() * w;
    const double tiny = 1e-14 * scale;
    const double l1 = lambda(0);
    bool hard = true;
    for (int k = 0; k < 3; ++k)
      if (lambda(k) - l1 <= tiny && std::abs(b(k)) > tiny) hard = false;
    if (hard) {
      double s = 0.0;
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k)
        if (lambda(k) - l1 > tiny) {
          c(k) = b(k) / (lambda(k) - l1);
          s += c(k) * c(k);
        }
      if (s <= 1.0) {
        c(0) = std::sqrt(1.0 - s);
        return V * c;
      }
    }
    // phi(sigma) = sum b_k^2 / (lambda_k - sigma)^2 rises from <= 1 at l1 - |b| to infinity.
    double lo = l1 - b.norm(), hi = l1;
    const auto phi = [&](double sigma) {
      double p = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double d = lambda(k) - sigma;
        if (d <= 0.0) return std::numeric_limits<double>::infinity();
        p += b(k) * b(k) / (d * d);
      }
      return p;
    };
    for (int it = 0; it < 200 && hi - lo > 4.0 * std::numeric_limits<double>::epsilon() *
                                                (std::abs(l1) + b.norm());
         ++it) {
      const double mid = 0.5 * (lo + hi);
      (phi(mid) < 1.0 ? lo : hi) = mid;
      ++iterations;
    }
    Eigen::Vector3d c;
    for (int k = 0; k < 3; ++k) c(k) = b(k) / std::max(lambda(k) - lo, 1e-300);
    return (V * c).normalized();
  }
};

/// f(J) from the residuals (not from the expanded quadratic, which cancels), with its p0.
double mean_square_residual(const Eigen::Ref<const Eigen::MatrixX3d>& y,
                            const Eigen::Ref<const Eigen::MatrixX3d>& image,
                            const Eigen::Vector3d& J, Eigen::Vector3d* fixed_point) {
  const Eigen::Matrix3d Q = improper_quarter_turn(J);
  const Eigen::Vector3d mean_y = y.colwise().mean().transpose();
  const Eigen::Vector3d mean_image = image.colwise().mean().transpose();
  const Eigen::Vector3d p0 =
      (Eigen::Matrix3d::Identity() - Q).partialPivLu().solve(mean_image - Q * mean_y);
  if (fixed_point) *fixed_point = p0;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < y.rows(); ++i)
    sum += (image.row(i).transpose() - p0 - Q * (y.row(i).transpose() - p0)).squaredNorm();
  return sum / static_cast<double>(y.rows());
}

}  // namespace

S4Defect s4_symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& reference_points,
                            const Eigen::Ref<const Eigen::MatrixX3d>& current_points,
                            const Eigen::Ref<const Eigen::MatrixX3d>& image_points, double radius) {
  const char* caller = "s4_symmetry_defect";
  check_radius(radius, caller);
  const Eigen::Index n = reference_points.rows();
  if (current_points.rows() != n || image_points.rows() != n)
    throw std::invalid_argument(std::string(caller) + ": " + std::to_string(n) +
                                " reference points, " + std::to_string(current_points.rows()) +
                                " current points and " + std::to_string(image_points.rows()) +
                                " image points: they must be matched samples");
  if (n < 3)
    throw std::invalid_argument(std::string(caller) + ": needs at least 3 samples, got " +
                                std::to_string(n));
  if (!reference_points.allFinite() || !current_points.allFinite() || !image_points.allFinite())
    throw std::invalid_argument(std::string(caller) + ": a sample holds a non-finite value");
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::abs(reference_points(i, 2)) > 1e-9 * radius)
      throw std::invalid_argument(std::string(caller) + ": reference point " + std::to_string(i) +
                                  " has z = " + std::to_string(reference_points(i, 2)) +
                                  ", off the reference plane z = 0");

  // The sheet's orientation: the normal F e_x x F e_y of the best linear map F from the
  // (centred) reference points to the state points.
  const Eigen::MatrixX2d Xc =
      reference_points.leftCols<2>().rowwise() - reference_points.leftCols<2>().colwise().mean();
  const Eigen::MatrixX3d d = current_points.rowwise() - current_points.colwise().mean();
  const Eigen::MatrixX3d dp = image_points.rowwise() - image_points.colwise().mean();
  const Eigen::Matrix2d XtX = Xc.transpose() * Xc;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> xeig(XtX);
  if (!(xeig.eigenvalues()(0) > 1e-12 * xeig.eigenvalues()(1)))
    throw std::invalid_argument(std::string(caller) +
                                ": the reference points are collinear (or coincide)");
  const Eigen::Matrix<double, 3, 2> F = d.transpose() * Xc * XtX.inverse();
  const Eigen::Vector3d sheet_normal = F.col(0).cross(F.col(1));

  // f(J) = (sum |d'|^2 + |d|^2 - 2 (w.J - J^T S J)) / n.
  const Eigen::Matrix3d C = dp.transpose() * d;
  SphereQuadratic q;
  q.S = 0.5 * (C + C.transpose());
  q.w = Eigen::Vector3d(C(2, 1) - C(1, 2), C(0, 2) - C(2, 0), C(1, 0) - C(0, 1));
  q.scale = q.S.norm() + q.w.norm() + std::numeric_limits<double>::min();

  S4Defect out;
  std::vector<Eigen::Vector3d> candidates;
  candidates.push_back(q.global_minimiser(out.iterations));
  {
    // The -1 eigenvector of the best improper orthogonal map d -> d' (Kabsch with det -1).
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Vector3d s(1.0, 1.0, -svd.matrixU().determinant() * svd.matrixV().determinant());
    const Eigen::Matrix3d Qk = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
    const Eigen::JacobiSVD<Eigen::Matrix3d> null(Qk + Eigen::Matrix3d::Identity(),
                                                 Eigen::ComputeFullV);
    candidates.push_back(null.matrixV().col(2));
    // The normal of the best-fit plane of the state points.
    const Eigen::JacobiSVD<Eigen::MatrixX3d> plane(d, Eigen::ComputeThinV);
    candidates.push_back(plane.matrixV().col(2));
    candidates.push_back(Eigen::Vector3d::UnitZ());
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < candidates.size(); ++c)
    for (double sign : {1.0, -1.0}) {
      if (c == 0 && sign < 0.0) continue;  // the global minimiser needs no mirror image
      Eigen::Vector3d J = sign * candidates[c];
      if (!(J.norm() > 0.5)) continue;
      out.iterations += q.refine(J);
      Eigen::Vector3d p0;
      const double f = mean_square_residual(current_points, image_points, J, &p0);
      if (f < best) {
        best = f;
        out.axis = J;
        out.fixed_point = p0;
      }
    }
  out.defect = std::sqrt(best) / radius;
  // Q(-J) = Rot_J(-90 deg) (I - 2 J J^T): report J on the sheet's side with the sense.
  if (out.axis.dot(sheet_normal) < 0.0) {
    out.axis = -out.axis;
    out.reversed_sense = true;
  }
  return out;
}

S4Defect s4_symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& reference_points,
                            const StateEvaluator& y, double radius) {
  if (!y) throw std::invalid_argument("s4_symmetry_defect: the state evaluator is empty");
  Eigen::MatrixX3d current(reference_points.rows(), 3), image(reference_points.rows(), 3);
  for (Eigen::Index i = 0; i < reference_points.rows(); ++i) {
    const Eigen::Vector3d X = reference_points.row(i).transpose();
    current.row(i) = y(X).transpose();
    image.row(i) = y(quarter_turned(X)).transpose();
  }
  return s4_symmetry_defect(reference_points, current, image, radius);
}

namespace {

/// Reference limit positions of the sheet vertices relative to the growth centre (z = 0), and R.
Eigen::MatrixX3d centred_reference(const ShellModel& model, double& radius) {
  const Eigen::Vector3d c = model.settings().growth.center;
  Eigen::MatrixX3d X = model.limit_positions(model.reference_positions());
  X.col(0).array() -= c.x();
  X.col(1).array() -= c.y();
  X.col(2).setZero();
  radius = 0.0;
  const Eigen::VectorXd& P = model.reference_positions();
  for (int v : model.sheet_vertices())
    radius = std::max(radius, (P.segment<2>(3 * v) - c.head<2>()).norm());
  return X;
}

void check_state(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                 const char* caller) {
  if (x.size() != model.dimension())
    throw std::invalid_argument(std::string(caller) + ": the state has " + std::to_string(x.size()) +
                                " entries, the model " + std::to_string(model.dimension()));
}

/// Image sheet index of every sheet vertex under the quarter turn about the growth centre, or
/// empty with a reason (a vertex without an image, or a face whose image is no face).
std::vector<int> sheet_quarter_turn(const ShellModel& model, double radius, std::string& reason) {
  const Eigen::VectorXd& P = model.reference_positions();
  Eigen::MatrixX3d positions =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(P.data(), P.size() / 3, 3);
  positions.leftCols<2>().rowwise() -= model.settings().growth.center.head<2>().transpose();
  std::optional<LinearVertexSymmetry> turn;
  try {
    turn = quarter_turn_symmetry(positions, 1e-9 * radius);
    check_maps_faces_onto_faces(model.topology(), *turn);
  } catch (const std::invalid_argument& e) {
    reason = e.what();
    return {};
  }
  const auto& sheet = model.sheet_vertices();
  std::vector<int> sheet_index(static_cast<std::size_t>(model.topology().num_vertices()), -1);
  for (std::size_t k = 0; k < sheet.size(); ++k)
    sheet_index[static_cast<std::size_t>(sheet[k])] = static_cast<int>(k);
  std::vector<int> image(sheet.size());
  for (std::size_t k = 0; k < sheet.size(); ++k) {
    image[k] = sheet_index[static_cast<std::size_t>(turn->image[static_cast<std::size_t>(sheet[k])])];
    if (image[k] < 0) {
      reason = "the quarter turn maps sheet vertex " + std::to_string(sheet[k]) +
               " onto a ghost vertex";
      return {};
    }
  }
  return image;
}

/// The S4 defect of the sheet vertices' limit positions `current`, their images given by the
/// quarter-turn vertex map `image`.
S4Defect vertex_map_defect(const Eigen::MatrixX3d& current, const Eigen::MatrixX3d& reference,
                           const std::vector<int>& image, double radius) {
  Eigen::MatrixX3d turned(current.rows(), 3);
  for (Eigen::Index k = 0; k < current.rows(); ++k)
    turned.row(k) = current.row(image[static_cast<std::size_t>(k)]);
  return s4_symmetry_defect(reference, current, turned, radius);
}

}  // namespace

S4Defect s4_symmetry_defect(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x) {
  check_state(model, x, "s4_symmetry_defect");
  double radius = 0.0;
  const Eigen::MatrixX3d reference = centred_reference(model, radius);
  std::string reason;
  const std::vector<int> image = sheet_quarter_turn(model, radius, reason);
  if (image.empty())
    throw std::invalid_argument(
        "s4_symmetry_defect: the reference mesh lacks the quarter-turn vertex symmetry about the "
        "growth centre, so the S4 images of its vertices are not vertices (" +
        reason + "); measure_cone_symmetry evaluates them on the surface instead");
  return vertex_map_defect(model.limit_positions(x), reference, image, radius);
}

FoldDirections fold_directions(const StateEvaluator& y, const Eigen::Vector3d& axis,
                               const Eigen::Vector3d& apex, double radius,
                               const FoldChordOptions& options) {
  const char* caller = "fold_directions";
  check_radius(radius, caller);
  if (!y) throw std::invalid_argument("fold_directions: the state evaluator is empty");
  if (!axis.allFinite() || std::abs(axis.norm() - 1.0) > 1e-9)
    throw std::invalid_argument("fold_directions: the axis J must be a finite unit vector");
  const int m = options.rim_samples;
  if (m < 8)
    throw std::invalid_argument("fold_directions: needs at least 8 rim samples, got " +
                                std::to_string(m));
  if (!apex.allFinite()) throw std::invalid_argument("fold_directions: the apex is not finite");
  double a = 0.0, b = 0.0;
  for (int k = 0; k < m; ++k) {
    const double t = 2.0 * std::numbers::pi * k / m;
    const double height =
        axis.dot(y(Eigen::Vector3d(radius * std::cos(t), radius * std::sin(t), 0.0)) - apex);
    a += height * std::cos(2.0 * t);
    b += height * std::sin(2.0 * t);
  }
  a *= 2.0 / m;
  b *= 2.0 / m;
  FoldDirections out;
  out.amplitude = std::hypot(a, b);
  if (!(out.amplitude > 1e-12 * radius))
    throw std::invalid_argument(
        "fold_directions: the rim's height along J has no cos 2 theta / sin 2 theta component "
        "(amplitude " + std::to_string(out.amplitude) + " m): no fold directions");
  // a cos 2t + b sin 2t = amplitude cos 2 (t - t_u).
  out.up_angle = 0.5 * std::atan2(b, a);
  if (out.up_angle <= -0.5 * std::numbers::pi) out.up_angle += std::numbers::pi;
  out.down_angle = out.up_angle + 0.5 * std::numbers::pi;
  return out;
}

FoldChords fold_pair_chords(const StateEvaluator& y, const FoldDirections& folds,
                            const Eigen::Vector3d& apex, double radius,
                            const FoldChordOptions& options) {
  check_radius(radius, "fold_pair_chords");
  if (!y) throw std::invalid_argument("fold_pair_chords: the state evaluator is empty");
  if (options.radius_fractions.empty())
    throw std::invalid_argument("fold_pair_chords: no radii to measure the chords at");
  for (double f : options.radius_fractions)
    if (!(f > 0.0 && f <= 1.0))
      throw std::invalid_argument("fold_pair_chords: radius fraction " + std::to_string(f) +
                                  " is outside (0, 1]");
  if (!apex.allFinite()) throw std::invalid_argument("fold_pair_chords: the apex is not finite");
  const auto chord = [&](double theta, double& where) {
    double best = std::numeric_limits<double>::infinity();
    for (double f : options.radius_fractions) {
      const double r = f * radius;
      const Eigen::Vector3d p = y(Eigen::Vector3d(r * std::cos(theta), r * std::sin(theta), 0.0));
      const Eigen::Vector3d q = y(Eigen::Vector3d(-r * std::cos(theta), -r * std::sin(theta), 0.0));
      const double length = 0.5 * ((p - apex).norm() + (q - apex).norm());
      if (!(length > 0.0))
        throw std::invalid_argument("fold_pair_chords: a fold point at radius " +
                                    std::to_string(r) + " m sits at the apex");
      const double c = (p - q).norm() / length;
      if (c < best) {
        best = c;
        where = r;
      }
    }
    return best;
  };
  FoldChords out;
  out.chord_up = chord(folds.up_angle, out.radius_up);
  out.chord_down = chord(folds.down_angle, out.radius_down);
  return out;
}

ConeSymmetryMeter::ConeSymmetryMeter(const ShellModel& model) : model_(model) {
  reference_ = centred_reference(model, radius_);
  std::string reason;
  image_ = sheet_quarter_turn(model, radius_, reason);
  if (image_.empty()) {
    // The quarter-turned material points of the sheet vertices, in the model's frame.
    const Eigen::Vector3d c = model.settings().growth.center;
    Eigen::MatrixX3d points(reference_.rows(), 3);
    for (Eigen::Index k = 0; k < reference_.rows(); ++k) {
      const Eigen::Vector3d X = quarter_turned(reference_.row(k).transpose());
      points.row(k) << X.x() + c.x(), X.y() + c.y(), c.z();
    }
    turned_.emplace(model, points);
  }
  // The rim (sheet vertices next to the ghost layer) tells a disc from a ring: a ring has rim
  // vertices well inside R. (Not a vertex sitting exactly at the centre: on a mesh with
  // extraordinary vertices the centre vertex's limit position is off the centre.)
  const auto& sheet = model.sheet_vertices();
  std::vector<char> in_sheet(static_cast<std::size_t>(model.topology().num_vertices()), 0);
  for (int v : sheet) in_sheet[static_cast<std::size_t>(v)] = 1;
  std::vector<Eigen::Index> rim;
  double r_min = std::numeric_limits<double>::infinity(), r_max = 0.0;
  for (std::size_t k = 0; k < sheet.size(); ++k) {
    bool on_rim = false;
    for (int u : model.topology().one_ring(sheet[k]))
      on_rim = on_rim || !in_sheet[static_cast<std::size_t>(u)];
    if (!on_rim) continue;
    const double r = reference_.row(static_cast<Eigen::Index>(k)).norm();
    r_min = std::min(r_min, r);
    r_max = std::max(r_max, r);
    rim.push_back(static_cast<Eigen::Index>(k));
  }
  if (r_min < 0.9 * r_max) {
    inner_radius_ = r_min;
    for (Eigen::Index k : rim)
      if (reference_.row(k).norm() < 0.5 * (r_min + r_max)) inner_rim_.push_back(k);
  }
}

S4Defect ConeSymmetryMeter::s4_of(const Eigen::Ref<const Eigen::VectorXd>& x,
                                  const Eigen::MatrixX3d& limit) const {
  if (!image_.empty()) return vertex_map_defect(limit, reference_, image_, radius_);
  return s4_symmetry_defect(reference_, limit, turned_->positions(x), radius_);
}

S4Defect ConeSymmetryMeter::s4(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  check_state(model_, x, "ConeSymmetryMeter::s4");
  return s4_of(x, model_.limit_positions(x));
}

ConeSymmetry ConeSymmetryMeter::measure(const Eigen::Ref<const Eigen::VectorXd>& x,
                                        const FoldChordOptions& options) const {
  check_state(model_, x, "measure_cone_symmetry");
  const Eigen::Vector3d c = model_.settings().growth.center;
  const StateEvaluator absolute = sheet_state_evaluator(model_, x);
  const StateEvaluator y = [&](const Eigen::Vector3d& X) {
    return absolute(Eigen::Vector3d(X.x() + c.x(), X.y() + c.y(), c.z()));
  };
  const Eigen::MatrixX3d limit = model_.limit_positions(x);
  ConeSymmetry out;
  out.vertex_map = !image_.empty();
  out.s4 = s4_of(x, limit);
  // The apex: the state at the growth centre for a disc, the centroid of the inner rim for a
  // ring, whose chords skip the radius fractions inside its hole.
  Eigen::Vector3d apex = y(Eigen::Vector3d::Zero());
  FoldChordOptions ring_options = options;
  if (inner_radius_) {
    apex.setZero();
    for (Eigen::Index k : inner_rim_) apex += limit.row(k).transpose();
    apex /= std::max<double>(static_cast<double>(inner_rim_.size()), 1.0);
    std::erase_if(ring_options.radius_fractions,
                  [&](double f) { return f * radius_ < *inner_radius_; });
    if (ring_options.radius_fractions.empty()) ring_options.radius_fractions = {1.0};
  }
  out.folds = fold_directions(y, out.s4.axis, apex, radius_, ring_options);
  out.chords = fold_pair_chords(y, out.folds, apex, radius_, ring_options);
  return out;
}

ConeSymmetry measure_cone_symmetry(const ShellModel& model,
                                   const Eigen::Ref<const Eigen::VectorXd>& x,
                                   const FoldChordOptions& options) {
  check_state(model, x, "measure_cone_symmetry");
  return ConeSymmetryMeter(model).measure(x, options);
}

}  // namespace growshell
