// io/json.hpp: reals survive a write and a read bit for bit, strings are escaped and unescaped
// exactly, nested objects keep their order, and malformed texts are refused with the line and
// column of the fault.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "sphark/io/json.hpp"

using namespace sphark;

namespace {
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::string parse_error(const std::string& text) {
  try {
    parse_json(text);
  } catch (const JsonError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(Json, RealsRoundTripBitForBit) {
  std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.1, 1.0 / 3.0, 2.0 / 3.0, 1e-300, 1e300, 6.02214076e23,
                                std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::epsilon(),
                                -std::numeric_limits<double>::lowest(), 4503599627370497.0, 9007199254740993.0};
  std::mt19937_64 rng(20);
  std::uniform_int_distribution<std::uint64_t> bits;
  while (values.size() < 20000) {  // random bit patterns: every exponent, subnormals included
    const std::uint64_t b = bits(rng);
    double d;
    std::memcpy(&d, &b, sizeof d);
    if (std::isfinite(d)) values.push_back(d);
  }
  Json a = Json::Array{};
  for (double v : values) a.push_back(v);
  const Json back = parse_json(to_json_text(a));
  ASSERT_EQ(back.as_array().size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    ASSERT_TRUE(same_bits(back.as_array()[i].as_number(), values[i]))
        << values[i] << " read back as " << back.as_array()[i].number_text();
    // and the text written is the one read (what --config hands the option parser)
    ASSERT_EQ(back.as_array()[i].number_text(), a.as_array()[i].number_text());
  }
}

TEST(Json, NonFiniteRealsAreNull) {
  EXPECT_TRUE(Json(std::numeric_limits<double>::infinity()).is_null());
  EXPECT_TRUE(Json(std::nan("")).is_null());
  EXPECT_EQ(to_json_line(Json::Array{Json(1.5), Json(-std::numeric_limits<double>::infinity())}), "[1.5, null]");
}

TEST(Json, IntegersAreWrittenAsIntegers) {
  EXPECT_EQ(to_json_line(Json(42)), "42");
  EXPECT_EQ(to_json_line(Json(-7L)), "-7");
  EXPECT_EQ(to_json_line(Json(static_cast<unsigned long>(18446744073709551615UL))), "18446744073709551615");
  EXPECT_EQ(parse_json("123456789012").number_text(), "123456789012");
}

TEST(Json, StringsAreEscapedAndReadBackExactly) {
  std::string all;  // every byte value but NUL-free ASCII control characters first
  for (int c = 1; c < 0x20; ++c) all += static_cast<char>(c);
  all += "\"quoted\" back\\slash /slash \xc3\xa9t\xc3\xa9 \xe2\x88\x87\xc2\xb7" "B \xf0\x9f\x98\x80";
  const std::string text = to_json_line(Json(all));
  for (int c = 1; c < 0x20; ++c) EXPECT_EQ(text.find(static_cast<char>(c)), std::string::npos) << c;  // all escaped
  EXPECT_NE(text.find("\\\"quoted\\\""), std::string::npos);
  EXPECT_NE(text.find("back\\\\slash"), std::string::npos);
  EXPECT_NE(text.find("\\n"), std::string::npos);
  EXPECT_NE(text.find("\\u0001"), std::string::npos);
  EXPECT_EQ(parse_json(text).as_string(), all);
  // escapes written by others: \/ and \u with a surrogate pair
  EXPECT_EQ(parse_json(R"("a\/b \u00e9 \u2207 \ud83d\ude00")").as_string(),
            "a/b \xc3\xa9 \xe2\x88\x87 \xf0\x9f\x98\x80");
}

TEST(Json, NestedObjectsKeepTheirOrderAndRoundTrip) {
  Json r = Json::Object{};
  r["program"] = "water_drop";
  r["version"]["git_commit"] = "unknown";
  r["version"]["git_modified"] = true;
  r["options"]["t-end"] = 0.1;
  r["options"]["resolutions"] = Json::Array{25, 50, 100};
  r["options"]["render"] = false;
  r["options"]["restart"] = "";
  r["files"] = Json::Array{};
  r["nothing"] = nullptr;
  const std::string text = to_json_text(r);
  const Json back = parse_json(text);
  EXPECT_TRUE(back == r);
  ASSERT_EQ(back.as_object().size(), 5u);
  EXPECT_EQ(back.as_object()[0].first, "program");
  EXPECT_EQ(back.as_object()[2].first, "options");
  EXPECT_EQ(back.find("options")->as_object()[1].first, "resolutions");
  EXPECT_EQ(to_json_text(back), text);  // a fixed point
  EXPECT_NE(text.find("\"resolutions\": [25, 50, 100]"), std::string::npos) << text;  // short arrays on one line
  EXPECT_EQ(back.find("missing"), nullptr);
}

TEST(Json, MalformedTextsNameTheLineAndColumn) {
  EXPECT_EQ(parse_error("{\n  \"a\": 1,\n  \"b\" 2\n}"), "line 3, column 7: expected ':'");
  EXPECT_EQ(parse_error("{\"a\": 1,}"), "line 1, column 9: expected a key (a string in double quotes)");
  EXPECT_EQ(parse_error("[1, 2"), "line 1, column 6: expected ',' or ']'");
  EXPECT_EQ(parse_error("{\"a\": 1, \"a\": 2}"), "line 1, column 10: duplicate key \"a\"");
  EXPECT_EQ(parse_error("01"), "line 1, column 1: malformed number '01'");
  EXPECT_EQ(parse_error("1.5e"), "line 1, column 1: malformed number '1.5e'");
  EXPECT_EQ(parse_error("nan"), "line 1, column 1: expected a JSON value");
  EXPECT_EQ(parse_error("\"tab\there\""), "line 1, column 5: control character in a string (write it as an escape)");
  EXPECT_EQ(parse_error("\"\\ud800\""), "line 1, column 8: lone surrogate in \\u escape");
  EXPECT_EQ(parse_error("{} x"), "line 1, column 4: unexpected text after the JSON value");
  EXPECT_EQ(parse_error(""), "line 1, column 1: unexpected end of the text (expected a JSON value)");
  EXPECT_EQ(parse_error(std::string(300, '[') + std::string(300, ']')),
            "line 1, column 258: nested deeper than 256 levels");
}

TEST(Json, OutOfRangeNumbersKeepTheirText) {
  const Json big = parse_json("1e400");
  EXPECT_EQ(big.number_text(), "1e400");
  EXPECT_TRUE(std::isinf(big.as_number()));
  EXPECT_EQ(parse_json("-1e-400").as_number(), 0.0);
}
