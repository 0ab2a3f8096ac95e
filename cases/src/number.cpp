#include "superball/cases/number.hpp"

#include <cctype>
#include <cstdlib>
#include <stdexcept>

#include "superball/cases/error.hpp"

namespace superball {
namespace {

[[noreturn]] void fail(std::string_view text, const std::string& why) {
  throw std::invalid_argument("Number::parse(): " + printable("'" + std::string(text) + "' " + why));
}

bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

std::string strip_zeros(std::string digits) {
  const auto first = digits.find_first_not_of('0');
  return first == std::string::npos ? "0" : digits.substr(first);
}

}  // namespace

Number Number::integer(long long value) {
  Number n;
  n.numerator = std::to_string(value);
  n.denominator = "1";
  n.text = n.numerator;
  return n;
}

Number Number::parse(std::string_view text) {
  std::string_view s = text;
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  if (s.empty()) fail(text, "is empty");
  Number out;
  out.text = std::string(s);
  bool negative = false;
  if (s.front() == '+' || s.front() == '-') {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  std::string num, den = "1";
  if (const auto slash = s.find('/'); slash != std::string_view::npos) {
    const auto p = s.substr(0, slash), q = s.substr(slash + 1);
    if (!all_digits(p) || !all_digits(q)) fail(text, "is not a fraction of two integers like 1/3");
    num = strip_zeros(std::string(p));
    den = strip_zeros(std::string(q));
    if (den == "0") fail(text, "has a zero denominator");
  } else {
    // decimal: digits [. digits] [e|E [sign] digits]; TOML's '_' separators are
    // allowed, as in TOML only between two digits ("1_000", not "_1", "1_" or "1__0").
    std::string mantissa, fraction;
    long exponent = 0;
    std::size_t k = 0;
    auto is_digit = [&](std::size_t at) { return at < s.size() && std::isdigit(static_cast<unsigned char>(s[at])); };
    auto take_digits = [&](std::string& into) {
      for (; is_digit(k) || (k < s.size() && s[k] == '_'); ++k) {
        if (s[k] != '_') {
          into += s[k];
        } else if (k == 0 || !is_digit(k - 1) || !is_digit(k + 1)) {
          fail(text, "has an '_' that is not between two digits");
        }
      }
    };
    take_digits(mantissa);
    if (k < s.size() && s[k] == '.') {
      ++k;
      take_digits(fraction);
    }
    if (mantissa.empty() && fraction.empty()) fail(text, "is not a number");
    if (k < s.size() && (s[k] == 'e' || s[k] == 'E')) {
      ++k;
      std::string exp_sign = "+", exp_digits;
      if (k < s.size() && (s[k] == '+' || s[k] == '-')) exp_sign = s[k++];
      take_digits(exp_digits);
      if (exp_digits.empty()) fail(text, "has an empty exponent");
      if (exp_digits.size() > 6) fail(text, "has an exponent out of range");
      exponent = std::strtol(exp_digits.c_str(), nullptr, 10);
      if (exp_sign == "-") exponent = -exponent;
    }
    if (k != s.size()) fail(text, "is not a number (unexpected '" + std::string(1, s[k]) + "')");
    exponent -= static_cast<long>(fraction.size());
    if (exponent > max_decimal_exponent || exponent < -max_decimal_exponent - 64)
      fail(text, "has an exponent out of range (|e| <= " + std::to_string(max_decimal_exponent) + ")");
    num = strip_zeros(mantissa + fraction);
    if (exponent >= 0) {
      if (num != "0") num += std::string(static_cast<std::size_t>(exponent), '0');
    } else {
      den = "1" + std::string(static_cast<std::size_t>(-exponent), '0');
    }
  }
  out.numerator = (negative && num != "0" ? "-" : "") + num;
  out.denominator = den;
  return out;
}

bool Number::is_zero() const { return numerator == "0"; }
bool Number::is_negative() const { return !numerator.empty() && numerator.front() == '-'; }

double Number::approx() const {
  // Digit strings of any length: strtod reads them correctly rounded; the
  // quotient adds at most one more rounding.
  return std::strtod(numerator.c_str(), nullptr) / std::strtod(denominator.c_str(), nullptr);
}

}  // namespace superball
