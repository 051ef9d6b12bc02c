#include "studies/econe_contact_cost.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace growshell {
namespace {

EconeTraceWork work(const std::string& name, int steps, int factorizations, int indices) {
  EconeTraceWork w;
  w.trace = name;
  w.steps = steps;
  w.failed_steps = 1;
  w.cost.continuation.stalled_correctors = 1;
  w.cost.continuation.rejected_steps = 3;
  w.cost.continuation.tangent_angle_rejections = 2;
  w.cost.segments = 2;
  w.cost.pair_search_seconds = 0.5;
  w.cost.continuation.linearizations = factorizations;
  w.cost.continuation.factorizations = factorizations;
  w.cost.continuation.stability_evaluations = indices;
  w.cost.continuation.total_seconds = 10.0;
  return w;
}

TEST(EconeContactCostJson, EachTraceAndTheirSumWithFactorisationsPerStep) {
  EconeContactCost cost;
  cost.traces = {work("symmetric", 40, 200, 44), work("skewed_down", 10, 35, 11)};
  cost.skewed_search_seconds = 106.0;
  cost.hard_contact_checks = 2;
  cost.hard_contact_seconds = 61.5;
  cost.wall_seconds = 420.0;
  const auto j = nlohmann::ordered_json::parse(econe_contact_cost_json(cost));
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"traces", "all_traces", "skewed_search_seconds",
                                            "hard_contact_checks", "hard_contact_seconds",
                                            "winding", "wall_seconds"}));
  ASSERT_EQ(j["traces"].size(), 2u);
  EXPECT_EQ(j["traces"][0]["trace"], "symmetric");
  EXPECT_EQ(j["traces"][0]["factorizations_per_step"].get<double>(), 5.0);
  EXPECT_EQ(j["traces"][0]["stability_evaluations_per_step"].get<double>(), 1.1);
  EXPECT_EQ(j["traces"][1]["factorizations_per_step"].get<double>(), 3.5);
  // The sums: 235 factorisations over 50 steps, 55 indices, 4 segments, 2 failed steps.
  const auto& all = j["all_traces"];
  EXPECT_FALSE(all.contains("trace"));
  EXPECT_EQ(all["steps"].get<int>(), 50);
  EXPECT_EQ(all["failed_steps"].get<int>(), 2);
  EXPECT_EQ(all["stalled_correctors"].get<int>(), 2);
  EXPECT_EQ(all["rejected_steps"].get<int>(), 6);
  EXPECT_EQ(all["tangent_angle_rejections"].get<int>(), 4);
  EXPECT_EQ(all["segments"].get<int>(), 4);
  EXPECT_EQ(all["factorizations"].get<int>(), 235);
  EXPECT_EQ(all["factorizations_per_step"].get<double>(), 4.7);
  EXPECT_EQ(all["stability_evaluations_per_step"].get<double>(), 1.1);
  EXPECT_EQ(all["pair_search_seconds"].get<double>(), 1.0);
  EXPECT_EQ(all["total_seconds"].get<double>(), 20.0);
  EXPECT_EQ(j["skewed_search_seconds"].get<double>(), 106.0);
  EXPECT_EQ(j["hard_contact_checks"].get<int>(), 2);
  EXPECT_TRUE(j["winding"].is_null());

  EconeContactCost wound;
  wound.winding = EconeWindingWork{4, 9, 40, 52, 1, 30.0};
  wound.traces = {work("turned_up", 0, 3, 1)};
  wound.wall_seconds = std::numeric_limits<double>::quiet_NaN();
  const auto w = nlohmann::json::parse(econe_contact_cost_json(wound));
  EXPECT_EQ(w["winding"]["factorizations_per_step"].get<double>(), 13.0);
  EXPECT_EQ(w["winding"]["minimisations"].get<int>(), 9);
  // No step: no ratio; nothing to say: null, not NaN or a division by zero.
  EXPECT_TRUE(w["traces"][0]["factorizations_per_step"].is_null());
  EXPECT_TRUE(w["skewed_search_seconds"].is_null());
  EXPECT_TRUE(w["wall_seconds"].is_null());
}

}  // namespace
}  // namespace growshell
