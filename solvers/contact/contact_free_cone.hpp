#pragma once
/// \file
/// The n-fold e-cone traced from the flat disc without contact, up to where a trace with
/// contact takes over: below first contact, and (with an exclusion radius that leaves the apex
/// core out of the contact) past the symmetric cone's subcritical branch point, which the
/// contact-free continuation passes on the symmetric branch (docs/contact.md, "Exclusion
/// radius"). Its samples belong to the symmetric branch: their energies join it for the energy
/// crossing (EconeBranchOptions::symmetric_before).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "solvers/continuation/branch_crossing.hpp"
#include "solvers/continuation/cone_branch_entry.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

struct ContactFreeConeOptions {
  ConeEntryOptions entry;  ///< folds, thickness and radius of the cone entered from flat
  /// Step control and tolerance of the cone's trace; parameter_max is where it stops.
  ArclengthOptions arclength;
  double contact_distance = 0.0;  ///< m, > 0
  double exclusion_radius = 0.0;  ///< m, >= contact_distance (as ContactBranchOptions)
};

struct ContactFreeCone {
  bool found = false;
  std::string message;              ///< why the cone was not traced to arclength.parameter_max
  double buckling_parameter = 0.0;  ///< phi_e of the flat disc's branch point
  /// The cone's converged samples by increasing phi_e, up to and including `start`; samples
  /// past first contact are left out.
  std::vector<BranchSample> samples;
  std::vector<SpecialPoint> special_points;  ///< on the cone, below start.parameter
  BranchSample start;  ///< the last sample free of contact: where the trace with contact starts
  /// True if the trace went past first contact (gap < contact distance between proxy
  /// primitives farther apart than the exclusion radius) and start is an earlier sample.
  bool stopped_before_contact = false;
  int steps = 0;
};

/// Enters the cone from the model's flat reference (enter_cone_branch), traces it by
/// pseudo-arclength continuation without contact up to options.arclength.parameter_max, and
/// returns its samples up to the last one free of contact on `proxy`. Nothing is thrown away
/// on failure: found = false with the message and the samples traced so far. Throws
/// std::invalid_argument if the distances are not positive or the exclusion radius is below
/// the contact distance.
ContactFreeCone trace_contact_free_cone(const ShellModel& model, const ContactProxy& proxy,
                                        const std::vector<Eigen::Index>& fixed_dofs,
                                        const ContactFreeConeOptions& options);

/// The samples' energies E_s + E_b and slopes dE/dphi_e (BranchEnergySample), for joining the
/// symmetric branch.
std::vector<BranchEnergySample> contact_free_energies(const ShellModel& model,
                                                      const std::vector<BranchSample>& samples);

}  // namespace growshell
