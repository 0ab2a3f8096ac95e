#include "superball/numeric/range.hpp"

#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/cases/number.hpp"
#include "superball/numeric/scalar.hpp"

namespace superball::numeric {

Range parse_range(const std::string& option, const std::string& text, const Scene& scene, int max_steps) {
  const auto eq = text.find('=');
  auto bad = [&](const std::string& why) -> std::invalid_argument {
    return std::invalid_argument(option + " " + printable(text) + ": " + why + " (expected KEY=FROM:TO:STEPS, e.g. K.3-4=0:20:401)");
  };
  if (eq == std::string::npos) throw bad("no '='");
  const std::string key = text.substr(0, eq), rest = text.substr(eq + 1);
  const auto c1 = rest.find(':'), c2 = rest.find(':', c1 == std::string::npos ? c1 : c1 + 1);
  if (c1 == std::string::npos || c2 == std::string::npos) throw bad("the range needs FROM:TO:STEPS");
  Range r{[&] {
            try {
              return Parameter::parse(key, scene);
            } catch (const std::invalid_argument& e) {
              throw bad(without_function_prefix(e.what()));
            }
          }(),
          0, 0, 0};
  try {
    r.from = parse_rational(Number::parse(rest.substr(0, c1)).fraction());
    r.to = parse_rational(Number::parse(rest.substr(c1 + 1, c2 - c1 - 1)).fraction());
  } catch (const std::invalid_argument& e) {
    throw bad(without_function_prefix(e.what()));
  }
  const std::string steps = rest.substr(c2 + 1);
  std::size_t used = 0;
  long s = 0;
  try {
    s = std::stol(steps, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != steps.size() || s < 2 || s > max_steps) throw bad("STEPS must be a whole number from 2 to " + std::to_string(max_steps));
  if (r.from == r.to) throw bad("FROM and TO are equal");
  r.steps = static_cast<int>(s);
  return r;
}

}  // namespace superball::numeric
