#include "solvers/contact/contact_free_cone.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "libshell/contact/near_contact_pairs.hpp"
#include "solvers/continuation/elastic_energy_slope.hpp"

namespace growshell {

ContactFreeCone trace_contact_free_cone(const ShellModel& model, const ContactProxy& proxy,
                                        const std::vector<Eigen::Index>& fixed_dofs,
                                        const ContactFreeConeOptions& options) {
  if (!(std::isfinite(options.contact_distance) && options.contact_distance > 0.0))
    throw std::invalid_argument("ContactFreeConeOptions::contact_distance must be finite and > 0");
  if (!(std::isfinite(options.exclusion_radius) &&
        options.exclusion_radius >= options.contact_distance))
    throw std::invalid_argument(
        "ContactFreeConeOptions::exclusion_radius must be finite and >= contact_distance");
  ContactFreeCone out;
  const ConeBranchEntry entry =
      enter_cone_branch(model, model, options.entry, fixed_dofs, options.arclength);
  if (!entry.found) {
    out.message = "the flat disc did not buckle: " + entry.message;
    return out;
  }
  out.buckling_parameter = entry.branch_point.parameter;
  const BranchTrace cone =
      leave_branch_point(entry, [&](const Eigen::VectorXd& start, const Eigen::VectorXd& mode) {
        return trace_branch_along(
            model, start, entry.branch_point.parameter, mode, 0.0, fixed_dofs, options.arclength,
            [&](const BranchSample& s) { out.samples.push_back(s); },
            [&](const SpecialPoint& p) { out.special_points.push_back(p); });
      }).trace;
  out.steps = cone.steps;
  // Past first contact the contact-free cone is not the symmetric branch any more: keep the
  // samples up to the last one free of contact.
  while (!out.samples.empty() &&
         !near_contact_pairs(proxy, out.samples.back().x, options.contact_distance,
                             options.exclusion_radius)
              .empty()) {
    out.samples.pop_back();
    out.stopped_before_contact = true;
  }
  if (out.samples.empty()) {
    out.message = "no sample of the cone is free of contact";
    return out;
  }
  out.start = out.samples.back();
  std::erase_if(out.special_points,
                [&](const SpecialPoint& p) { return !(p.parameter < out.start.parameter); });
  out.found = cone.reached_bound || out.stopped_before_contact;
  if (!out.found) out.message = "the contact-free cone ended: " + cone.message;
  return out;
}

std::vector<BranchEnergySample> contact_free_energies(const ShellModel& model,
                                                      const std::vector<BranchSample>& samples) {
  std::vector<BranchEnergySample> out;
  out.reserve(samples.size());
  for (const BranchSample& s : samples) {
    const ShellEnergyBreakdown e = model.energy_breakdown(s.x, s.parameter);
    out.push_back(
        {s.parameter, e.stretching + e.bending, elastic_energy_slope(model, s.x, s.parameter)});
  }
  return out;
}

}  // namespace growshell
