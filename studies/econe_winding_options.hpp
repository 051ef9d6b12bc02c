#pragma once
/// \file
/// The settings with which the econe_contact study winds the sheet up (stage 8, study.wind_to):
/// growth in natural steps of at most 0.05 rad, each a bounded-Newton minimisation of shell +
/// penalty over every triangle near a proxy vertex, started from the secant prediction, and
/// the winding record's pins. One place for the study and for bench_winding_step, which times
/// these steps.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/contact_growth_path.hpp"

namespace growshell {

/// The winding's options for `scene` on `model` and its contact proxy: the scene's penalty
/// (scene_contact_penalty) on every triangle near a proxy vertex, in the full space;
/// scene_penalty_relaxation with steps of at most h/4 per dof, the adaptive shift and 5000
/// steps in all; growth steps of at most min(0.05, continuation.max_step).
ContactGrowthOptions econe_winding_options(const Scene& scene, const ShellModel& model,
                                           const ContactProxy& proxy);

/// The dofs listed in `path` (one per line, each in [0, n)): the winding record's pins.txt,
/// the rigid-motion pins its path goes on with. Throws std::runtime_error naming the file if
/// it is missing or holds anything else.
std::vector<Eigen::Index> read_winding_pins(const std::string& path, Eigen::Index n);

}  // namespace growshell
