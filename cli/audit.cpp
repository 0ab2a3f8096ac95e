// `superball audit`: the paper's printed conditions and claims in words
// (cases/paper/printed-conditions.toml) against the symbolic derivation and
// the exact numeric solution (superball::verify).
#include <nlohmann/json.hpp>

#include <memory>

#include "commands.hpp"
#include "superball/cases/printed_conditions.hpp"
#include "superball/present/audit.hpp"
#include "superball/verify/audit.hpp"
#include "superball/verify/verification.hpp"

namespace superball::cli {

using present::audit_json;

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
  cmd->add_option("--samples", o->samples, "Points tried per search, 1 to " + std::to_string(verify::max_audit_samples))->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the pseudo-random points")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON for programs");
  cmd->add_option("--output,-o", o->output, "Write to this file instead of standard output")->check(non_empty());
  cmd->callback([o, &action] {
    action = [o] {
      verify::AuditOptions options;
      options.epsilon = verify::parse_epsilon("epsilon", o->epsilon);
      options.samples = o->samples;
      options.seed = o->seed;
      options.check();
      const verify::Audit a = verify::audit_paper(PrintedConditions::paper(), options);
      const std::string text = o->json ? audit_json(a).dump(2) + "\n" : present::to_text(a);
      write_output(o->output, text);
      return ok;
    };
  });
}

}  // namespace superball::cli
