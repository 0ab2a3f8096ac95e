// The overlay of a map (verify/overlay.hpp) for people and programs:
// `superball map --overlay` and its JSON.
#include "superball/present/overlay.hpp"

#include <cln/real.h>

#include <string>

#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/scalar.hpp"

namespace superball::present {

std::string to_text(const verify::Overlay& o, const numeric::Map& map) {
  const Vocabulary& v = Vocabulary::paper();
  std::string cases;
  for (const ContactSet& c : o.cases) cases += (cases.empty() ? "" : ", ") + v.case_name(c);
  std::size_t bounding = 0;
  for (const verify::DerivedZero& z : o.zeros) bounding += z.at_case;
  std::string text = "overlay: the derived conditions of case" + std::string(o.cases.size() == 1 ? " " : "s ") + cases + " (" +
                     std::to_string(o.conditions) + " conditions, PSD left out), located exactly on the grid lines: " +
                     std::to_string(o.zeros.size()) + " zeros, " + std::to_string(bounding) + " of them next to a point of their case\n";
  text += "  boundary points compared: " + std::to_string(o.matches.size()) + "; largest distance to the nearest derived zero " +
          numeric::to_string(o.largest_distance, 3) + " of the grid step (allowed: the two brackets' widths, up to " +
          numeric::to_string(o.largest_allowed, 3) + "): " + (o.agrees() ? "agree" : "DISAGREE") + "\n";
  for (const verify::OverlayMatch& m : o.matches) {
    if (m.agrees()) continue;
    const numeric::MapBoundary& b = map.boundaries[m.boundary];
    const auto [x, y] = numeric::position(map, b);
    text += "  disagreement at (" + numeric::to_string(x, 17) + ", " + numeric::to_string(y, 17) + "): case " + v.case_name(b.below.closed) +
            (b.below.superball ? " superball" : "") + " -> case " + v.case_name(b.above.closed) + (b.above.superball ? " superball" : "") + ": ";
    if (!m.found) {
      text += "no derived condition of either case changes side on its grid segment\n";
    } else {
      const verify::DerivedZero& z = o.zeros[m.zero];
      text += "the nearest derived zero (case " + v.case_name(z.closed) + ", " + z.condition() + ") is " +
              numeric::to_string(cln::double_approx(m.distance), 3) + " away, allowed " + numeric::to_string(cln::double_approx(m.allowed), 3) +
              "\n";
    }
  }
  return text;
}

nlohmann::ordered_json to_json(const verify::Overlay& o, const numeric::Map& map) {
  const Vocabulary& v = Vocabulary::paper();
  nlohmann::ordered_json j;
  auto& cases = j["cases"] = nlohmann::ordered_json::array();
  for (const ContactSet& c : o.cases) cases.push_back(v.case_name(c));
  j["conditions"] = o.conditions;
  j["agrees"] = o.agrees();
  j["largest_distance_in_steps"] = o.largest_distance;
  j["largest_allowed_in_steps"] = o.largest_allowed;
  auto& zeros = j["zeros"] = nlohmann::ordered_json::array();
  for (const verify::DerivedZero& z : o.zeros) {
    const auto [x, y] = verify::position(map, z);
    zeros.push_back({{"case", v.case_name(z.closed)},
                     {"condition", z.condition()},
                     {"along", z.along_x ? map.x.parameter.key() : map.y.parameter.key()},
                     {"x", cln::double_approx(x)},
                     {"y", cln::double_approx(y)},
                     {"low", numeric::to_string(z.low)},
                     {"high", numeric::to_string(z.high)},
                     {"holds_low", z.holds_low},
                     {"next_to_case", z.at_case}});
  }
  auto& matches = j["matches"] = nlohmann::ordered_json::array();
  for (const verify::OverlayMatch& m : o.matches) {
    nlohmann::ordered_json q{{"boundary", m.boundary}, {"found", m.found}};
    if (m.found) {
      q["zero"] = m.zero;
      q["distance"] = cln::double_approx(m.distance);
      q["allowed"] = cln::double_approx(m.allowed);
    }
    q["agrees"] = m.agrees();
    matches.push_back(std::move(q));
  }
  return j;
}

}  // namespace superball::present
