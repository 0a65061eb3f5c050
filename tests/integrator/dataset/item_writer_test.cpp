// Parameter values as JSON (integrator/dataset/item_writer.cpp, parameterJson): params.json
// and index.jsonl must stay valid JSON whatever value a manifest sets, so numbers and flow
// lists of numbers go through as written and everything else becomes a JSON string. Each
// case below fails if the scanner accepts a non-JSON number (leading zero, bare dot,
// trailing comma, missing exponent digits) or rejects a valid one.
#include "integrator/dataset/item_writer.h"

#include <gtest/gtest.h>

namespace camsim {
namespace {

TEST(ParameterJson, NumbersAndNumberListsPassThrough) {
  for (const char* v : {"0", "-0", "12", "-3.25", "1e-3", "6.02E+23", "0.5", "[]", "[1]",
                        "[0, 0, -3]", "[1.5,2,  -4e2]", "[ 1 , 2 ]"})
    EXPECT_EQ(parameterJson(v), v) << v;
}

TEST(ParameterJson, NullStaysNull) {
  EXPECT_EQ(parameterJson("~"), "null");
  EXPECT_EQ(parameterJson("null"), "null");
}

TEST(ParameterJson, EverythingElseIsAString) {
  EXPECT_EQ(parameterJson("imx363"), "\"imx363\"");
  EXPECT_EQ(parameterJson("say \"hi\""), "\"say \\\"hi\\\"\"");
  // Valid YAML numbers that are not JSON numbers, and lists that are not number lists.
  for (const char* v : {"01", ".5", "5.", "1e", "+1", "0x10", "inf", "[1, 2, ]", "[1 2]",
                        "[[1, 2]]", "[a, b]", "[1,", "{a: 1}", ""}) {
    const std::string j = parameterJson(v);
    ASSERT_FALSE(j.empty()) << v;
    EXPECT_EQ(j.front(), '"') << v << " -> " << j;
  }
}

}  // namespace
}  // namespace camsim
