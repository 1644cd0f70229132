// RunConsistency: the self-check every run reports (experiment/run_consistency.hpp).

#include "stochnav/experiment/run_consistency.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace stochnav {
namespace {

std::array<double, kErrorMetricCount> filled(double value) {
  std::array<double, kErrorMetricCount> a;
  a.fill(value);
  return a;
}

TEST(RunConsistency, SharesInsideThreeSigmaAndNeesMean) {
  RunConsistency check({}, {});
  EXPECT_FALSE(check.has_truth());
  EXPECT_TRUE(check.consistency_json().is_null());
  EXPECT_EQ(check.consistency_line(), "");
  for (int k = 0; k < 100; ++k) {
    auto errors = filled(1.0);
    errors[0] = k < 41 ? 2.9 : 3.1;  // lat_err_m inside 3-sigma in 41 of 100 epochs
    errors[5] = std::numeric_limits<double>::quiet_NaN();  // skipped (vertical hole)
    check.add_epoch(errors, filled(1.0), k % 2 == 0 ? 8.0 : 10.0);
  }
  EXPECT_TRUE(check.has_truth());
  EXPECT_DOUBLE_EQ(check.inside_3sigma(0), 0.41);
  EXPECT_DOUBLE_EQ(check.inside_3sigma(1), 1.0);
  EXPECT_TRUE(std::isnan(check.inside_3sigma(5)));
  EXPECT_DOUBLE_EQ(check.nees_mean(), 9.0);
  EXPECT_EQ(check.consistency_line(),
            "consistency: OPTIMISTIC (lat_err_m inside 3-sigma only 41 % of epochs)");
  const nlohmann::json json = check.consistency_json();
  EXPECT_DOUBLE_EQ(json["inside_3sigma"]["lat_err_m"].get<double>(), 0.41);
  EXPECT_TRUE(json["inside_3sigma"]["azimuth_err_deg"].is_null());
  EXPECT_EQ(json["nees_mean"], 9.0);

  RunConsistency good({}, {});
  good.add_epoch(filled(0.5), filled(1.0), 9.0);
  EXPECT_EQ(good.consistency_line().rfind("consistency: ok", 0), 0u);
}

TEST(RunConsistency, AidStatisticsAndWarnings) {
  RunConsistency check({"zupt", "pipe_length"}, {3, 1});
  for (int k = 0; k < 100; ++k) {
    InnovationRecord zupt{.t_s = static_cast<double>(k), .aid_index = 0, .accepted = true, .nis = 3.0, .size = 3};
    InnovationRecord pipe{.t_s = static_cast<double>(k), .aid_index = 1, .accepted = k % 10 != 0, .nis = 1.0,
                          .size = 1};
    if (!pipe.accepted) pipe.nis = 100.0;
    const InnovationRecord records[] = {zupt, pipe};
    check.add_innovations(records);
  }
  ASSERT_EQ(check.aids().size(), 2u);
  EXPECT_DOUBLE_EQ(check.aids()[0].nis_mean(), 3.0);
  EXPECT_EQ(check.aids()[0].rejected_share(), 0.0);
  EXPECT_DOUBLE_EQ(check.aids()[1].rejected_share(), 0.1);
  EXPECT_DOUBLE_EQ(check.aids()[1].nis_mean(), 1.0) << "mean over the accepted updates";
  const auto warnings = check.aid_warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("aid 1 (pipe_length) rejected in 10 %"), std::string::npos)
      << warnings[0];
  const nlohmann::json aids = check.aids_json();
  EXPECT_EQ(aids[1]["type"], "pipe_length");
  EXPECT_EQ(aids[1]["attempts"], 100);
  EXPECT_EQ(aids[0]["dof"], 3);
}

InnovationRecord innovation(int aid, double z, double sigma, bool accepted = true) {
  InnovationRecord record{.t_s = 0.0, .aid_index = aid, .accepted = accepted, .nis = 1.0,
                          .size = 2};
  record.innovation[0] = z;
  record.innovation[1] = -z;
  record.innovation_sigma[0] = sigma;
  record.innovation_sigma[1] = sigma;
  return record;
}

TEST(RunConsistency, WithoutTruthTheInnovationsJudgeTheRun) {
  RunConsistency check({"rop", "zupt"}, {2, 2});
  EXPECT_EQ(check.self_check_json()["source"], "none");
  EXPECT_EQ(check.consistency_line(), "");
  // rop: 90 of 100 attempts inside 3 sigma (the 10 outside rejected by the gate); zupt: all.
  for (int k = 0; k < 100; ++k) {
    const InnovationRecord records[] = {innovation(0, k < 90 ? 2.9 : 3.1, 1.0, k < 90),
                                        innovation(1, 0.5, 1.0)};
    check.add_innovations(records);
  }
  EXPECT_DOUBLE_EQ(check.aids()[0].inside_3sigma(), 0.9);
  EXPECT_DOUBLE_EQ(check.aids()[1].inside_3sigma(), 1.0);
  const nlohmann::json self = check.self_check_json();
  EXPECT_EQ(self["source"], "innovations");
  EXPECT_TRUE(self["optimistic"].get<bool>());
  EXPECT_EQ(check.consistency_line(),
            "consistency (innovations, no truth): OPTIMISTIC (rop innovations inside 3-sigma only "
            "90 % of 200 components)");
  EXPECT_DOUBLE_EQ(check.aids_json()[0]["inside_3sigma"].get<double>(), 0.9);

  RunConsistency good({"zupt"}, {2});
  const InnovationRecord records[] = {innovation(0, 0.5, 1.0)};
  good.add_innovations(records);
  EXPECT_FALSE(good.self_check_json()["optimistic"].get<bool>());
  EXPECT_EQ(good.consistency_line(),
            "consistency (innovations, no truth): ok (inside 3-sigma: zupt 100.0 %)");

  // With truth, truth decides.
  good.add_epoch(filled(0.5), filled(1.0), 9.0);
  EXPECT_EQ(good.self_check_json()["source"], "truth");
  EXPECT_EQ(good.consistency_line().rfind("consistency: ok", 0), 0u);
}

}  // namespace
}  // namespace stochnav
