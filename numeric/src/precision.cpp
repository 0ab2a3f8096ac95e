#include "superball/numeric/precision.hpp"

#include <cctype>
#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/numeric/scalar.hpp"

namespace superball::numeric {

Precision Precision::parse(const std::string& text) {
  if (text == "double") return {Kind::Double, 0};
  if (text == "long-double") return {Kind::LongDouble, 0};
  if (text == "exact") return {Kind::Exact, 0};
  if (text.rfind("digits:", 0) == 0) {
    const std::string d = text.substr(7);
    bool ok = !d.empty() && d.size() < 7;
    for (char c : d) ok = ok && std::isdigit(static_cast<unsigned char>(c));
    const int digits = ok ? std::stoi(d) : 0;
    if (!ok || digits < min_digits || digits > max_digits)
      throw std::invalid_argument("Precision::parse(): '" + printable(text) + "': N in digits:N must be a whole number from " +
                                  std::to_string(min_digits) + " to " + std::to_string(max_digits));
    return {Kind::Digits, digits};
  }
  throw std::invalid_argument("Precision::parse(): unknown precision '" + printable(text) +
                              "' (expected double, long-double, digits:N or exact)");
}

SolvePrecision SolvePrecision::parse(const std::string& precision, std::optional<double> rtol) {
  SolvePrecision p;
  p.automatic = precision == "auto";
  p.rtol = rtol;
  if (!p.automatic) {
    // The rule of rtol first: it names what was asked, whatever the spelling of the precision.
    if (rtol)
      throw std::invalid_argument("SolvePrecision::check(): rtol is the certified error of precision auto; precision " + printable(precision) +
                                  " has none");
    p.fixed = Precision::parse(precision);
  }
  p.check();
  return p;
}

void SolvePrecision::check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("SolvePrecision::check(): " + what); };
  if (rtol && !automatic) fail("rtol is the certified error of precision auto; precision " + fixed.name() + " has none");
  if (rtol && !(*rtol >= 0 && *rtol <= 1)) fail("rtol must be a number from 0 to 1, got " + to_string(*rtol, 3));
}

std::string Precision::name() const {
  switch (kind) {
    case Kind::Double: return "double";
    case Kind::LongDouble: return "long-double";
    case Kind::Digits: return "digits:" + std::to_string(digits);
    case Kind::Exact: break;
  }
  return "exact";
}

}  // namespace superball::numeric
