#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/sweep.hpp"

namespace superball::cli {
namespace {

struct Range {
  Parameter parameter;
  cln::cl_RA from, to;
  int steps;
};

/// KEY=FROM:TO:STEPS, e.g. K.3-4=0:20:401.
Range parse_vary(const std::string& text, const Scene& scene) {
  const auto eq = text.find('=');
  auto bad = [&](const std::string& why) -> std::invalid_argument {
    return std::invalid_argument("--vary " + text + ": " + why + " (expected KEY=FROM:TO:STEPS, e.g. K.3-4=0:20:401)");
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
    r.from = numeric::parse_rational(Number::parse(rest.substr(0, c1)).fraction());
    r.to = numeric::parse_rational(Number::parse(rest.substr(c1 + 1, c2 - c1 - 1)).fraction());
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
  if (used != steps.size() || s < 2 || s > 10000000) throw bad("STEPS must be a whole number from 2 to 10000000");
  if (r.from == r.to) throw bad("FROM and TO are equal");
  r.steps = static_cast<int>(s);
  return r;
}

std::string decimal(const cln::cl_RA& x, int digits = 17) { return numeric::to_decimal(x, digits); }

}  // namespace

void add_sweep(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, vary, precision = "double";
    bool csv = false, switches = false;
    int threads = numeric::thread_count(0);
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("sweep", "Velocities after the collision along one parameter, and where the case changes");
  cmd->footer(
      "KEY names a parameter: K.i-j, alpha.k (n = 4), coupling.i-j/k-l, mass.i, velocity.i, drop_height,\n"
      "fall_speed, g.  FROM and TO are numbers or fractions (exact); STEPS counts the values, ends included.\n"
      "--switch-points bisects on the exact solution (CLN rationals) between sweep values whose evolution\n"
      "case differs, to 64 bits below the step.  The values are solved on --threads threads (default: all\n"
      "cores); the output does not depend on the number of threads.\n\n"
      "Examples:\n"
      "  superball sweep cases/scenes/paper-4.4-alpha2.toml --vary K.3-4=0:20:401 --csv\n"
      "  superball sweep cases/scenes/paper-4.4-alpha2.toml --vary K.3-4=0:20:41 --switch-points");
  cmd->add_option("scene", o->scene, "Scene file (TOML)")->required();
  cmd->add_option("--vary", o->vary, "KEY=FROM:TO:STEPS")->required();
  cmd->add_option("--precision,-p", o->precision, "Arithmetic of the sweep values (see solve)")->capture_default_str();
  cmd->add_flag("--csv", o->csv, "Print CSV: the parameter, U1..Un, the case");
  cmd->add_flag("--switch-points", o->switches, "Print only the parameter values where the evolution case changes");
  cmd->add_option("--threads,-j", o->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  cmd->callback([o, &action] {
    action = [o] {
      const Scene scene = load_scene(o->scene);
      const Range r = parse_vary(o->vary, scene);
      const auto precision = numeric::Precision::parse(o->precision);
      const auto points = numeric::sweep(scene, r.parameter, numeric::linspace(r.from, r.to, r.steps), precision, o->threads);
      const Vocabulary& v = Vocabulary::paper();
      std::ostringstream os;
      int failures = 0;
      if (o->switches) {
        const auto switches = numeric::switch_points(scene, r.parameter, points, 64, o->threads);
        if (switches.empty()) os << "no change of evolution case for " << r.parameter.key() << " in the range\n";
        for (const auto& s : switches)
          os << r.parameter.key() << " = " << decimal((s.low + s.high) / 2) << "  (bracket width "
             << decimal(s.high - s.low, 3) << "): case " << v.case_name(s.below) << " " << s.below.to_string() << " -> case "
             << v.case_name(s.above) << " " << s.above.to_string() << '\n';
      } else {
        const std::string sep = o->csv ? "," : "  ";
        os << r.parameter.key();
        for (int i = 1; i <= scene.size(); ++i) os << sep << "U" << i;
        os << sep << "case\n";
        for (const auto& p : points) {
          os << decimal(p.value, 10);
          for (double w : p.velocities_after) os << sep << numeric::to_string(w, o->csv ? 17 : 8);
          os << sep << v.case_name(p.closed);
          if (p.status != numeric::Status::Success) os << sep << numeric::to_string(p.status), ++failures;
          os << '\n';
        }
      }
      std::cout << os.str();
      return failures ? numerical_failure : ok;
    };
  });
}

}  // namespace superball::cli
