// The audit for people and programs (`superball audit`, `--json`, the Python module's audit()).
#include "superball/present/audit.hpp"

#include <cln/rational_io.h>

#include <cctype>
#include <sstream>
#include <string>

#include "superball/verify/space.hpp"

namespace superball::present {

namespace {

nlohmann::ordered_json witness_json(const verify::Witness& w) {
  nlohmann::ordered_json j;
  nlohmann::ordered_json point = nlohmann::ordered_json::object();
  for (const auto& [name, v] : w.point) point[name] = verify::to_string(v);
  j["point"] = point;
  j["quantity"] = w.quantity;
  if (!w.actual_case.empty()) j["actual_case"] = w.actual_case;
  j["printed_holds"] = w.printed;
  j["exact_solution_holds"] = w.numeric;
  j["derived_exact_holds"] = w.derived_exact;
  j["derived_asymptotic_holds"] = w.derived_asymptotic;
  return j;
}

}  // namespace

nlohmann::ordered_json audit_json(const verify::Audit& a) {
  nlohmann::ordered_json j;
  j["epsilon"] = verify::to_string(a.options.epsilon);
  j["samples"] = a.options.samples;
  j["seed"] = a.options.seed;
  nlohmann::ordered_json conditions = nlohmann::ordered_json::array();
  for (const auto& c : a.conditions) {
    nlohmann::ordered_json x;
    x["section"] = c.printed.section;
    x["case"] = c.printed.case_name;
    x["alphas"] = c.printed.alphas;
    x["kind"] = c.printed.kind;
    x["about"] = c.printed.about;
    x["printed"] = c.printed.printed;
    x["printed_text"] = c.as_printed.text;
    x["printed_latex"] = c.as_printed.latex;
    x["derived_exact"] = c.exact.text;
    x["derived_exact_latex"] = c.exact.latex;
    x["derived_asymptotic"] = c.asymptotic.text;
    x["derived_asymptotic_latex"] = c.asymptotic.latex;
    x["verdict"] = verify::to_string(c.agreement);
    x["notes"] = c.notes;
    if (c.witness) x["witness"] = witness_json(*c.witness);
    x["tried"] = c.tried;
    conditions.push_back(x);
  }
  j["conditions"] = conditions;
  nlohmann::ordered_json claims = nlohmann::ordered_json::array();
  for (const auto& c : a.claims) {
    nlohmann::ordered_json x;
    x["id"] = c.claim.id;
    x["section"] = c.claim.section;
    x["text"] = c.claim.text;
    x["supported"] = c.supported;
    x["verdict"] = c.verdict;
    x["derived_superball"] = c.superball.text;
    x["derived_superball_latex"] = c.superball.latex;
    x["comparisons"] = c.comparisons;
    if (!c.certificate.empty()) x["certificate"] = c.certificate;
    if (c.example) x["example"] = witness_json(*c.example);
    x["tried"] = c.tried;
    x["hits"] = c.hits;
    claims.push_back(x);
  }
  j["claims"] = claims;
  return j;
}

std::string to_text(const verify::Audit& audit) {
  std::ostringstream os;
  auto decimal = [](const cln::cl_RA& x) {
    std::ostringstream d;
    d.precision(6);
    d << cln::double_approx(x);
    return d.str();
  };
  auto point = [&](const verify::Witness& w) {
    std::string s;
    for (const auto& [name, v] : w.point) s += (s.empty() ? "" : ", ") + name + " = " + verify::to_string(v) + (cln::denominator(v) == 1 ? "" : " (" + decimal(v) + ")");
    return s;
  };
  auto yes = [](bool b) { return b ? "holds" : "fails"; };
  os << "superball audit: the paper's printed conditions against the derivation\n"
     << "(bottom body fixed, m4 = inf; regime m1 ~ eps, K14 ~ 1/eps, others O(1); points sampled at eps = " << verify::to_string(audit.options.epsilon)
     << ", M positive semi-definite; the exact solution of each point is the numeric backend's, in rationals)\n\n";
  int counts[3] = {0, 0, 0};
  for (const verify::ConditionAudit& c : audit.conditions) {
    ++counts[static_cast<int>(c.agreement)];
    os << "§" << c.printed.section << " case " << c.printed.case_name << ", " << c.printed.kind << " " << c.printed.about << " — " << c.printed.words << '\n';
    os << "  printed:    " << c.as_printed.text << "      [paper: " << c.printed.printed << "]\n";
    os << "  derived:    exact " << c.exact.text << '\n';
    os << "              asymptotic " << c.asymptotic.text << '\n';
    if (c.printed.kind != "velocity") os << "  printed, dominant balance: " << c.printed_asymptotic.text << '\n';
    std::string verdict = verify::to_string(c.agreement);
    for (char& ch : verdict) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    os << "  verdict:    " << verdict << '\n';
    for (const std::string& n : c.notes) os << "  note:       " << n << '\n';
    if (c.agreement == verify::Agreement::Different) {
      if (c.witness) {
        const verify::Witness& w = *c.witness;
        os << "  point:      " << point(w) << '\n';
        os << "  there:      exact solution of case " << c.printed.case_name << ": " << w.quantity << " -> the condition " << yes(w.numeric)
           << "; printed " << yes(w.printed) << " (disagrees); derived exact " << yes(w.derived_exact) << (w.derived_exact == w.numeric ? " (agrees)" : " (DISAGREES)")
           << "; derived asymptotic " << yes(w.derived_asymptotic) << (w.derived_asymptotic == w.numeric ? " (agrees)" : " (disagrees)");
        if (!w.actual_case.empty()) os << "; actual case there " << w.actual_case;
        os << " [" << c.tried << " points tried]\n";
      } else {
        os << "  no disagreeing point in " << c.tried << " samples\n";
      }
    }
    os << '\n';
  }
  for (const verify::ClaimAudit& c : audit.claims) {
    os << "claim (§" << c.claim.section << "): \"" << c.claim.text << "\"\n";
    os << "  derived superball condition in case " << c.claim.case_name << ": " << c.superball.text << '\n';
    for (const std::string& line : c.comparisons) os << "  vs the like pattern: " << line << '\n';
    if (!c.certificate.empty()) os << "  certificate: " << c.certificate << '\n';
    if (c.example) os << "  example:    " << point(*c.example) << " -> " << c.example->quantity << ", actual case " << c.example->actual_case << '\n';
    os << "  verdict:    " << c.verdict << " (" << c.tried << " points tried, " << c.hits << " with the superball in the case)\n\n";
  }
  os << "summary: " << counts[0] << " printed conditions identical to the exact condition, " << counts[1] << " identical at the asymptotic order, "
     << counts[2] << " different\n";
  return os.str();
}

}  // namespace superball::present
