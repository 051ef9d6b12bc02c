#include "studies/hard_contact_check.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "libshell/analysis/cone_symmetry.hpp"
#include "libshell/analysis/contact_zones.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/contact/hard_contact_solve_options.hpp"
#include "solvers/contact/penalty_warm_start.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "studies/pattern_orientation_check.hpp"
#include "studies/turn_free_stability_index.hpp"

namespace growshell {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The smallest distance over the vertex-triangle and edge-edge pairs of x nearer than
/// `reach` and farther apart in the reference than the exclusion radius, or +infinity.
double smallest_distance(const ContactProxy& proxy, const Eigen::VectorXd& x,
                         double exclusion_radius, double reach) {
  return smallest_pair_distance(proxy, near_contact_pairs(proxy, x, reach, exclusion_radius), x);
}

double s4_defect(const ShellModel& model, const Eigen::VectorXd& x) {
  try {
    return measure_cone_symmetry(model, x).s4.defect;
  } catch (const std::exception&) {
    return kNaN;  // no fold directions: no S4 defect
  }
}

double elastic_energy(const ShellModel& model, const Eigen::VectorXd& x, double phi_e) {
  const ShellEnergyBreakdown e = model.energy_breakdown(x, phi_e);
  return e.stretching + e.bending;
}

}  // namespace

HardContactCheck check_hard_contact(const Scene& scene, const ShellModel& model,
                                    const ContactProxy& proxy, const BranchSample& state,
                                    int ipopt_print_level) {
  if (state.x.size() != model.dimension())
    throw std::invalid_argument("check_hard_contact: the state has " +
                                std::to_string(state.x.size()) + " unknowns, the model " +
                                std::to_string(model.dimension()));
  const PatternOrientationCheckOptions studies =
      scene_orientation_check_options(scene, model, proxy);
  const ContactBranchOptions& penalty = studies.contact;
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  ContactSolveOptions options =
      hard_contact_solve_options(model, h, penalty.contact_distance, penalty.exclusion_radius,
                                 penalty.candidate_margin, studies.relaxation);
  options.minimizer.print_level = ipopt_print_level;
  const Eigen::VectorXd& X = model.reference_positions();
  const auto pinned = mirror_axis_pinned_dofs(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
      model.sheet_vertices(), model.settings().growth.center);
  const std::vector<Eigen::Index> pins =
      analysis_pins(model, state.x, pinned, TurnFreeStabilityIndex::kDefaultMaxPinCondition);

  const auto start = std::chrono::steady_clock::now();
  const ContactSolveResult warm =
      penalty_warm_start(proxy, near_penalty_pairs(proxy, state.x, penalty), state.x,
                         penalty.contact_distance, penalty.stiffness);
  ContactSolveResult hard =
      solve_contact_equilibrium(model, state.parameter, proxy, state.x, pins, options, &warm);

  HardContactCheck c;
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  c.phi_e = state.parameter;
  c.unknowns = model.dimension();
  c.converged = hard.converged;
  c.message = hard.message;
  c.rounds = hard.rounds;
  c.iterations = hard.iterations;
  c.penalty_elastic_energy = elastic_energy(model, state.x, state.parameter);
  c.hard_elastic_energy = elastic_energy(model, hard.x, state.parameter);
  c.relative_energy_difference =
      (c.penalty_elastic_energy - c.hard_elastic_energy) / c.hard_elastic_energy;
  c.state_difference_over_h = (hard.x - state.x).cwiseAbs().maxCoeff() / h;
  const double reach = 2.0 * penalty.contact_distance;
  c.penalty_min_distance_over_h =
      smallest_distance(proxy, state.x, penalty.exclusion_radius, reach) / h;
  c.hard_min_distance_over_h = smallest_distance(proxy, hard.x, penalty.exclusion_radius, reach) / h;
  c.penalty_s4_defect = s4_defect(model, state.x);
  c.hard_s4_defect = s4_defect(model, hard.x);
  c.penalty_gamma =
      warm.forces.size() == 0
          ? kNaN
          : cone_contact_plane_angle(ContactGapConstraints(proxy, warm.pairs,
                                                           penalty.contact_distance,
                                                           model.dimension()),
                                     state.x, warm.forces, scene.geometry.radius);
  c.hard_gamma = hard.forces.size() == 0
                     ? kNaN
                     : cone_contact_plane_angle(
                           ContactGapConstraints(proxy, hard.pairs, options.contact_distance,
                                                 model.dimension(), options.gap),
                           hard.x, hard.forces, scene.geometry.radius);
  c.x = std::move(hard.x);
  return c;
}

std::string hard_contact_check_json(const HardContactCheck& c) {
  using Json = nlohmann::ordered_json;
  const auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  Json j;
  j["phi_e"] = number(c.phi_e);
  j["unknowns"] = c.unknowns;
  j["converged"] = c.converged;
  j["message"] = c.message;
  j["seconds"] = number(c.seconds);
  j["rounds"] = c.rounds;
  j["iterations"] = c.iterations;
  j["penalty_elastic_energy"] = number(c.penalty_elastic_energy);
  j["hard_elastic_energy"] = number(c.hard_elastic_energy);
  j["relative_energy_difference"] = number(c.relative_energy_difference);
  j["state_difference_over_h"] = number(c.state_difference_over_h);
  j["penalty_min_distance_over_h"] = number(c.penalty_min_distance_over_h);
  j["hard_min_distance_over_h"] = number(c.hard_min_distance_over_h);
  j["penalty_s4_defect"] = number(c.penalty_s4_defect);
  j["hard_s4_defect"] = number(c.hard_s4_defect);
  j["penalty_gamma"] = number(c.penalty_gamma);
  j["hard_gamma"] = number(c.hard_gamma);
  return j.dump(2) + "\n";
}

}  // namespace growshell
