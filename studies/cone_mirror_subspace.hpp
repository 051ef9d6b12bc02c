#pragma once
/// \file
/// The symmetric subspace an n-fold cone with a fold on the x-axis is traced in: the states
/// with its mirrors (y -> -y, and x -> -x for even n), or, for the two-fold cone's skewed and
/// turned branches, with the half turn about its axis; or none, with a note saying why, where
/// the mesh lacks them (the annulus grid, a disc centred off the origin) or a start state is
/// not symmetric. Background: docs/continuation.md, "Symmetric subspace".

#include <Eigen/Core>
#include <memory>
#include <string>

#include "libshell/assembly/shell_model.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"

namespace growshell {

/// A subspace to trace in, or none (null) and why (`note`, empty when there is a subspace).
struct ConeSubspaceChoice {
  std::shared_ptr<const SymmetricSubspace> subspace;
  std::string note;
};

/// The mirror subspace of the `folds`-fold cone on `model` (mirror_subspace with tolerance
/// 1e-9 radius), or none with a note "the symmetric branch is traced in the full space: ..."
/// naming what the mesh lacks.
ConeSubspaceChoice cone_mirror_subspace(const ShellModel& model, double radius, int folds);

/// The half-turn subspace (about the z-axis) of a two-fold cone's skewed, turned or wound
/// states on `model` (half_turn_subspace with tolerance 1e-9 radius), or none with a note
/// "`branch` is traced in the full space: ..." naming what the mesh lacks.
ConeSubspaceChoice cone_half_turn_subspace(const ShellModel& model, double radius,
                                           const std::string& branch);

/// `subspace` if the start state x has its symmetry up to `max_asymmetry` (m) in some frame
/// (SymmetricSubspace::aligned_asymmetry), else none with a note "`branch` is traced in the
/// full space: ...": e.g. a cone grown in natural steps, whose fold pattern has crept round
/// against the mesh. A null subspace stays null (without a note).
ConeSubspaceChoice subspace_for_start(std::shared_ptr<const SymmetricSubspace> subspace,
                                      const Eigen::Ref<const Eigen::VectorXd>& x,
                                      double max_asymmetry,
                                      const std::string& branch = "the symmetric branch");

}  // namespace growshell
