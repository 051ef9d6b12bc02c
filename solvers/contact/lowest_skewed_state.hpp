#pragma once
/// \file
/// The choice among the relaxed pushes of a skewed-cone search: the lowest state that lies
/// below the symmetric one by a relative margin. The margin decides only whether a state is a
/// different (skewed) state at all; two skewed minima can lie closer to each other than the
/// margin (measured at h = 0.02, phi_e = 7.095: 0.105630 J and 0.105639 J against the
/// symmetric 0.105968 J), and they can lie on different branches, of which only the lower one
/// was traced down to the crossing. So among the skewed states the lowest wins, by any amount.

#include <Eigen/Core>

namespace growshell {

class LowestSkewedState {
 public:
  /// `symmetric_energy` (J) is the symmetric state's energy at the search point; a state is
  /// skewed if its energy is below symmetric_energy - relative_margin * |symmetric_energy|.
  /// Throws std::invalid_argument unless symmetric_energy is finite and relative_margin is
  /// finite and >= 0.
  LowestSkewedState(double symmetric_energy, double relative_margin);

  /// Offers the relaxed state x of energy `energy` (J). It becomes the choice if it is skewed
  /// and lower than the choice so far; returns whether it did. A non-finite energy is never
  /// chosen.
  bool offer(double energy, const Eigen::Ref<const Eigen::VectorXd>& x);

  bool found() const { return state_.size() > 0; }
  /// The chosen state's energy (J), or the symmetric energy while none is chosen.
  double energy() const { return energy_; }
  /// The chosen state; empty while none is chosen.
  const Eigen::VectorXd& state() const { return state_; }

 private:
  double threshold_;
  double energy_;
  Eigen::VectorXd state_;
};

}  // namespace growshell
