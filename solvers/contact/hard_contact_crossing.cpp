#include "solvers/contact/hard_contact_crossing.hpp"

#include "solvers/contact/penalty_warm_start.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "libshell/analysis/contact_zones.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "solvers/continuation/elastic_energy_slope.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace growshell {

namespace {

using Clock = std::chrono::steady_clock;

void validate(const HardContactCrossingOptions& o, const std::vector<Eigen::Index>& pins) {
  if (!(o.penalty_stiffness >= 0.0) || !std::isfinite(o.penalty_stiffness))
    throw std::invalid_argument("penalty_stiffness must be >= 0 and finite");
  if (!(o.max_pin_condition > 1.0)) throw std::invalid_argument("max_pin_condition must be > 1");
  if (!(o.zone_link_distance > 0.0) || !std::isfinite(o.zone_link_distance))
    throw std::invalid_argument("zone_link_distance must be > 0 and finite");
  if (!(o.zone_active_fraction >= 0.0))
    throw std::invalid_argument("zone_active_fraction must be >= 0");
  if (!(o.zone_max_normal_angle > 0.0 && o.zone_max_normal_angle <= 0.5 * std::numbers::pi))
    throw std::invalid_argument("zone_max_normal_angle must be in (0, pi/2]");
  if (!(o.slope_step > 0.0) || !std::isfinite(o.slope_step))
    throw std::invalid_argument("slope_step must be > 0 and finite");
  if (!(o.max_branch_mismatch > 0.0))
    throw std::invalid_argument("max_branch_mismatch must be > 0");
  if (!(o.crossing_tolerance > 0.0) || !std::isfinite(o.crossing_tolerance))
    throw std::invalid_argument("crossing_tolerance must be > 0 and finite");
  if (pins.size() != 6)
    throw std::invalid_argument(
        "re-solving under hard contact needs the six rigid-motion pins, got " +
        std::to_string(pins.size()) + " dofs");
}

void validate_state(const ShellModel& model, const BranchSample& s, const std::string& where) {
  if (s.x.size() != model.dimension())
    throw std::invalid_argument(where + ": state has " + std::to_string(s.x.size()) +
                                " entries, the model " + std::to_string(model.dimension()));
  if (!std::isfinite(s.parameter) || !s.x.allFinite())
    throw std::invalid_argument(where + ": phi_e or state is not finite");
}

void validate_samples(const ShellModel& model, const std::vector<BranchSample>& samples,
                      char branch) {
  for (std::size_t i = 0; i < samples.size(); ++i)
    validate_state(model, samples[i],
                   std::string("branch ") + branch + " sample " + std::to_string(i));
}

double elastic_energy(const ShellModel& model, const Eigen::VectorXd& x, double excess_angle) {
  const ShellEnergyBreakdown e = model.energy_breakdown(x, excess_angle);
  return e.stretching + e.bending;
}

HardContactSample resolve(const ShellModel& model, const ContactProxy& proxy, const BranchSample& s,
                          const std::vector<Eigen::Index>& pins,
                          const HardContactCrossingOptions& o) {
  const auto start = Clock::now();
  HardContactSample out;
  out.parameter = s.parameter;
  out.start_energy = elastic_energy(model, s.x, s.parameter);
  const std::vector<Eigen::Index> fixed =
      well_conditioned_pins(Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(
                                s.x.data(), s.x.size() / 3, 3),
                            pins, model.sheet_vertices(), o.max_pin_condition);
  // Warm start: the penalty's forces on the vertex-triangle pairs within reach of the start
  // (zero where the gap exceeds the contact distance). Those pairs are among the solve's own
  // initial selection, and a seed that lists them keeps the barrier small from the start even
  // where no pair touches yet.
  ContactSolveResult penalty;
  if (o.penalty_stiffness > 0.0) {
    NearPairSelection selection;
    selection.edge_edge_pairs = false;
    selection.nearest_triangle_only = o.solve.nearest_triangle_only;
    penalty = penalty_warm_start(
        proxy,
        near_contact_pairs(proxy, s.x, o.solve.contact_distance + o.solve.candidate_margin,
                           o.solve.exclusion_radius, selection),
        s.x, o.solve.contact_distance, o.penalty_stiffness);
  }
  ContactSolveResult r = solve_contact_equilibrium(model, s.parameter, proxy, s.x, fixed, o.solve,
                                                   o.penalty_stiffness > 0.0 ? &penalty : nullptr);
  out.converged = r.converged;
  out.message = r.message;
  out.x = std::move(r.x);
  out.rounds = r.rounds;
  out.iterations = r.iterations;
  out.min_distance = r.min_distance;
  out.max_state_difference = (out.x - s.x).cwiseAbs().maxCoeff();
  out.energy = elastic_energy(model, out.x, s.parameter);
  out.energy_slope = elastic_energy_slope(model, out.x, s.parameter, o.slope_step);

  out.gamma = std::numeric_limits<double>::quiet_NaN();
  out.constrained_pairs = static_cast<int>(r.forces.size());
  if (r.forces.size() > 0) {
    out.total_force = r.forces.sum();
    const double largest = r.forces.maxCoeff();
    for (Eigen::Index k = 0; k < r.forces.size(); ++k)
      if (r.forces(k) > o.zone_active_fraction * largest) ++out.active_pairs;
    if (largest > 0.0) {
      const ContactGapConstraints gaps(proxy, r.pairs, o.solve.contact_distance, model.dimension(),
                                       o.solve.gap);
      out.gamma =
          contact_plane_angle(contact_zones(gaps, out.x, r.forces, o.zone_link_distance,
                                            o.zone_active_fraction, o.zone_max_normal_angle));
    }
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace

double branch_continuity_mismatch(const HardContactSample& a, const HardContactSample& b) {
  const double dphi = b.parameter - a.parameter;
  if (!std::isfinite(dphi) || dphi == 0.0 || !std::isfinite(a.energy) || !std::isfinite(b.energy) ||
      !std::isfinite(a.energy_slope) || !std::isfinite(b.energy_slope))
    throw std::invalid_argument(
        "branch_continuity_mismatch: the samples need finite, distinct phi_e and finite energies "
        "and slopes");
  const double scale =
      std::max(std::abs(a.energy_slope), std::abs(b.energy_slope)) * std::abs(dphi);
  const double miss =
      std::abs(b.energy - a.energy - 0.5 * (a.energy_slope + b.energy_slope) * dphi);
  return scale > 0.0 ? miss / scale : (miss > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
}

std::pair<std::size_t, std::size_t> continuous_stretch(
    const std::vector<HardContactSample>& samples, std::size_t anchor, double max_mismatch) {
  if (anchor >= samples.size())
    throw std::invalid_argument("continuous_stretch: anchor " + std::to_string(anchor) +
                                " is out of range (" + std::to_string(samples.size()) +
                                " samples)");
  if (!(max_mismatch > 0.0))
    throw std::invalid_argument("continuous_stretch: max_mismatch must be > 0");
  std::size_t first = anchor, last = anchor;
  while (last + 1 < samples.size() &&
         branch_continuity_mismatch(samples[last], samples[last + 1]) <= max_mismatch)
    ++last;
  while (first > 0 &&
         branch_continuity_mismatch(samples[first - 1], samples[first]) <= max_mismatch)
    --first;
  return {first, last};
}

HardContactSample resolve_with_hard_contact(const ShellModel& model, const ContactProxy& proxy,
                                            const BranchSample& sample,
                                            const std::vector<Eigen::Index>& pins,
                                            const HardContactCrossingOptions& options) {
  validate(options, pins);
  validate_state(model, sample, "sample at phi_e = " + std::to_string(sample.parameter));
  return resolve(model, proxy, sample, pins, options);
}

HardContactCrossing hard_contact_energy_crossing(const ShellModel& model, const ContactProxy& proxy,
                                                 const std::vector<BranchSample>& a,
                                                 const std::vector<BranchSample>& b,
                                                 const std::vector<Eigen::Index>& pins,
                                                 const HardContactCrossingOptions& options,
                                                 const HardContactSampleCallback& on_sample) {
  validate(options, pins);
  validate_samples(model, a, 'a');
  validate_samples(model, b, 'b');

  HardContactCrossing out;
  std::ostringstream failed;
  std::ostringstream broken;
  const auto run = [&](const std::vector<BranchSample>& samples, char name,
                       std::vector<HardContactSample>& results,
                       std::vector<BranchEnergySample>& energies) {
    const HardContactSample* previous = nullptr;
    std::size_t previous_index = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      results.push_back(resolve(model, proxy, samples[i], pins, options));
      const HardContactSample& r = results.back();
      if (r.converged) {
        energies.push_back({r.parameter, r.energy, r.energy_slope});
        if (previous != nullptr) {
          const double mismatch = branch_continuity_mismatch(*previous, r);
          if (mismatch > options.max_branch_mismatch)
            broken << " branch " << name << " samples " << previous_index << " and " << i
                   << " do not lie on one smooth branch (mismatch " << mismatch << ");";
        }
        previous = &r;
        previous_index = i;
      } else {
        failed << " branch " << name << " sample " << i << " (phi_e = " << r.parameter
               << ") failed: " << r.message << ";";
      }
      if (on_sample) on_sample(name, i, r);
    }
  };
  out.a.reserve(a.size());
  out.b.reserve(b.size());
  std::vector<BranchEnergySample> energy_a, energy_b;
  run(a, 'a', out.a, energy_a);
  run(b, 'b', out.b, energy_b);

  std::ostringstream m;
  if (!failed.str().empty()) m << "not converged:" << failed.str();
  if (!broken.str().empty()) m << (m.str().empty() ? "" : " ") << "suspect:" << broken.str();
  if (energy_a.size() < 2 || energy_b.size() < 2) {
    m << (m.str().empty() ? "" : " ") << "a branch has fewer than two converged samples ("
      << energy_a.size() << " and " << energy_b.size() << "): no crossing located";
  } else {
    out.crossings = energy_crossings(energy_a, energy_b, options.crossing_tolerance);
    if (out.crossings.empty())
      m << (m.str().empty() ? "" : " ")
        << "the re-solved energies do not cross within the samples' range";
  }
  out.message = m.str();
  return out;
}

}  // namespace growshell
