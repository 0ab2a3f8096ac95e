#include "superball/numeric/precision.hpp"

#include <cctype>
#include <stdexcept>

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
      throw std::invalid_argument("Precision::parse(): '" + text + "': N in digits:N must be a whole number from " +
                                  std::to_string(min_digits) + " to " + std::to_string(max_digits));
    return {Kind::Digits, digits};
  }
  throw std::invalid_argument("Precision::parse(): unknown precision '" + text +
                              "' (expected double, long-double, digits:N or exact)");
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
