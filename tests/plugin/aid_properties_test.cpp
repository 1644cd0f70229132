// The aid property suite (stochnav/testing/aid_properties.hpp) on every bundled aid, as an aid
// author runs it on theirs.

#include "stochnav/testing/aid_properties.hpp"

#include "bundled_aid_cases.hpp"

namespace stochnav::testing {
namespace {

INSTANTIATE_TEST_SUITE_P(BundledAids, AidProperties,
                         ::testing::ValuesIn(plugin::bundled_aid_cases::all()), aid_case_name);

}  // namespace
}  // namespace stochnav::testing
