#pragma once
// The columns of the branch records that the studies' tests write.

#include <string>
#include <vector>

namespace growshell::test_support {

inline const std::vector<std::string> kBranchColumns = {"phi_e", "n_negative", "s4_defect"};

}  // namespace growshell::test_support
