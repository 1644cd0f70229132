// Issue #26: the one JSON reader refuses a key twice in one object, naming its JSON pointer
// (nlohmann keeps the last silently, while unknown keys are refused: a typo'd duplicate would
// change a run without a word).

#include <gtest/gtest.h>

#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/json_document.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

struct DuplicateCase {
  std::string name;
  std::string text;
  std::string pointer;  ///< of the duplicate; empty: the document is accepted
};
void PrintTo(const DuplicateCase& c, std::ostream* os) { *os << c.name; }

class DuplicateKeys : public ::testing::TestWithParam<DuplicateCase> {};

TEST_P(DuplicateKeys, RefusedWithTheirPointer) {
  const DuplicateCase& c = GetParam();
  testing::TempDir dir;
  const std::string path = dir.write("config.json", c.text);
  if (c.pointer.empty()) {
    EXPECT_EQ(read_json_document(path, "the config"), nlohmann::json::parse(c.text));
    return;
  }
  try {
    read_json_document(path, "the config");
    FAIL() << "accepted " << c.text;
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message, path + ": duplicate key at " + c.pointer +
                           "; JSON objects need distinct keys: keep one of them");
  }
}

INSTANTIATE_TEST_SUITE_P(
    Issue26, DuplicateKeys,
    ::testing::Values(
        DuplicateCase{"top_level", R"({"units": "deg/h", "rate_hz": 1, "units": "rad/s"})",
                      "/units"},
        DuplicateCase{"nested", R"({"noise": {"gyro": {"plugin": "white", "plugin": "ar"}}})",
                      "/noise/gyro/plugin"},
        DuplicateCase{"in_an_array_element",
                      R"({"terms": [{"type": "a", "N": 1}, {"type": "b", "N": 1, "N": 2}]})",
                      "/terms/1/N"},
        DuplicateCase{"after_nested_arrays",
                      R"({"a": [[1, 2], {"x": [3]}, 4, {"k": 1, "k": 2}]})", "/a/3/k"},
        DuplicateCase{"escaped_in_the_pointer", R"({"a/b": {"m~n": 1, "m~n": 2}})",
                      "/a~1b/m~0n"},
        DuplicateCase{"the_same_key_in_sibling_objects_is_fine",
                      R"({"a": {"k": 1}, "b": {"k": 2}, "c": [{"k": 3}, {"k": 4}]})", ""},
        DuplicateCase{"a_key_equal_to_its_parent_is_fine", R"({"k": {"k": {"k": 1}}})", ""},
        DuplicateCase{"not_an_object", R"([1, 2, 2, "x"])", ""}),
    [](const ::testing::TestParamInfo<DuplicateCase>& case_info) { return case_info.param.name; });

TEST(JsonDocument, OptionTextIsCheckedTheSameWay) {
  EXPECT_THROW(parse_json_document(R"({"sigma": 1, "sigma": 2})", "--params"), InputError);
  EXPECT_EQ(parse_json_document(R"({"sigma": 1})", "--params")["sigma"], 1);
}

}  // namespace
}  // namespace stochnav
