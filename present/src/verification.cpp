// The verification of a case (verify/verification.hpp) for people and
// programs: `superball verify`, its --json, and the comment of a
// disagreement's scene file.
#include "superball/present/verification.hpp"

#include <cln/rational_io.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "superball/verify/space.hpp"

namespace superball::present {

using namespace superball::verify;

namespace {

/// \p s padded with spaces to \p width characters (UTF-8 lead bytes counted), on the left when \p right.
std::string pad(const std::string& s, std::size_t width, bool right = true) {
  // width in characters: count UTF-8 lead bytes only
  std::size_t n = 0;
  for (unsigned char ch : s) n += (ch & 0xC0) != 0x80;
  const std::string fill(n < width ? width - n : 0, ' ');
  return right ? fill + s : s + fill;
}

}  // namespace

std::string describe(const Verification& v, const Disagreement& d) {
  std::ostringstream os;
  os << "superball verify: case " << v.case_name << " (" << v.pattern << ", obstacle " << v.obstacle << "), eps = "
     << verify::epsilon_name(v.epsilons[static_cast<std::size_t>(d.epsilon_index)].epsilon) << (d.near ? ", a point near a boundary" : "") << '\n';
  os << "the exact solution: case " << d.actual_case << ", " << d.quantity << " -> case " << v.case_name << " with U1+ > a "
     << (d.truth ? "TRUE" : "FALSE") << '\n';
  os << "the exact conditions " << (d.exact ? "hold" : "fail") << (d.exact == d.truth ? " (agree)" : " (DISAGREE)") << "; the asymptotic conditions "
     << (d.asymptotic ? "hold" : "fail") << (d.asymptotic == d.truth ? " (agree)" : " (disagree)") << '\n';
  for (const std::string& s : d.details) os << s << '\n';
  std::string point;
  for (const auto& [name, x] : d.point) point += (point.empty() ? "" : ", ") + name + " = " + verify::to_string(x);
  os << "point: " << point;
  return os.str();
}

std::string to_text(const Verification& v) {
  std::ostringstream os;
  os << "case " << v.case_name << " — " << v.pattern << ", obstacle " << v.obstacle << ", regime " << v.scaling << '\n';
  os << "conditions (exact" << (v.obstacle == "finite" ? ", finite m_n" : "") << " | asymptotic):\n";
  for (const VerifiedCondition& c : v.conditions)
    os << "  " << pad(c.name(), 18, false) << ' ' << c.exact_text << "   |   " << c.asymptotic_text << '\n';
  os << "points per eps: " << v.samples << " drawn, then per condition up to " << v.boundary_pairs
     << " segments across its boundary bisected to 2^-" << verify::boundary_bracket_bits << " (both ends kept; a side short of drawn points is searched for), seed "
     << v.seed << "\n\n";
  auto ratio = [](long long part, long long whole) { return std::to_string(part) + "/" + std::to_string(whole); };
  os << "   eps  points  drawn  bound |  exact agree |  asymptotic agree: drawn     near |  exact: H&T   H&F   F&T   F&F |  asymptotic: H&T   H&F   F&T   F&F\n";
  for (const EpsilonResult& e : v.epsilons) {
    const Tally t = e.all();
    os << pad(verify::epsilon_name(e.epsilon), 6) << pad(std::to_string(t.exact.total()), 8) << pad(std::to_string(e.drawn.exact.total()), 7)
       << pad(std::to_string(e.boundary.exact.total()), 7) << " | " << pad(ratio(t.exact.agree(), t.exact.total()), 12) << " | "
       << pad(ratio(e.drawn.asymptotic.agree(), e.drawn.asymptotic.total()), 23) << pad(ratio(e.boundary.asymptotic.agree(), e.boundary.asymptotic.total()), 9)
       << " |";
    for (const Confusion* m : {&t.exact, &t.asymptotic})
      os << (m == &t.exact ? "     " : "           ") << pad(std::to_string(m->holds_true), 5) << pad(std::to_string(m->holds_false), 6)
         << pad(std::to_string(m->fails_true), 6) << pad(std::to_string(m->fails_false), 6) << (m == &t.exact ? " |" : "");
    if (t.undrawn || t.unsolved) os << "   (" << t.undrawn << " draws without an admissible point, " << t.unsolved << " unsolved)";
    os << '\n';
  }
  os << "\nper condition (all eps): points on each side of it, of them near its boundary, agreement of its exact form;\n"
     << "then per eps the points where its asymptotic form disagrees: among the drawn ones / among those near its boundary\n";
  os << "  condition            holds (near)    fails (near)  exact agree  | asymptotic disagree:";
  for (const EpsilonResult& e : v.epsilons) os << pad(verify::epsilon_name(e.epsilon), 12);
  os << '\n';
  for (std::size_t c = 0; c < v.conditions.size(); ++c) {
    const ConditionTally all = v.condition_total(c);
    os << "  " << pad(v.conditions[c].name(), 18, false) << pad(std::to_string(all.holds) + " (" + std::to_string(all.near_holds) + ")", 15)
       << pad(std::to_string(all.fails) + " (" + std::to_string(all.near_fails) + ")", 16) << pad(ratio(all.exact_agree, all.points()), 13)
       << "  |                     ";
    for (const EpsilonResult& e : v.epsilons) {
      const ConditionTally& d = e.drawn.conditions[c];
      const ConditionTally& n = e.boundary.conditions[c];
      const long long near = n.near_holds + n.near_fails;
      os << pad(std::to_string(d.points() - d.asymptotic_agree) + " / " + (near ? ratio(near - n.near_asymptotic_agree, near) : std::string("-")), 12);
    }
    for (bool side : {true, false}) {
      std::string where;
      for (const EpsilonResult& e : v.epsilons) {
        const ConditionTally& t = e.drawn.conditions[c];
        const ConditionTally& n = e.boundary.conditions[c];
        if ((side ? t.holds + n.holds : t.fails + n.fails) == 0) where += (where.empty() ? "" : ",") + verify::epsilon_name(e.epsilon);
      }
      if (where.empty()) continue;
      const symbolic::Verdict verdict = v.conditions[c].asymptotic_verdict;
      os << "   (" << (side ? "holds" : "fails") << " side not reached at eps " << where;
      if (verdict != symbolic::Verdict::Depends) os << ": its asymptotic form " << (verdict == symbolic::Verdict::Always ? "always holds" : "never holds");
      os << ")";
    }
    os << '\n';
  }
  const auto exact = std::count_if(v.disagreements.begin(), v.disagreements.end(), [](const Disagreement& d) { return d.exact_form; });
  os << "\ndisagreements: " << v.disagreements.size() << " points (" << exact << " where an exact form disagrees)\n";
  for (const Disagreement& d : v.disagreements)
    if (d.exact_form) os << "  EXACT FORM DISAGREES: " << describe(v, d) << '\n';
  return os.str();
}

nlohmann::ordered_json to_json(const Verification& v) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["case"] = v.case_name;
  j["pattern"] = v.pattern;
  j["obstacle"] = v.obstacle;
  j["scaling"] = v.scaling;
  j["samples"] = v.samples;
  j["boundary_pairs"] = v.boundary_pairs;
  j["boundary_bracket"] = "2^-" + std::to_string(verify::boundary_bracket_bits);
  j["seed"] = v.seed;
  j["exact_agrees"] = v.exact_agrees();
  ordered_json conditions = ordered_json::array();
  for (const VerifiedCondition& c : v.conditions)
    conditions.push_back({{"kind", symbolic::to_string(c.kind)},
                          {"about", c.about},
                          {"exact", c.exact_text},
                          {"asymptotic", c.asymptotic_text},
                          {"asymptotic_verdict", symbolic::to_string(c.asymptotic_verdict)}});
  j["conditions"] = conditions;
  auto confusion = [](const Confusion& m) {
    return ordered_json{{"holds_true", m.holds_true}, {"holds_false", m.holds_false}, {"fails_true", m.fails_true}, {"fails_false", m.fails_false},
                        {"agree", m.agree()}, {"total", m.total()}};
  };
  auto tally = [&](const Tally& t) {
    ordered_json x;
    x["points"] = t.points;
    x["undrawn"] = t.undrawn;
    x["unsolved"] = t.unsolved;
    x["exact"] = confusion(t.exact);
    x["asymptotic"] = confusion(t.asymptotic);
    ordered_json per = ordered_json::array();
    for (std::size_t c = 0; c < t.conditions.size(); ++c) {
      const ConditionTally& k = t.conditions[c];
      per.push_back({{"condition", v.conditions[c].name()}, {"holds", k.holds}, {"fails", k.fails}, {"near_holds", k.near_holds},
                     {"near_fails", k.near_fails}, {"exact_agree", k.exact_agree}, {"asymptotic_agree", k.asymptotic_agree},
                     {"near_asymptotic_agree", k.near_asymptotic_agree}});
    }
    x["conditions"] = per;
    return x;
  };
  ordered_json eps = ordered_json::array();
  for (const EpsilonResult& e : v.epsilons)
    eps.push_back({{"epsilon", verify::to_string(e.epsilon)}, {"all", tally(e.all())}, {"drawn", tally(e.drawn)}, {"boundary", tally(e.boundary)}});
  j["epsilons"] = eps;
  ordered_json dis = ordered_json::array();
  for (const Disagreement& d : v.disagreements) {
    ordered_json point = ordered_json::object();
    for (const auto& [name, x] : d.point) point[name] = verify::to_string(x);
    dis.push_back({{"epsilon", verify::to_string(v.epsilons[static_cast<std::size_t>(d.epsilon_index)].epsilon)},
                   {"near_boundary", d.near},
                   {"point", point},
                   {"actual_case", d.actual_case},
                   {"quantity", d.quantity},
                   {"truth", d.truth},
                   {"exact_holds", d.exact},
                   {"asymptotic_holds", d.asymptotic},
                   {"exact_form_disagrees", d.exact_form},
                   {"details", d.details}});
  }
  j["disagreements"] = dis;
  return j;
}

}  // namespace superball::present
