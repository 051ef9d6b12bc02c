#pragma once
/// \file
/// What a cone study measures at every converged sample of its branch (one row of branch.csv):
/// the energies and the normalised bending energy E_b-hat, the area, the smallest gap between
/// non-neighbouring parts of the sheet, the number of folds, the core radius R_c, and for the
/// two-fold cone its distance from the improper quarter-turn symmetry S4 and the chords of its
/// two fold pairs (libshell/analysis/cone_symmetry.hpp). Also the quantities its event test
/// functions need: the gap, the signed gap and dE_b-hat/dphi_e along the branch.

#include <Eigen/Core>
#include <optional>
#include <string>

#include "libshell/analysis/cone_symmetry.hpp"
#include "libshell/analysis/self_distance.hpp"
#include "libshell/analysis/self_intersection.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// Settings of ConeSampleMeasurer. Lengths in metres.
struct ConeMeasureSettings {
  /// Reference distance below which two parts of the sheet are neighbours, never in contact
  /// (SelfDistanceOptions::exclusion_radius), > 0; the studies use the scene's
  /// (physics.contact_exclusion_radius, 8 h by default).
  double exclusion_radius = 0.0;
  /// The sheet within this reference distance of the growth centre is left out of the gap and
  /// the self-intersection test (>= 0; 0 keeps all of it).
  double core_radius = 0.0;
  /// Measure the S4 defect and the fold-pair chords (meaningful for the two-fold cone only);
  /// otherwise they are NaN.
  bool measure_symmetry = true;
};

/// The measures of one sample (SI units: J, m^2, m; E_b-hat in 1/m^2).
struct ConeSampleMeasures {
  double stretching = 0.0;
  double bending = 0.0;
  double eb_hat = 0.0;       ///< ShellEnergyBreakdown::normalized_bending
  double area = 0.0;         ///< current area
  double min_gap = 0.0;      ///< smallest_self_distance (infinite if no admissible pair)
  int folds = 0;             ///< analyze_rim_folds
  double core_radius = 0.0;  ///< radius about the growth centre holding half the stretching
                             ///< energy (0 without stretching)
  double s4_defect = 0.0;    ///< NaN if not measured
  double chord_up = 0.0;     ///< NaN if not measured
  double chord_down = 0.0;   ///< NaN if not measured
  /// Why the S4 defect is NaN although it was to be measured (e.g. a state without fold
  /// directions, such as the flat start); empty otherwise.
  std::string symmetry_note;
};

/// Measures samples of a cone branch of `model`. The smallest gap of a state is computed once
/// however many of the measures and event functions ask for it (the spatial search is the
/// expensive part). Holds a reference to the model.
class ConeSampleMeasurer {
 public:
  ConeSampleMeasurer(const ShellModel& model, const ConeMeasureSettings& settings);

  /// All the measures of the sample (at its excess angle).
  ConeSampleMeasures measure(const BranchSample& sample);

  /// Smallest gap (m) between non-neighbouring parts of the sheet at state x.
  double gap(const Eigen::VectorXd& x);

  /// The gap, negated once the mid-surface passes through itself (signed_gap).
  double signed_gap(const Eigen::VectorXd& x);

  /// E_b-hat (1/m^2) of state x at excess angle phi_e.
  double eb_hat(const Eigen::VectorXd& x, double phi_e);

  /// dE_b-hat/dphi_e along the branch at the sample, by a central difference of step 1e-4
  /// along its tangent (the sign taken so that it is the slope in phi_e).
  double eb_hat_slope(const BranchSample& sample);

 private:
  const ShellModel& model_;
  ConeMeasureSettings settings_;
  SelfDistanceOptions gap_options_;
  SelfIntersectionOptions crossing_options_;
  Eigen::VectorXd gap_state_;
  double gap_value_ = 0.0;
  /// The symmetry measures' mesh-dependent part, prepared at the first sample measured.
  std::optional<ConeSymmetryMeter> symmetry_;
};

}  // namespace growshell
