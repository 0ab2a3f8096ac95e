// `superball reproduce`: recompute the paper's numbers and write a report.
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "present.hpp"
#include "superball/cases/printed.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/sweep.hpp"

#ifndef SUPERBALL_SCENES_DIR
#define SUPERBALL_SCENES_DIR "cases/scenes"
#endif

namespace superball::cli {
namespace {

/// Half a unit of the last digit printed in \p printed ("3.3069" -> 5e-5).
double printed_half_ulp(const Number& printed) {
  const auto dot = printed.text.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(printed.text.size() - dot - 1);
  return 0.5 * std::pow(10.0, -decimals);
}

std::string fixed(double x, int decimals) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(decimals);
  os << x;
  return os.str();
}

std::string decimal(const cln::cl_RA& x, int digits) { return numeric::to_decimal(x, digits); }

struct Section {
  std::string markdown;
  int matches = 0, total = 0;
};

/// Eq. (16): both readings of §4.4, exact.
Section eq16(const std::string& dir) {
  const PrintedNumbers& printed = PrintedNumbers::paper();
  const numeric::Precision exact{numeric::Precision::Kind::Exact, 0};
  const char* files[] = {"paper-4.4-as-printed.toml", "paper-4.4-alpha2.toml"};
  std::vector<Presented> runs;
  for (const char* f : files) runs.push_back(solve_scene(load_scene(dir + "/" + f), exact));
  Section s;
  std::ostringstream os;
  os << "## Eq. (16): velocities after the collision, §" << printed.eq16_section << "\n\n"
     << "Exact solves (CLN rationals) of the two readings of §4.4: the coupling -100 on alpha_4 as printed, "
        "and on alpha_2.  A value matches when it rounds to the paper's printed digits.\n\n"
     << "| body | paper | as printed (alpha_4 = -100) | match | alpha_2 = -100 | match |\n|---|---|---|---|---|---|\n";
  std::vector<int> matches(runs.size(), 0);
  for (std::size_t i = 0; i < printed.eq16_velocities.size(); ++i) {
    const Number& p = printed.eq16_velocities[i];
    os << "| " << i + 1 << " | " << p.text;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const double v = runs[r].after[i];
      const bool ok = std::fabs(v - p.approx()) <= printed_half_ulp(p) * (1 + 1e-12);
      matches[r] += ok;
      os << " | " << numeric::to_string(v, 8) << " | " << (ok ? "yes" : "**no**");
    }
    os << " |\n";
  }
  os << "| case | " << printed.eq16_case;
  for (const auto& r : runs) os << " | " << r.case_name << " | " << (r.case_name == printed.eq16_case ? "yes" : "**no**");
  os << " |\n\n";
  for (std::size_t r = 0; r < runs.size(); ++r)
    os << "- `" << runs[r].origin << "`: " << matches[r] << " of " << printed.eq16_velocities.size()
       << " velocities match the printed digits; U1+ exact = " << runs[r].after_text[0] << "; superball: "
       << (runs[r].superball ? "yes" : "no") << ".\n";
  os << "\nWhich single coupling of M carries the -100?  Every alpha_k = +-100 in place of alpha_4 = -100, the rest "
        "as printed, exact solves:\n\n| coupling | value | M positive semi-definite | velocities matching eq. (16) | case |\n"
        "|---|---|---|---|---|\n";
  const Scene printed_scene = load_scene(dir + "/" + files[0]);
  const Vocabulary& vocab = Vocabulary::paper();
  for (const auto& alpha : vocab.alphas())
    for (const char* value : {"-100", "100"}) {
      Scene scene = printed_scene;
      scene.entries.erase(std::remove_if(scene.entries.begin(), scene.entries.end(), [](const MatrixEntry& e) { return !e.diagonal(); }),
                          scene.entries.end());
      Parameter::parse("alpha." + std::to_string(alpha.index), scene).set(scene, Number::parse(value));
      os << "| alpha_" << alpha.index << " | " << value << " | ";
      try {
        const Presented r = solve_scene(scene, exact);
        int m = 0;
        for (std::size_t i = 0; i < printed.eq16_velocities.size(); ++i)
          m += std::fabs(r.after[i] - printed.eq16_velocities[i].approx()) <= printed_half_ulp(printed.eq16_velocities[i]) * (1 + 1e-12);
        os << "yes | " << m << " of " << printed.eq16_velocities.size() << " | " << r.case_name << " |\n";
      } catch (const InputError& e) {
        os << "no | - | - |\n";
      }
    }
  os << '\n';
  s.markdown = os.str();
  s.matches = matches.back() == static_cast<int>(printed.eq16_velocities.size());
  s.total = 1;
  return s;
}

/// Fig. 7: switch points along K34 for both readings, beside the printed ones.
Section fig7(const std::string& dir) {
  const PrintedNumbers& printed = PrintedNumbers::paper();
  const Vocabulary& v = Vocabulary::paper();
  std::ostringstream os;
  os << "## Fig. 7: where the evolution case changes along K34, §4.4\n\n"
     << "`superball sweep SCENE --vary K.3-4=0:20:401 --switch-points`: bisection on the exact solution "
        "between sweep values of different cases.\n\n"
     << "| scene | paper | computed switch K34 | cases | relative difference |\n|---|---|---|---|---|\n";
  Section s;
  for (const char* f : {"paper-4.4-as-printed.toml", "paper-4.4-alpha2.toml"}) {
    const Scene scene = load_scene(dir + "/" + f);
    const Parameter k34 = Parameter::parse("K.3-4", scene);
    const auto points = numeric::sweep(scene, k34, numeric::linspace(0, 20, 401), {numeric::Precision::Kind::Double, 0});
    const auto switches = numeric::switch_points(scene, k34, points);
    for (const auto& p : printed.switches) {
      os << "| `" << f << "` | " << p.value.text << " (case " << p.case_name << ") | ";
      const numeric::SwitchPoint* found = nullptr;
      for (const auto& sw : switches)
        if (v.case_name(sw.below) == p.case_name || v.case_name(sw.above) == p.case_name) found = &sw;
      if (!found) {
        os << "none in 0..20 | - | - |\n";
        continue;
      }
      const cln::cl_RA mid = (found->low + found->high) / 2;
      os << decimal(mid, 4) << " (" << decimal(mid, 15) << ") | " << v.case_name(found->below) << " -> "
         << v.case_name(found->above) << " | " << fixed(100 * (cln::double_approx(mid) - p.value.approx()) / p.value.approx(), 2)
         << " % |\n";
      ++s.total;
    }
  }
  os << '\n';
  s.markdown = os.str();
  return s;
}

/// §4.1: the epsilon family, exact, obstacle of infinite mass.
Section epsilon_family(const std::string& dir) {
  const Scene base = load_scene(dir + "/paper-4.1-family.toml");
  const Vocabulary& v = Vocabulary::paper();
  std::ostringstream os;
  os << "## The epsilon family of §4.1 (case 1, alpha_2 = -1, m4 = infinity, a = 1)\n\n"
     << "K12 = -alpha2 (1 - eps + eps^2), K13 = -alpha2 eps^2, K14 = -alpha2 (1 + eps), m1 = -alpha2 eps^3; "
        "other parameters from `cases/scenes/paper-4.1-family.toml`.  Exact solves.\n\n"
     << "| eps | case | U1+/a exact | U1+/a | 1/(2 eps) | U1+ / (a/(2 eps)) |\n|---|---|---|---|---|---|\n";
  Section s;
  for (int k = 1; k <= 6; ++k) {
    cln::cl_RA eps = 1;
    for (int j = 0; j < k; ++j) eps = eps / 10;
    Scene scene = base;
    const cln::cl_RA alpha2 = -1;
    auto set = [&](const std::string& key, const cln::cl_RA& x) { Parameter::parse(key, scene).set(scene, Number::parse(numeric::to_string(x))); };
    set("K.1-2", -alpha2 * (1 - eps + eps * eps));
    set("K.1-3", -alpha2 * eps * eps);
    set("K.1-4", -alpha2 * (1 + eps));
    set("mass.1", -alpha2 * eps * eps * eps);
    set("alpha.2", alpha2);
    const auto problem = numeric::Problem<cln::cl_RA>::from(numeric::ExactScene::from(scene));
    const auto sol = numeric::solve(problem);
    const cln::cl_RA u1 = sol.velocities_after[0] * problem.unit;
    const cln::cl_RA claim = 1 / (2 * eps);
    os << "| 1e-" << k << " | " << v.case_name(sol.closed) << " | " << numeric::to_string(u1) << " | " << decimal(u1, 10) << " | "
       << decimal(claim, 10) << " | " << decimal(u1 / claim, 10) << " |\n";
    s.total++;
    s.matches += v.case_name(sol.closed) == "1";
  }
  os << "\nThe ratio tends to 1 as eps -> 0: U1+ = a/(2 eps) holds to leading order (the exact value of the paper's "
        "formula on this family is a (1 - eps^2) / (eps (2 + eps)) = a/(2 eps) - a/4 + O(eps)).\n\n";
  s.markdown = os.str();
  return s;
}

/// cases/scenes below the working folder when there is one (paths in the
/// report stay relative), else the source tree's.
std::string default_scenes() {
  struct stat st {};
  return ::stat("cases/scenes", &st) == 0 && S_ISDIR(st.st_mode) ? "cases/scenes" : SUPERBALL_SCENES_DIR;
}

}  // namespace

void add_reproduce(CLI::App& app, Action& action) {
  struct Options {
    std::string out = "report", scenes = default_scenes();
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("reproduce", "Recompute the paper's numbers (eq. 16, Fig. 7, §4.1) and write a report");
  cmd->footer(
      "Every number in the report is computed by this run from the scene files in --scenes; the paper's\n"
      "printed numbers (cases/paper/printed-numbers.toml) are shown beside them for comparison only.\n\n"
      "Example:\n  superball reproduce --out report   # writes report/report.md and prints it");
  cmd->add_option("--out,-o", o->out, "Report folder (created if missing)")->capture_default_str();
  cmd->add_option("--scenes", o->scenes, "Folder of the paper's scene files")->capture_default_str();
  cmd->callback([o, &action] {
    action = [o] {
      std::ostringstream md;
      md << "# superball reproduce: the paper's numbers recomputed\n\n"
         << "Paper: Collision of four balls aligned (Fremond's theory).  Scenes: `" << o->scenes << "`.\n\n";
      const Section sections[] = {eq16(o->scenes), fig7(o->scenes), epsilon_family(o->scenes)};
      for (const auto& s : sections) md << s.markdown;
      if (::mkdir(o->out.c_str(), 0777) != 0 && errno != EEXIST)
        throw std::runtime_error("reproduce: --out " + o->out + ": cannot create the folder");
      write_file_atomically(o->out + "/report.md", md.str());
      std::cout << md.str() << "(written to " << o->out << "/report.md)\n";
      return ok;
    };
  });
}

}  // namespace superball::cli
