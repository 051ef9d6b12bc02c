#include "solvers/continuation/subspace_branch_trace.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "solvers/continuation/symmetric_subspace_family.hpp"
#include "solvers/stability/hessian_negative_count.hpp"
#include "solvers/stability/symmetry_class_stability_index.hpp"

namespace growshell {
namespace {

void check_dimensions(const ParametrizedObjective& family, const SymmetricSubspace& subspace,
                      Eigen::Index x0_size, Eigen::Index direction_size, const char* caller) {
  if (subspace.full_dimension() != family.dimension())
    throw std::invalid_argument(std::string(caller) + ": the subspace is for " +
                                std::to_string(subspace.full_dimension()) +
                                " unknowns, the family has " + std::to_string(family.dimension()));
  if (x0_size != family.dimension() || direction_size != family.dimension())
    throw std::invalid_argument(std::string(caller) + ": the start and the direction need " +
                                std::to_string(family.dimension()) + " entries");
}

/// The trace from the reduced state y0 in the subspace's frame `frame` (x = frame^-1(Q y)).
BranchTrace trace_from_reduced(const ParametrizedObjective& family,
                               const SymmetricSubspace& subspace, const RigidMotion& frame,
                               const Eigen::VectorXd& y0, double lambda0,
                               const Eigen::Ref<const Eigen::VectorXd>& direction_state,
                               double direction_parameter,
                               const std::vector<Eigen::Index>& fixed_dofs,
                               const ArclengthOptions& options,
                               const std::function<void(const BranchSample&)>& on_sample,
                               const std::function<void(const SpecialPoint&)>& on_special,
                               const std::vector<BranchEvent>& events,
                               const std::function<void(const LocatedEvent&)>& on_event) {
  const auto state_to_caller = [&](const Eigen::VectorXd& y) {
    return frame.apply_inverse(subspace.expand(y));
  };
  const auto to_caller = [&](BranchSample s) {
    if (s.x.size() == subspace.dimension()) {
      s.reduced_x = std::move(s.x);
      s.reduced_frame = frame;
      s.x = state_to_caller(s.reduced_x);
    }
    if (s.tangent_state.size() == subspace.dimension())
      s.tangent_state = frame.rotate_inverse(subspace.expand(s.tangent_state));
    return s;
  };

  SymmetricSubspaceFamily reduced(family, subspace);
  const std::vector<Eigen::Index> pins = subspace.trace_pins(subspace.expand(y0));
  Eigen::VectorXd direction = subspace.restrict_to(frame.rotate(direction_state));
  for (const Eigen::Index d : pins) direction(d) = 0.0;

  // The default index: class by class where the subspace's group splits the space (the
  // blocks of its symmetry classes, factorised at the expanded state in the subspace's frame),
  // else the full Hessian with the caller's pins.
  std::unique_ptr<SymmetryClassStabilityIndex> class_index;
  std::unique_ptr<HessianNegativeCount> full_count;
  if (!options.stability_index) {
    if (subspace.group().classes_split_space())
      class_index = std::make_unique<SymmetryClassStabilityIndex>(family, subspace.group());
    else
      full_count = std::make_unique<HessianNegativeCount>(family, fixed_dofs);
  }
  ArclengthOptions o = options;
  const auto free_full =
      static_cast<double>(family.dimension() - static_cast<Eigen::Index>(fixed_dofs.size()));
  const auto free_reduced =
      static_cast<double>(subspace.dimension() - static_cast<Eigen::Index>(pins.size()));
  o.state_weight = options.state_weight * free_reduced / free_full;
  o.stability_index = [&](const BranchSample& s) {
    if (class_index) return class_index->at(subspace.expand(s.x), s.parameter);
    BranchSample full;
    full.parameter = s.parameter;
    full.x = state_to_caller(s.x);
    full.reduced_x = s.x;
    full.reduced_frame = frame;
    return options.stability_index ? options.stability_index(full)
                                   : full_count->at(full.x, full.parameter);
  };
  if (options.accept_step)
    o.accept_step = [&](const BranchSample& from, const BranchSample& to) {
      return options.accept_step(to_caller(from), to_caller(to));
    };
  std::vector<BranchEvent> full_events = events;
  for (BranchEvent& e : full_events)
    e.value = [&, value = e.value](const BranchSample& s) { return value(to_caller(s)); };

  BranchTrace trace = trace_branch_along(
      reduced, y0, lambda0, direction, direction_parameter, pins, o,
      [&](const BranchSample& s) {
        if (on_sample) on_sample(to_caller(s));
      },
      [&](SpecialPoint sp) {
        sp.x = state_to_caller(sp.x);
        if (on_special) on_special(sp);
      },
      full_events,
      [&](LocatedEvent e) {
        e.x = state_to_caller(e.x);
        if (on_event) on_event(e);
      });
  trace.last = to_caller(std::move(trace.last));
  for (SpecialPoint& sp : trace.special_points) sp.x = state_to_caller(sp.x);
  for (LocatedEvent& e : trace.events) e.x = state_to_caller(e.x);
  return trace;
}

}  // namespace

BranchTrace trace_branch_in_subspace(const ParametrizedObjective& family,
                                     const SymmetricSubspace& subspace,
                                     const Eigen::Ref<const Eigen::VectorXd>& x0, double lambda0,
                                     const Eigen::Ref<const Eigen::VectorXd>& direction_state,
                                     double direction_parameter,
                                     const std::vector<Eigen::Index>& fixed_dofs,
                                     const ArclengthOptions& options,
                                     const std::function<void(const BranchSample&)>& on_sample,
                                     const std::function<void(const SpecialPoint&)>& on_special,
                                     const std::vector<BranchEvent>& events,
                                     const std::function<void(const LocatedEvent&)>& on_event) {
  check_dimensions(family, subspace, x0.size(), direction_state.size(), "trace_branch_in_subspace");
  const RigidMotion frame = subspace.aligning_motion(x0);
  return trace_from_reduced(family, subspace, frame, subspace.restrict_to(frame.apply(x0)),
                            lambda0, direction_state, direction_parameter, fixed_dofs, options,
                            on_sample, on_special, events, on_event);
}

BranchTrace resume_branch_in_subspace(const ParametrizedObjective& family,
                                      const SymmetricSubspace& subspace, const BranchSample& start,
                                      const Eigen::Ref<const Eigen::VectorXd>& direction_state,
                                      double direction_parameter,
                                      const std::vector<Eigen::Index>& fixed_dofs,
                                      const ArclengthOptions& options,
                                      const std::function<void(const BranchSample&)>& on_sample,
                                      const std::function<void(const SpecialPoint&)>& on_special,
                                      const std::vector<BranchEvent>& events,
                                      const std::function<void(const LocatedEvent&)>& on_event,
                                      bool* reduced_start_used) {
  check_dimensions(family, subspace, start.x.size(), direction_state.size(),
                   "resume_branch_in_subspace");
  // The sample's reduced coordinates, if they are of this subspace and still give its x.
  const bool reduced = start.reduced_x.size() == subspace.dimension() &&
                       start.reduced_frame.apply_inverse(subspace.expand(start.reduced_x)) ==
                           start.x;
  if (reduced_start_used) *reduced_start_used = reduced;
  if (!reduced)
    return trace_branch_in_subspace(family, subspace, start.x, start.parameter, direction_state,
                                    direction_parameter, fixed_dofs, options, on_sample,
                                    on_special, events, on_event);
  return trace_from_reduced(family, subspace, start.reduced_frame, start.reduced_x,
                            start.parameter, direction_state, direction_parameter, fixed_dofs,
                            options, on_sample, on_special, events, on_event);
}

}  // namespace growshell
