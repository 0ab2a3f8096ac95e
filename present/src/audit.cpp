// The JSON of the audit (`superball audit --json`, the Python module's audit()).
#include "superball/present/audit.hpp"

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

}  // namespace superball::present
