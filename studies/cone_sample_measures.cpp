#include "studies/cone_sample_measures.hpp"

#include <limits>
#include <stdexcept>

#include "libshell/analysis/cone_symmetry.hpp"
#include "libshell/analysis/core_radius.hpp"
#include "libshell/analysis/rim_folds.hpp"

namespace growshell {

ConeSampleMeasurer::ConeSampleMeasurer(const ShellModel& model, const ConeMeasureSettings& settings)
    : model_(model), settings_(settings) {
  gap_options_.exclusion_radius = settings.exclusion_radius;
  gap_options_.core_radius = settings.core_radius;
  gap_options_.core_center = model.settings().growth.center;
  crossing_options_.exclusion_radius = gap_options_.exclusion_radius;
  crossing_options_.core_radius = gap_options_.core_radius;
  crossing_options_.core_center = gap_options_.core_center;
}

double ConeSampleMeasurer::gap(const Eigen::VectorXd& x) {
  if (gap_state_.size() != x.size() || gap_state_ != x) {
    gap_value_ = smallest_self_distance(model_, x, gap_options_).distance;
    gap_state_ = x;
  }
  return gap_value_;
}

double ConeSampleMeasurer::signed_gap(const Eigen::VectorXd& x) {
  return growshell::signed_gap(find_self_intersection(model_, x, crossing_options_), gap(x));
}

double ConeSampleMeasurer::eb_hat(const Eigen::VectorXd& x, double phi_e) {
  return model_.energy_breakdown(x, phi_e).normalized_bending();
}

double ConeSampleMeasurer::eb_hat_slope(const BranchSample& s) {
  const double eps = 1e-4;
  const double d = (eb_hat(s.x + eps * s.tangent_state, s.parameter + eps * s.tangent_parameter) -
                    eb_hat(s.x - eps * s.tangent_state, s.parameter - eps * s.tangent_parameter)) /
                   (2 * eps);
  return s.tangent_parameter >= 0 ? d : -d;
}

ConeSampleMeasures ConeSampleMeasurer::measure(const BranchSample& s) {
  ConeSampleMeasures m;
  const ShellEnergyBreakdown e = model_.energy_breakdown(s.x, s.parameter);
  m.stretching = e.stretching;
  m.bending = e.bending;
  m.eb_hat = e.normalized_bending();
  m.area = e.current_area;
  m.min_gap = gap(s.x);
  m.folds = analyze_rim_folds(model_, s.x).folds;
  const Eigen::Vector3d center = model_.settings().growth.center;
  m.core_radius =
      e.stretching > 0.0 ? stretching_core_radius(model_, s.x, s.parameter, 0.5, center).radius : 0.0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  m.s4_defect = m.chord_up = m.chord_down = nan;
  if (settings_.measure_symmetry) {
    try {
      if (!symmetry_) symmetry_.emplace(model_);
      const ConeSymmetry symmetry = symmetry_->measure(s.x);
      m.s4_defect = symmetry.s4.defect;
      m.chord_up = symmetry.chords.chord_up;
      m.chord_down = symmetry.chords.chord_down;
    } catch (const std::invalid_argument& error) {
      m.symmetry_note = error.what();
    }
  }
  return m;
}

}  // namespace growshell
