// io/csv_numbers.hpp writes exactly what printf writes for the formats of the output files.

#include "stochnav/io/csv_numbers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace stochnav {
namespace {

std::string printf_form(const char* format, double value) {
  char text[512];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::vector<double> awkward_values() {
  // Ties, carries into a new digit, the extremes, values of the output files; then random ones.
  std::vector<double> values = {0.0,    -0.0,    1.0,         -1.0,          0.5,         2.5,
                                0.0625, 1e-300,  1e300,       9.9999995,     999999.5,    0.0001,
                                1e-5,   0.1 / 3, 123456789.0, 116.344800004, 39.977800006};
  values.push_back(std::numeric_limits<double>::max());
  values.push_back(std::numeric_limits<double>::denorm_min());
  std::mt19937_64 engine(7);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> exponent(-12, 12);
  for (int i = 0; i < 20000; ++i) {
    values.push_back(normal(engine) * std::pow(10.0, exponent(engine)));
  }
  return values;
}

TEST(CsvNumbers, GeneralFormIsPrintfs) {
  for (double value : awkward_values()) {
    for (int significant : {1, 6, 9, 17}) {
      std::string out;
      append_general(out, value, significant);
      const std::string format = "%." + std::to_string(significant) + "g";
      ASSERT_EQ(out, printf_form(format.c_str(), value)) << value;
    }
  }
}

TEST(CsvNumbers, FixedFormIsPrintfs) {
  for (double value : awkward_values()) {
    for (int decimals : {0, 3, 4, 6, 9, 17}) {
      std::string out;
      append_fixed(out, value, decimals);
      const std::string format = "%." + std::to_string(decimals) + "f";
      ASSERT_EQ(out, printf_form(format.c_str(), value)) << value;
    }
  }
}

TEST(CsvNumbers, Appends) {
  std::string out = "t";
  out += ',';
  append_fixed(out, 1.5, 3);
  out += ',';
  append_general(out, 2e-7, 6);
  EXPECT_EQ(out, "t,1.500,2e-07");
}

}  // namespace
}  // namespace stochnav
