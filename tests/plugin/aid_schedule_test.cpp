// AidSchedule::row_at against a plain binary search over the rows, whatever the order of the
// queries: ascending (a run's epochs, served from the previous query's row), backwards and
// random (a binary search), rows off the query grid by more and less than the tolerance.

#include "stochnav/plugin/aid_schedule.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <vector>

namespace stochnav::plugin {
namespace {

std::optional<std::size_t> searched_row(const std::vector<double>& rows, double t_s) {
  const auto it = std::lower_bound(rows.begin(), rows.end(), t_s - kEpochMatchTolerance_s);
  if (it == rows.end() || *it > t_s + kEpochMatchTolerance_s) return std::nullopt;
  return static_cast<std::size_t>(it - rows.begin());
}

TEST(AidSchedule, RowAtIsTheSearchedRowInAnyQueryOrder) {
  // 1-s rows, some of them 0.5 us off the 10-ms query grid (matched) and some 4 ms (not).
  std::vector<double> rows;
  for (int k = 0; k < 200; ++k) rows.push_back(k + (k % 7 == 3 ? 0.004 : k % 5 == 1 ? 5e-7 : 0.0));
  std::vector<double> queries;
  for (int k = -50; k < 20500; ++k) queries.push_back(0.01 * k);
  int matched = 0;
  const auto check = [&](const AidSchedule& schedule, double t_s) {
    const std::optional<std::size_t> row = schedule.row_at(t_s);
    ASSERT_EQ(row, searched_row(rows, t_s)) << "t = " << t_s;
    matched += row.has_value();
  };
  const AidSchedule ascending = AidSchedule::at_rows(rows);
  for (const double t : queries) check(ascending, t);
  EXPECT_EQ(matched, 171);  // the 29 rows 4 ms off never match
  const AidSchedule backwards = AidSchedule::at_rows(rows);
  for (auto t = queries.rbegin(); t != queries.rend(); ++t) check(backwards, *t);
  std::mt19937_64 engine(7);
  std::shuffle(queries.begin(), queries.end(), engine);
  const AidSchedule shuffled = AidSchedule::at_rows(rows);
  for (const double t : queries) check(shuffled, t);
  const AidSchedule empty = AidSchedule::at_rows({});
  EXPECT_FALSE(empty.row_at(0.0).has_value());
}

}  // namespace
}  // namespace stochnav::plugin
