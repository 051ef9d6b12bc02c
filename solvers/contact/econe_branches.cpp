#include "solvers/contact/econe_branches.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "libshell/analysis/self_intersection.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"

namespace growshell {

const char* to_string(EconeBranch branch) {
  return branch == EconeBranch::Symmetric ? "symmetric" : "skewed";
}

namespace {

using Clock = std::chrono::steady_clock;

bool same_rows(const Eigen::MatrixX2i& a, const Eigen::MatrixX2i& b) {
  return a.rows() == b.rows() && a == b;
}

/// The penalised energy of the pairs near y, with its pair set.
struct NearPenalty {
  ContactCandidates pairs;
  ContactPenalty penalty;
  PenalizedEnergy energy;
  NearPenalty(ShellModel& model, const ContactProxy& proxy, const Eigen::VectorXd& y,
              const ContactBranchOptions& o)
      : pairs(near_contact_pairs(proxy, y, o.contact_distance + o.candidate_margin,
                                 o.exclusion_radius, o.selection)),
        penalty(proxy, pairs, o.contact_distance, o.stiffness, model.dimension(), o.gap),
        energy(model, penalty) {}
};

/// The eigenvector of the penalised Hessian at (y, phi) nearest zero (nearest_zero) or lowest.
Eigen::VectorXd mode_at(ShellModel& model, const ContactProxy& proxy, const Eigen::VectorXd& y,
                        double phi, const std::vector<Eigen::Index>& fixed,
                        const ContactBranchOptions& o, bool nearest_zero, double* eigenvalue) {
  model.set_excess_angle(phi);
  NearPenalty near(model, proxy, y, o);
  EigenpairOptions eig;
  eig.count = 1;
  if (nearest_zero) eig.shift = 0.0;
  const Eigenpairs modes = lowest_eigenpairs(near.energy, y, fixed, eig);
  *eigenvalue = modes.values[0];
  return modes.vectors.col(0);
}

/// Minimises shell + penalty at the model's excess angle from y, rebuilding the pair set until
/// the set built at the result is the one it was minimised with (so that the result is an
/// equilibrium of exactly the energy a trace then continues). Returns false if that does not
/// happen in 10 rounds or Newton fails.
bool relax(ShellModel& model, const ContactProxy& proxy, Eigen::VectorXd& y,
           const std::vector<Eigen::Index>& fixed, const EconeBranchOptions& o, double* energy,
           std::string* message) {
  for (int round = 0; round < 10; ++round) {
    NearPenalty near(model, proxy, y, o.contact);
    const NewtonResult r = NewtonSolver(o.relaxation).minimize(near.energy, y, fixed);
    y = r.x;
    if (!r.converged()) {
      *message = "relaxation failed: " + r.message;
      return false;
    }
    const ContactCandidates rebuilt =
        near_contact_pairs(proxy, y, o.contact.contact_distance + o.contact.candidate_margin,
                           o.contact.exclusion_radius, o.contact.selection);
    if (same_rows(rebuilt.vertex_triangle, near.pairs.vertex_triangle) &&
        same_rows(rebuilt.edge_edge, near.pairs.edge_edge)) {
      *energy = r.energy;
      return true;
    }
  }
  *message = "the pair set did not settle in 10 relaxation rounds";
  return false;
}

void validate(const EconeBranchOptions& o) {
  if (!(o.push > 0.0 && std::isfinite(o.push)))
    throw std::invalid_argument("EconeBranchOptions::push must be finite and > 0");
  if (!(o.energy_margin >= 0.0 && std::isfinite(o.energy_margin)))
    throw std::invalid_argument("EconeBranchOptions::energy_margin must be finite and >= 0");
  if (o.max_steps_per_branch < 1)
    throw std::invalid_argument("EconeBranchOptions::max_steps_per_branch must be >= 1");
  if (!(o.tangency_exclusion >= 0.0))
    throw std::invalid_argument("EconeBranchOptions::tangency_exclusion must be >= 0");
}

}  // namespace

EconeBranchResult trace_econe_branches(ShellModel& model, const ContactProxy& proxy,
                                       const Eigen::Ref<const Eigen::VectorXd>& x0, double phi0,
                                       const std::vector<Eigen::Index>& fixed_dofs,
                                       const EconeBranchOptions& options,
                                       const EconeBranchCallbacks& callbacks) {
  validate(options);
  if (!(options.symmetric_end > phi0))
    throw std::invalid_argument("EconeBranchOptions::symmetric_end must exceed the start phi_e");
  const ContactBranchOptions& o = options.contact;
  const double h_c = o.contact_distance;
  const auto note = [&](const std::string& text) {
    if (callbacks.on_note) callbacks.on_note(text);
  };
  EconeBranchResult out;

  // The symmetric branch, with the first-contact event (smallest pair distance = h_c; its
  // test function needs a pair search, so it is evaluated only until the event is found).
  bool contact_found = false;
  BranchEvent contact_event;
  contact_event.kind = "contact";
  contact_event.value = [&](const BranchSample& s) {
    if (contact_found) return -h_c;
    const ContactCandidates near =
        near_contact_pairs(proxy, s.x, 2.0 * h_c, o.exclusion_radius, o.selection);
    if (near.empty()) return h_c;
    ContactGapConstraints gaps(proxy, near, h_c, model.dimension(), o.gap);
    double d = 2.0 * h_c;
    for (Eigen::Index k = 0; k < gaps.count(); ++k)
      d = std::min(d, gaps.pair_geometry(s.x, k).distance);
    return d - h_c;
  };
  std::vector<BranchEnergySample> symmetric_energy, down_energy, up_energy;
  const auto energy_of = [](const ContactBranchSample& s) {
    return BranchEnergySample{s.sample.parameter,
                              s.stretching_energy + s.bending_energy + s.penalty_energy,
                              s.energy_slope};
  };
  ContactBranchOptions symmetric_options = o;
  symmetric_options.arclength.parameter_min = phi0 - 1.0;
  symmetric_options.arclength.parameter_max = options.symmetric_end;
  symmetric_options.arclength.max_steps = options.max_steps_per_branch;
  out.symmetric = trace_contact_branch(
      model, proxy, x0, phi0, Eigen::VectorXd::Zero(model.dimension()), 1.0, fixed_dofs,
      symmetric_options,
      [&](const ContactBranchSample& s) {
        symmetric_energy.push_back(energy_of(s));
        if (callbacks.on_sample) callbacks.on_sample(EconeBranch::Symmetric, s);
      },
      [&](const SpecialPoint& sp) {
        if (!out.stability_loss && sp.negative_before == 0 && sp.negative_after > 0)
          out.stability_loss = sp;
        if (callbacks.on_special) callbacks.on_special(EconeBranch::Symmetric, sp);
      },
      {contact_event},
      [&](const LocatedEvent& e) {
        if (e.kind == "contact") {
          contact_found = true;
          if (!out.first_contact) out.first_contact = e;
        }
        if (callbacks.on_event) callbacks.on_event(e);
      });
  note("symmetric branch: " + out.symmetric.message + " (" + std::to_string(out.symmetric.steps) +
       " steps)");

  // The skewed branch.
  const auto t_search = Clock::now();
  const auto on_skewed_sample = [&](std::vector<BranchEnergySample>& energies) {
    return [&](const ContactBranchSample& s) {
      energies.push_back(energy_of(s));
      if (callbacks.on_sample) callbacks.on_sample(EconeBranch::Skewed, s);
    };
  };
  const auto on_skewed_special = [&](const SpecialPoint& sp) {
    if (callbacks.on_special) callbacks.on_special(EconeBranch::Skewed, sp);
  };
  ContactBranchOptions skewed_options = o;
  skewed_options.arclength.parameter_min = phi0 - 1.0;
  skewed_options.arclength.parameter_max = options.skewed_end;
  skewed_options.arclength.max_steps = options.max_steps_per_branch;
  std::optional<double> entered_at;  // branch point the skewed branch was entered at
  if (!options.trace_skewed) {
    out.skewed_message = "not traced (trace_skewed = false)";
  } else if (out.symmetric.last.sample.x.size() != model.dimension()) {
    out.skewed_message = "not searched: the symmetric branch has no converged sample";
  } else if (options.skewed_start == SkewedStart::BranchPoint && out.stability_loss &&
      out.stability_loss->kind == SpecialPoint::Kind::BranchPoint) {
    const SpecialPoint& bp = *out.stability_loss;
    double lambda = 0.0;
    const Eigen::VectorXd mode =
        mode_at(model, proxy, bp.x, bp.parameter, fixed_dofs, o, true, &lambda);
    out.skewed_search_seconds = std::chrono::duration<double>(Clock::now() - t_search).count();
    std::ostringstream m;
    m << "entered at the branch point phi_e = " << bp.parameter
      << " along the critical mode (eigenvalue " << lambda << ")";
    out.skewed_message = m.str();
    note(out.skewed_message);
    out.skewed_found = true;
    entered_at = bp.parameter;
    // Off the branch point by h_c / 4 at the mode's largest entry: far enough for the corrector
    // to stay off the symmetric branch, close enough to land on the bifurcating one.
    const double offset = 0.25 * h_c / mode.cwiseAbs().maxCoeff();
    out.skewed_up = trace_contact_branch(model, proxy, bp.x + offset * mode, bp.parameter, mode,
                                         0.0, fixed_dofs, skewed_options,
                                         on_skewed_sample(up_energy), on_skewed_special);
  } else {
    const BranchSample top = out.symmetric.last.sample;
    double lambda = 0.0;
    const Eigen::VectorXd mode =
        mode_at(model, proxy, top.x, top.parameter, fixed_dofs, o, false, &lambda);
    model.set_excess_angle(top.parameter);
    {
      NearPenalty near(model, proxy, top.x, o);
      out.symmetric_top_energy = near.energy.evaluate(top.x, nullptr, nullptr);
    }
    double best_energy = out.symmetric_top_energy;
    Eigen::VectorXd best;
    std::ostringstream m;
    m << "lowest eigenvalue " << lambda << " at phi_e = " << top.parameter << ";";
    for (const int sign : {1, -1}) {
      Eigen::VectorXd y =
          top.x + sign * (options.push * h_c / mode.cwiseAbs().maxCoeff()) * mode;
      double energy = 0.0;
      std::string why;
      if (!relax(model, proxy, y, fixed_dofs, options, &energy, &why)) {
        m << " push " << sign << ": " << why << ";";
        continue;
      }
      SelfIntersectionOptions si;
      si.exclusion_radius = o.exclusion_radius;
      const bool crossed = find_self_intersection(model, y, si).intersects;
      m << " push " << sign << ": energy " << energy << " (symmetric "
        << out.symmetric_top_energy << ")" << (crossed ? ", passes through itself" : "") << ";";
      if (!crossed &&
          energy < best_energy - options.energy_margin * std::abs(out.symmetric_top_energy)) {
        best_energy = energy;
        best = y;
      }
    }
    out.skewed_search_seconds = std::chrono::duration<double>(Clock::now() - t_search).count();
    out.skewed_message = m.str();
    note(out.skewed_message);
    if (best.size() > 0) {
      out.skewed_found = true;
      out.skewed_relaxed_energy = best_energy;
      // Downwards until the branch ends at a fold; the part beyond it comes back up, and the
      // trace stops when that part reaches the relaxed state's phi_e again.
      ContactBranchOptions down_options = skewed_options;
      down_options.arclength.parameter_max = top.parameter;
      out.skewed_down = trace_contact_branch(
          model, proxy, best, top.parameter, Eigen::VectorXd::Zero(model.dimension()), -1.0,
          fixed_dofs, down_options, on_skewed_sample(down_energy), on_skewed_special);
      note("skewed branch, downwards: " + out.skewed_down.message);
      if (options.skewed_end > top.parameter) {
        out.skewed_up = trace_contact_branch(
            model, proxy, best, top.parameter, Eigen::VectorXd::Zero(model.dimension()), 1.0,
            fixed_dofs, skewed_options, on_skewed_sample(up_energy), on_skewed_special);
        note("skewed branch, upwards: " + out.skewed_up.message);
      }
    }
  }

  // phi_e^crit by energy. A skewed branch born at a branch point touches the symmetric one
  // there (energy difference ~ (phi - phi_b)^2): that tangency is not a crossing.
  if (symmetric_energy.size() >= 2) {
    for (const auto* part : {&down_energy, &up_energy}) {
      if (part->size() < 2) continue;
      for (const EnergyCrossing& c : energy_crossings(symmetric_energy, *part)) {
        if (entered_at && std::abs(c.parameter - *entered_at) < options.tangency_exclusion)
          continue;
        out.crossings.push_back(c);
      }
    }
    std::sort(out.crossings.begin(), out.crossings.end(),
              [](const EnergyCrossing& a, const EnergyCrossing& b) { return a.parameter < b.parameter; });
  }
  return out;
}

}  // namespace growshell
