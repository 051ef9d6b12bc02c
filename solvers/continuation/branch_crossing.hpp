#pragma once
/// \file
/// Where two traced branches of equilibria have equal total energy (e.g. the energy crossing
/// phi_e^crit of the symmetric and the skewed e-cone), located from the branch samples alone.
///
/// Why the samples suffice: along a branch of equilibria x(lambda) of E(x; lambda) the
/// gradient in x vanishes, so dE/dlambda = dE/dlambda|_x (the partial derivative at fixed x),
/// which the tracer can evaluate exactly at every sample. With value and slope at both ends of a
/// sample interval, E(lambda) is interpolated by the cubic Hermite polynomial, whose error is
///     E(lambda) - E^H(lambda) = E''''(xi) / 24 * (lambda - lambda_i)^2 (lambda - lambda_{i+1})^2,
/// i.e. O(dlambda^4); a crossing located on the interpolants inherits that order.
///
/// Error estimate (EnergyCrossing::error_estimate). Per interval [i, i+1] the Hermite error is
/// estimated by the embedded quartic
///     E^Q(lambda) = E^H(lambda) + c w(lambda),  w(lambda) = (lambda - lambda_i)^2 (lambda - lambda_{i+1})^2,
/// which also passes through a neighbouring sample n (i-1 or i+2): c = (E_n - E^H(lambda_n)) /
/// w(lambda_n). E^Q is fifth order, and c -> E''''/24, so |c| w(lambda) is an asymptotically
/// exact estimate of |E - E^H| (the brief suggested a quadratic through the neighbour; that
/// difference is O(dlambda^3) and would overestimate the fourth-order error by a factor that grows
/// as the step shrinks, which is why the quartic is used). A neighbour qualifies only if it
/// continues the interval's direction in lambda (no fold in between): across a fold the
/// neighbour lies on the other sheet, a different function of lambda. With both neighbours
/// available the larger |c| is used (conservative). Without a qualifying neighbour (a two-sample
/// branch, or an interval between two folds) the estimate falls back to |E^H - E^L| with E^L the
/// chord through the two samples: a deliberately conservative O(dlambda^2) bound.
/// The crossing then moves by at most (err_a + err_b) / |slope_difference| (first order in the
/// energy errors; triangle inequality rather than the signed difference, so a chance
/// cancellation of the two errors does not hide either), plus the root-finding bracket.
///
/// Work: the intervals of both branches are sorted by their lower end and swept, keeping the
/// intervals of each branch that are still open; pairing is output-sensitive,
/// O((N_a + N_b) log(N_a + N_b) + K) for K overlapping pairs (K = O(N_a + N_b) for branches
/// with a bounded number of folds). Each pair costs O(log(1/tolerance)) Hermite evaluations.

#include <cstddef>
#include <vector>

namespace growshell {

/// One sample of a traced branch: the parameter lambda (e.g. phi_e, radians), the total energy
/// at the equilibrium (energy units of the model, e.g. J) and dE/dlambda along the branch
/// (= partial E / partial lambda at fixed state; energy units per parameter unit).
struct BranchEnergySample {
  double parameter;
  double energy;
  double energy_slope;
};

/// A parameter at which the Hermite-interpolated energies of two branches are equal.
struct EnergyCrossing {
  double parameter;  ///< lambda at the crossing (parameter units)
  double energy;     ///< the common energy there (mean of the two interpolants)
  /// dE_a/dlambda - dE_b/dlambda at the crossing, from the interpolants (energy per parameter).
  double slope_difference;
  /// Estimated |error| of `parameter` (parameter units): interpolation error of both branches
  /// over |slope_difference|, plus the root-finding bracket; see the file comment. Infinite
  /// if the branches touch without crossing (slope_difference == 0).
  double error_estimate;
  /// Index i of the sample interval [i, i+1] on branch a and on branch b that holds the crossing.
  std::size_t segment_a, segment_b;
};

/// The cubic Hermite interpolant through (s0.parameter, s0.energy, s0.energy_slope) and
/// (s1.parameter, ...), evaluated at `lambda` (energy units). Works for either order of the two
/// parameters and extrapolates outside them. Throws std::invalid_argument if the two parameters
/// are equal.
double hermite_energy(const BranchEnergySample& s0, const BranchEnergySample& s1, double lambda);

/// All crossings of the energies of branches a and b (each a sequence of samples along the
/// branch in tracing order; lambda may go back and forth through folds), sorted by parameter.
/// Every consecutive sample pair of nonzero width is an interval carrying a cubic Hermite
/// interpolant; for every pair of intervals (one per branch) whose lambda ranges overlap, the
/// roots of E_a^H - E_b^H on the overlap are bracketed exactly (the difference is a cubic, split
/// at the roots of its derivative into monotone pieces) and bisected to `tolerance` in lambda.
/// A root shared by adjacent intervals (at a sample) is reported once. Points where the
/// interpolants touch without changing sign are reported only if the difference is exactly
/// zero at a piece boundary (then slope_difference is ~0 and error_estimate large or infinite:
/// callers should filter them). Ranges that only touch at a point carry no crossing. Interval
/// pairs with identical interpolants (a stretch shared by both branches, e.g. before a
/// symmetry-breaking branch point) are skipped, but the sample where such a shared stretch ends
/// is reported as a crossing if the energies there are bit-identical: pass the second branch
/// from beyond the shared stretch. Throws std::invalid_argument (naming branch and sample index) on a
/// non-finite value or fewer than 2 samples, and on a tolerance that is not positive and finite.
std::vector<EnergyCrossing> energy_crossings(const std::vector<BranchEnergySample>& a,
                                             const std::vector<BranchEnergySample>& b,
                                             double tolerance = 1e-10);

/// One branch traced in two pieces: `earlier`, by strictly increasing lambda (e.g. the
/// contact-free cone followed up to where a trace with contact starts), then `later` (that
/// trace, starting at or above earlier's last lambda and going either way afterwards). Samples
/// of `earlier` at or beyond later's first lambda are left out, so the shared start is not
/// counted twice; an empty piece returns the other. Throws std::invalid_argument naming the
/// sample if `earlier` is not strictly increasing or has a non-finite parameter.
std::vector<BranchEnergySample> join_branch_samples(const std::vector<BranchEnergySample>& earlier,
                                                    const std::vector<BranchEnergySample>& later);

}  // namespace growshell
