#pragma once
/// \file
/// How far a two-fold e-cone is from its symmetry group D2d, and the gaps of its two fold
/// pairs.
///
/// The n = 2 e-cone (docs/physics.md, "Stability of the h -> 0 cone") has two mirror planes
/// through its axis J and the improper quarter turn S4: a quarter turn about J followed by the
/// reflection across the plane normal to J through a fixed point p0; S4 maps the up-folds onto
/// the down-folds. On the reference disc (centre at the origin, plane z = 0) S4 acts as the
/// quarter turn Rq (X, Y) -> (-Y, X), and on the state as Q = Rot_J(+90 deg) (I - 2 J J^T)
/// = [J]_x - J J^T about p0: y(Rq X) = p0 + Q (y(X) - p0). The mode B2 of the cone's second
/// variation breaks S4 but keeps both mirrors: one fold pair closes, the other opens.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "libshell/analysis/state_evaluator.hpp"
#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// Result of s4_symmetry_defect.
struct S4Defect {
  /// min over J and p0 of sqrt(mean_i |y'_i - p0 - Q (y_i - p0)|^2) / R (dimensionless): 0 for
  /// a state with the S4 symmetry, of the order of the displacement that breaks it over R.
  double defect = 0.0;
  /// The axis J (unit vector) of the best improper quarter turn, oriented like the sheet: on
  /// the side of the normal F e_x x F e_y of the best linear map F from the reference points
  /// to the state points.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  /// Its fixed point p0 (m): the apex of a symmetric cone.
  Eigen::Vector3d fixed_point = Eigen::Vector3d::Zero();
  /// false: the best Q turns by +90 deg about the oriented J. That is the sense of every
  /// S4-symmetric smooth state with the images at Rq X, whatever its placement, proper or
  /// mirrored (differentiating y(Rq X) = p0 + Q (y(X) - p0) shows that the sheet's normal and
  /// the sense of Q about it go together). true: it turns by -90 deg: the image points match
  /// the clockwise quarter turn Rq^-1 X better (a caller's convention error), or the sheet is
  /// folded so far that F e_x x F e_y, an average over the whole sheet, points to the wrong
  /// side. Minimising over both senses keeps the defect a measure of the symmetry alone.
  bool reversed_sense = false;
  /// Iterations of the minimisation over J (secular-equation bisection and the Newton
  /// refinements together).
  int iterations = 0;
};

/// The S4 defect of matched samples: reference points X_i (one row each, m, about the disc
/// centre at the origin, z = 0), the state's points y_i = y(X_i) (m) and the image points
/// y'_i = y(Rq X_i) (m), the state at the quarter-turned material points (for a mesh with the
/// quarter-turn vertex symmetry the points of the image vertices; otherwise evaluated on the
/// surface); `radius` R (m) makes the defect dimensionless.
///
/// For given J the best p0 is closed form, p0 = (I - Q)^-1 (mean y' - Q mean y) (I - Q is
/// invertible for an improper quarter turn), which leaves f(J) = mean |d'_i - Q d_i|^2 for the
/// centred points d, d'. Because Q = [J]_x - J J^T is quadratic in J, f is a quadratic on the
/// unit sphere, f = (sum |d'|^2 + |d|^2 - 2 (w.J - J^T S J)) / n with S the symmetric part and
/// w the axial vector of the antisymmetric part of sum d'_i d_i^T. Its global minimum is found
/// from the secular equation of the trust-region subproblem (bisection to rounding, the hard
/// case included), then refined by Newton on the sphere; Newton is also started from the -1
/// eigenvector of the best improper orthogonal map (Kabsch), the normal of the best-fit plane
/// of the state points and the z axis, each with both signs, and the smallest objective wins,
/// so no starting guess decides the answer. J ranges over the whole sphere, which covers both
/// senses of the quarter turn about the unoriented axis (Rot_{-J}(t) = Rot_J(-t) while
/// I - 2 J J^T is even in J): the result is the smaller of the two senses' minima, and
/// reversed_sense says which it was. The defect itself is evaluated from the residuals, not
/// from the expanded quadratic, so that it is accurate down to rounding of the points.
/// Deterministic. Throws std::invalid_argument naming the problem for matrices of different
/// row counts, fewer than 3 samples, a non-finite value, a reference point off the plane
/// z = 0 (by more than 1e-9 R), collinear reference points, or a radius that is not finite
/// and > 0.
S4Defect s4_symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& reference_points,
                            const Eigen::Ref<const Eigen::MatrixX3d>& current_points,
                            const Eigen::Ref<const Eigen::MatrixX3d>& image_points, double radius);

/// The same with the state given as an evaluator: y_i = y(X_i), y'_i = y(Rq X_i).
S4Defect s4_symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& reference_points,
                            const StateEvaluator& y, double radius);

/// The S4 defect of the state x (control points, vertex-major like ShellModel, m) of `model`
/// at the sheet vertices, using their limit positions (ShellModel::limit_positions) as the
/// samples and the vertex map of the quarter turn about the growth centre as the image: exact,
/// no interpolation. R is the largest reference distance of a sheet vertex from the growth
/// centre. Throws std::invalid_argument if the reference control mesh lacks the quarter-turn
/// vertex symmetry within 1e-9 R (the message names the vertex or face that lacks it, e.g. for
/// the hexagonal disc of make_disc_mesh, which has only 60-degree turns and mirrors; use
/// measure_cone_symmetry there), or x does not have model.dimension() entries.
S4Defect s4_symmetry_defect(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x);

/// Directions of the folds of a two-fold state, as reference polar angles (rad) about the
/// disc centre.
struct FoldDirections {
  /// Angle theta_u of the first up-fold, in (-pi/2, pi/2]; the second up-fold is at theta_u +
  /// pi, the down-folds at theta_u +- pi/2.
  double up_angle = 0.0;
  /// theta_u + pi/2: the first down-fold.
  double down_angle = 0.0;
  /// Amplitude (m) of the cos 2 theta / sin 2 theta component of the rim's height along J.
  double amplitude = 0.0;
};

/// Options of fold_directions and fold_pair_chords.
struct FoldChordOptions {
  /// Reference radii, as fractions of R in (0, 1], over which the smallest chord is taken.
  std::vector<double> radius_fractions = {0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  /// Equally spaced rim samples for the Fourier component of the height (>= 8).
  int rim_samples = 64;
};

/// The fold directions of y: the extremes of the height J.(y(R, theta) - apex) of the rim
/// along the axis J (unit; e.g. S4Defect::axis), from its cos 2 theta / sin 2 theta Fourier
/// component over options.rim_samples equally spaced angles ("up" is +J). The apex (m) is
/// the state's point at the centre, y(0) for a disc. Throws
/// std::invalid_argument for a radius that is not finite and > 0, a J that is not a finite
/// unit vector (within 1e-9), too few rim samples, or a rim without that component
/// (amplitude below 1e-12 R: flat or axisymmetric, no fold directions).
FoldDirections fold_directions(const StateEvaluator& y, const Eigen::Vector3d& axis,
                               const Eigen::Vector3d& apex, double radius,
                               const FoldChordOptions& options = {});

/// The gaps of the two fold pairs (dimensionless).
struct FoldChords {
  /// min over r of |y(r, theta_u) - y(r, theta_u + pi)| / (mean distance of the two points
  /// from the apex): the chord between the up-folds over the generator length; for the
  /// h -> 0 cone at phi_e = 5.0 it is 0.677, and 0 when the folds touch.
  double chord_up = 0.0;
  /// The same for the down-folds at theta_u +- pi/2. A state with S4 has chord_down = chord_up;
  /// B2 moves them apart in opposite directions.
  double chord_down = 0.0;
  /// Reference radii (m) where the minima were attained.
  double radius_up = 0.0, radius_down = 0.0;
};

/// The fold-pair chords of y over options.radius_fractions of R, with the apex (m) as in
/// fold_directions. (The mean of the two generator lengths equals |y(r, theta) - apex| for a
/// state with the half turn about J.) Throws std::invalid_argument for a radius that is not
/// finite and > 0, an empty set of radii or one outside (0, 1], a non-finite apex, or a point
/// at the apex (zero generator length).
FoldChords fold_pair_chords(const StateEvaluator& y, const FoldDirections& folds,
                            const Eigen::Vector3d& apex, double radius,
                            const FoldChordOptions& options = {});

/// All of it for one state.
struct ConeSymmetry {
  S4Defect s4;
  FoldDirections folds;  ///< along s4.axis
  FoldChords chords;
  /// true: the image points were the vertices' (the mesh has the quarter turn); false: they
  /// were evaluated on the limit surface at the quarter-turned material points
  /// (sheet_state_evaluator). Both are exact.
  bool vertex_map = false;
};

/// S4 defect, fold directions and chords of the state x of `model` (about the growth
/// centre): the S4 defect as s4_symmetry_defect(model, x) where the reference mesh has the
/// quarter-turn vertex symmetry, otherwise from the sheet vertices and the limit surface at
/// their quarter-turned reference points (sheet_state_evaluator); the folds and chords on the
/// limit surface either way. The apex is the limit position of the sheet vertex at
/// the growth centre, or for a ring the centroid of its inner rim's (as analyze_rim_folds);
/// a ring's chords skip the radius fractions inside its hole (and use the rim alone if none
/// is left). Throws std::invalid_argument as the functions it calls. Prepares a
/// ConeSymmetryMeter for the call: to measure many states of one model, hold one.
ConeSymmetry measure_cone_symmetry(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                   const FoldChordOptions& options = {});

/// measure_cone_symmetry for many states of one model: what depends on the mesh alone (the
/// centred reference, and the quarter-turn vertex map or, on a mesh without it, the
/// quarter-turned sheet vertices located on the reference limit surface as a
/// MaterialPointSampling) is prepared once, so that the S4 defect of a state on a Gmsh disc is
/// a sparse product instead of a search for each point. Holds a reference to the model, which
/// must outlive it.
class ConeSymmetryMeter {
 public:
  /// Throws std::invalid_argument as measure_cone_symmetry for a model without elements.
  explicit ConeSymmetryMeter(const ShellModel& model);
  /// measure_cone_symmetry(model, x, options).
  ConeSymmetry measure(const Eigen::Ref<const Eigen::VectorXd>& x,
                       const FoldChordOptions& options = {}) const;
  /// Its S4 defect alone (measure(x).s4), without the folds and chords.
  S4Defect s4(const Eigen::Ref<const Eigen::VectorXd>& x) const;

 private:
  /// The S4 defect of x, whose sheet vertices' limit positions are `limit`.
  S4Defect s4_of(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::MatrixX3d& limit) const;

  const ShellModel& model_;
  double radius_ = 0.0;
  Eigen::MatrixX3d reference_;
  std::vector<int> image_;  // sheet index of each sheet vertex's quarter turn, if the mesh has it
  std::optional<MaterialPointSampling> turned_;  // else the quarter-turned points
  std::optional<double> inner_radius_;           // a ring's: its inner rim's smallest radius
  std::vector<Eigen::Index> inner_rim_;          // a ring's inner rim (sheet indices), for the apex
};

}  // namespace growshell
