// Number: the exact rational a user wrote in a scene.  The value is checked
// exactly with CLN rationals (p/q from Number::fraction()), never through a
// double, so that 0.001 must be 1/1000 and not the nearest binary fraction.
#include <gtest/gtest.h>

#include <cln/rational.h>
#include <cln/rational_io.h>

#include <stdexcept>
#include <string>

#include "superball/cases/number.hpp"

namespace superball {
namespace {

cln::cl_RA value(const Number& n) { return cln::cl_RA(n.fraction().c_str()); }
cln::cl_RA rational(const char* text) { return cln::cl_RA(text); }

struct Spelling {
  const char* text;
  const char* exact;  // the value as CLN reads it: "p/q" or an integer
};

class NumberGood : public ::testing::TestWithParam<Spelling> {};

TEST_P(NumberGood, ParsesToTheExactValueWritten) {
  const Spelling s = GetParam();
  const Number n = Number::parse(s.text);
  EXPECT_EQ(value(n), rational(s.exact)) << "spelling '" << s.text << "' read as " << n.fraction();
  // The denominator is a positive decimal integer and never zero.
  ASSERT_FALSE(n.denominator.empty());
  EXPECT_NE(n.denominator.front(), '-');
  EXPECT_NE(n.denominator, "0");
  EXPECT_EQ(n.is_zero(), cln::zerop(value(n)));
  EXPECT_EQ(n.is_negative(), cln::minusp(value(n)));
}

INSTANTIATE_TEST_SUITE_P(
    Spellings, NumberGood,
    ::testing::Values(Spelling{"15", "15"}, Spelling{"-3", "-3"}, Spelling{"+7", "7"}, Spelling{"0", "0"},
                      Spelling{"-0", "0"}, Spelling{"007", "7"}, Spelling{"0.001", "1/1000"}, Spelling{"5e6", "5000000"},
                      Spelling{"5E6", "5000000"}, Spelling{"1.5E-3", "3/2000"}, Spelling{"2.5e+3", "2500"},
                      Spelling{"3.13209", "313209/100000"}, Spelling{"-0.000017", "-17/1000000"}, Spelling{".5", "1/2"},
                      Spelling{"5.", "5"}, Spelling{"1e0", "1"}, Spelling{"1/3", "1/3"}, Spelling{"-2/7", "-2/7"},
                      Spelling{"+2/7", "2/7"}, Spelling{"6/4", "3/2"}, Spelling{"0/5", "0"}, Spelling{"-0/5", "0"},
                      Spelling{"  12  ", "12"}, Spelling{"1_000", "1000"}, Spelling{"1_000.000_1", "10000001/10000"},
                      Spelling{"0.1e1", "1"}, Spelling{"123456789012345678901234567890", "123456789012345678901234567890"},
                      Spelling{"1e-30", "1/1000000000000000000000000000000"}));

TEST(Number, KeepsTheSpellingForMessages) {
  EXPECT_EQ(Number::parse(" 1.5E-3 ").text, "1.5E-3");
  EXPECT_EQ(Number::parse("1/3").text, "1/3");
}

// A NUL (a scene file's "\u0000", a Python string's "\x00") is escaped in
// the message itself: what() is a C string, a raw NUL would end the line there.
TEST(Number, AControlByteInTheTextIsEscapedInTheWholeMessage) {
  try {
    (void)Number::parse(std::string("1\0" "2\x1b", 4));
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "Number::parse(): '1\\02\\e' is not a number (unexpected '\\0')");
  }
}

TEST(Number, DecimalsAreKeptAsPowersOfTen) {
  // 0.001 is 1/1000 exactly; the fraction is not reduced (the cases library
  // has no big integers), but it is a decimal fraction.
  const Number n = Number::parse("0.001");
  EXPECT_EQ(n.numerator, "1");
  EXPECT_EQ(n.denominator, "1000");
  const Number m = Number::parse("5e6");
  EXPECT_EQ(m.numerator, "5000000");
  EXPECT_EQ(m.denominator, "1");
  EXPECT_EQ(Number::parse("-0.25").fraction(), "-25/100");
}

TEST(Number, LargestExponentIsAccepted) {
  const std::string big = "1e" + std::to_string(max_decimal_exponent);
  const Number n = Number::parse(big);
  EXPECT_EQ(n.numerator.size(), static_cast<std::size_t>(max_decimal_exponent) + 1);
  EXPECT_EQ(n.numerator, "1" + std::string(static_cast<std::size_t>(max_decimal_exponent), '0'));
  const Number small = Number::parse("1e-" + std::to_string(max_decimal_exponent));
  EXPECT_EQ(value(small) * value(n), 1);
}

TEST(Number, Integer) {
  EXPECT_EQ(value(Number::integer(-42)), -42);
  EXPECT_EQ(Number::integer(0).is_zero(), true);
  EXPECT_EQ(Number::integer(9).text, "9");
}

TEST(Number, ApproxIsTheNearestDouble) {
  EXPECT_EQ(Number::parse("0.001").approx(), 0.001);
  EXPECT_EQ(Number::parse("1/3").approx(), 1.0 / 3.0);
  EXPECT_EQ(Number::parse("5e6").approx(), 5e6);
  EXPECT_EQ(Number::parse("-3.13209").approx(), -3.13209);
}

class NumberBad : public ::testing::TestWithParam<const char*> {};

TEST_P(NumberBad, IsRejectedWithTheFunctionPrefix) {
  const std::string text = GetParam();
  try {
    const Number n = Number::parse(text);
    ADD_FAILURE() << "'" << text << "' was accepted as " << n.fraction();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("Number::parse(): ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Spellings, NumberBad,
                         ::testing::Values("", "   ", "abc", "1/0", "-1/000", "1/", "/2", "1/2/3", "1/-2", "1/+2", "--1",
                                           "+-1", "1e", "1e+", "e5", ".", "-.", "1.2.3", "1,5", "0x10", "inf", "-inf",
                                           "nan", "1 000", "1/3.0", "1.5/2", "3 /4", "1e4001", "1e9999999",
                                           "1e-99999999", "12abc", "\xc2\xbd",
                                           // '_' only between two digits, as in TOML
                                           "_1_", "_1", "1_", "_", "1__0", "+_1", "1_.5", "1._5", "._5", "1_e5",
                                           "1e_5", "1e5_", "1.5_"));

TEST(Number, ReasonsAreSpecific) {
  auto message = [](const char* text) -> std::string {
    try {
      Number::parse(text);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message("1/0").find("zero denominator"), std::string::npos) << message("1/0");
  EXPECT_NE(message("1e4001").find("exponent out of range"), std::string::npos) << message("1e4001");
  EXPECT_NE(message("").find("empty"), std::string::npos) << message("");
  EXPECT_NE(message("12abc").find("'12abc'"), std::string::npos) << message("12abc");
  EXPECT_NE(message("_1_").find("'_' that is not between two digits"), std::string::npos) << message("_1_");
}

TEST(Number, UnderscoresBetweenDigitsEverywhereTomlAllowsThem) {
  // TOML groups digits in the integer part, the fraction and the exponent.
  EXPECT_EQ(Number::parse("1_0.2_5e1_0").fraction(), Number::parse("10.25e10").fraction());
  EXPECT_EQ(Number::parse("-1_2_3").fraction(), "-123/1");
}

}  // namespace
}  // namespace superball
