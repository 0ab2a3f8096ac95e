// `superball audit`: the paper's printed conditions and claims in words
// (cases/paper/printed-conditions.toml) against the symbolic derivation and
// the exact numeric solution (superball::verify).
#include <nlohmann/json.hpp>

#include <memory>

#include "commands.hpp"
#include "superball/cases/number.hpp"
#include "superball/cases/printed_conditions.hpp"
#include "superball/verify/audit.hpp"

namespace superball::cli {
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

}  // namespace

void add_audit(CLI::App& app, Action& action) {
  struct Options {
    std::string epsilon = "1/1000", output;
    int samples = 20000;
    std::uint64_t seed = 1;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("audit", "The paper's printed conditions and claims against the derivation and exact solutions");
  cmd->footer(
      "Every condition the paper prints for case 1 (alpha_2), 2.1 (alpha_1, alpha_6) and 3.2 (alpha_5), and its\n"
      "claims in words, are transcribed in cases/paper/printed-conditions.toml.  For each printed condition the\n"
      "audit says: identical to the exact condition (m4 = infinity), identical at the asymptotic order (the\n"
      "dominant balance for m1 ~ eps, K14 ~ 1/eps), or different.  For a different one it shows a parameter point\n"
      "(M positive semi-definite, m1 = eps * O(1), K14 = O(1) / eps) where the printed condition and the exact\n"
      "solution of the case (numeric backend, rationals) disagree, and what the derived conditions say there.\n"
      "Claims: 'superball possible' needs a point where the case is the actual evolution with U1+ > a;\n"
      "'superball impossible' needs a proof (the superball condition against a quadratic form of M).\n\n"
      "Examples:\n"
      "  superball audit\n"
      "  superball audit --epsilon 1/100000 --samples 50000 --seed 7\n"
      "  superball audit --json -o audit.json");
  cmd->add_option("--epsilon", o->epsilon, "The small parameter of the sampled points, a number or fraction in (0, 1)")->capture_default_str();
  cmd->add_option("--samples", o->samples, "Points tried per search")->check(CLI::Range(1, 10000000))->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the pseudo-random points")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON for programs");
  cmd->add_option("--output,-o", o->output, "Write to this file instead of standard output")->check(non_empty());
  cmd->callback([o, &action] {
    action = [o] {
      verify::AuditOptions options;
      const Number eps = Number::parse(o->epsilon);
      options.epsilon = cln::cl_RA((eps.numerator + "/" + eps.denominator).c_str());
      options.samples = o->samples;
      options.seed = o->seed;
      const verify::Audit a = verify::audit_paper(PrintedConditions::paper(), options);
      const std::string text = o->json ? audit_json(a).dump(2) + "\n" : verify::to_text(a);
      write_output(o->output, text);
      return ok;
    };
  });
}

}  // namespace superball::cli
