#include "studies/pattern_orientation_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/objective_at_parameter.hpp"
#include "libshell/analysis/cone_symmetry.hpp"
#include "libshell/analysis/state_transfer.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"
#include "studies/scene_contact_penalty.hpp"
#include "studies/turn_free_stability_index.hpp"

namespace growshell {

namespace {

/// Per element: whether its centroid (reference) lies within `radius` of the growth centre.
std::vector<char> core_elements(const ShellModel& model, double radius) {
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::Vector3d& c = model.settings().growth.center;
  std::vector<char> inside(static_cast<std::size_t>(model.num_elements()));
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    const auto& face = model.topology().face(model.patches().face[static_cast<std::size_t>(e)]);
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const int v : face) centroid += Eigen::Vector2d(X(3 * v), X(3 * v + 1)) / 3.0;
    inside[static_cast<std::size_t>(e)] = (centroid - c.head<2>()).norm() < radius;
  }
  return inside;
}

/// The elastic energy (J) of the elements inside (first) and outside (second) the core.
std::pair<double, double> split_energy(const ShellModel& model,
                                       const Eigen::Ref<const Eigen::VectorXd>& x, double phi_e,
                                       const std::vector<char>& inside) {
  double core = 0.0, outside = 0.0;
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    const ShellEnergyBreakdown part = model.element_breakdown(x, phi_e, e);
    (inside[static_cast<std::size_t>(e)] ? core : outside) += part.stretching + part.bending;
  }
  return {core, outside};
}

double penalised_energy(const ShellModel& model, const ContactProxy& proxy,
                        const Eigen::Ref<const Eigen::VectorXd>& x, double phi_e,
                        const ContactBranchOptions& o) {
  PenalizedShell total(model, proxy, near_penalty_pairs(proxy, x, o), o);
  return total.energy.evaluate(x, phi_e, nullptr, nullptr);
}

}  // namespace

PatternOrientationCheckOptions scene_orientation_check_options(const Scene& scene,
                                                               const ShellModel& model,
                                                               const ContactProxy& proxy) {
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  PatternOrientationCheckOptions o;
  for (const double t : scene.study.orientation_check_turns)
    o.turns.push_back(t * std::numbers::pi / 180.0);
  o.contact = scene_contact_penalty(scene, model, proxy);
  o.relaxation = scene_penalty_relaxation(scene, model);
  o.relaxation.max_step_inf_norm = 0.25 * h;
  o.relaxation.max_iterations = 1000;
  o.core_radius = h;
  return o;
}

double PatternOrientationCheck::largest_energy_change() const {
  double largest = 0.0;
  for (const TurnedPatternState& s : turned)
    if (s.converged) largest = std::max(largest, std::abs(s.energy_relative));
  return largest;
}

double PatternOrientationCheck::lowest_energy_relative() const {
  double lowest = std::numeric_limits<double>::infinity();
  for (const TurnedPatternState& s : turned)
    if (s.converged) lowest = std::min(lowest, s.energy_relative);
  return std::isfinite(lowest) ? lowest : 0.0;
}

PatternOrientationCheck check_pattern_orientation(const ShellModel& model,
                                                  const ContactProxy& proxy,
                                                  const Eigen::Ref<const Eigen::VectorXd>& x,
                                                  double phi_e,
                                                  const std::vector<Eigen::Index>& pins,
                                                  const PatternOrientationCheckOptions& options) {
  if (x.size() != model.dimension())
    throw std::invalid_argument("check_pattern_orientation: the state needs " +
                                std::to_string(model.dimension()) + " entries");
  if (options.turns.empty())
    throw std::invalid_argument("PatternOrientationCheckOptions::turns is empty");
  for (const double t : options.turns)
    if (!std::isfinite(t))
      throw std::invalid_argument("PatternOrientationCheckOptions::turns holds a non-finite turn");
  if (!(options.core_radius > 0.0 && std::isfinite(options.core_radius)))
    throw std::invalid_argument(
        "PatternOrientationCheckOptions::core_radius must be finite and > 0");
  const ContactBranchOptions& o = options.contact;
  const std::vector<char> inside = core_elements(model, options.core_radius);

  PatternOrientationCheck out;
  out.phi_e = phi_e;
  out.energy = penalised_energy(model, proxy, x, phi_e, o);
  const ConeSymmetry traced_symmetry = measure_cone_symmetry(model, x);
  out.s4_defect = traced_symmetry.s4.defect;
  out.fold_angle = traced_symmetry.folds.up_angle;
  const auto [traced_core, traced_outside] = split_energy(model, x, phi_e, inside);
  const double traced_penalty = out.energy - traced_core - traced_outside;

  for (const double turn : options.turns) {
    TurnedPatternState s;
    s.turn = turn;
    s.x = transfer_state(model, x, model, turn);
    const std::vector<Eigen::Index> state_pins = rigid_pins_for_state(model, s.x, pins, o);
    const ContactRelaxation relaxed =
        relax_with_contact(model, phi_e, proxy, s.x, state_pins, o, options.relaxation);
    s.converged = relaxed.relaxed;
    s.energy = relaxed.energy;
    if (!s.converged) {
      s.message = relaxed.message;
      out.turned.push_back(std::move(s));
      continue;
    }
    const ShellEnergyBreakdown parts = model.energy_breakdown(s.x, phi_e);
    s.stretching = parts.stretching;
    s.bending = parts.bending;
    const ConeSymmetry symmetry = measure_cone_symmetry(model, s.x);
    s.s4_defect = symmetry.s4.defect;
    s.fold_angle = symmetry.folds.up_angle;
    s.chord_up = symmetry.chords.chord_up;
    s.chord_down = symmetry.chords.chord_down;
    s.energy_relative = (s.energy - out.energy) / out.energy;
    const auto [core, outside] = split_energy(model, s.x, phi_e, inside);
    s.energy_change_core = core - traced_core;
    s.energy_change_outside =
        outside - traced_outside + (s.energy - core - outside) - traced_penalty;
    PenalizedShell total(model, proxy, near_penalty_pairs(proxy, s.x, o), o);
    EigenpairOptions eig;
    eig.count = 1;
    ObjectiveAtParameter at(total.energy, phi_e);
    s.lowest_eigenvalue = lowest_eigenpairs(at, s.x, state_pins, eig).values[0];
    TurnFreeStabilityIndex index(total.energy, model, state_pins);
    s.turn_free_index = index.at(s.x, phi_e);
    out.turned.push_back(std::move(s));
  }
  return out;
}

}  // namespace growshell
