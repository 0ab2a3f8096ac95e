// `superball explore`: is the superball reachable for a pattern of M in an
// evolution case?  A witness found by a search on the derived conditions and
// confirmed by an exact solve, or a proof that the conditions clash
// (superball::verify::explore_case); --all-patterns gives the table of every
// single alpha_k and {alpha_1, alpha_6} against every case of n = 4.
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "distribute.hpp"
#include "progress.hpp"
#include "selection.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/scalar.hpp"
#include "superball/present/explore.hpp"
#include "superball/symbolic/workers.hpp"
#include "superball/verify/explore.hpp"

namespace superball::cli {
namespace {

/// The file name of a witness: explore_alpha1_alpha6_case2.1.toml.
std::string witness_name(const verify::ExploreResult& r) {
  std::string pattern = r.pattern_ascii;
  for (char& c : pattern)
    if (c == ',') c = '_';
  return "explore_" + pattern + "_case" + r.case_name + ".toml";
}

/// Reads back task \p k's text (a case of \p case_name explored) as data and
/// checks it: the fields of the task's JSON, the case it is of, a verdict
/// that is one of the four with what it rests on (yes: a witness whose exact
/// U1+/a exceeds 1; no (proved), case impossible: the clash that proves it,
/// and no witness beyond U1+ = a), and a witness file name that is a plain
/// name of this case.  std::invalid_argument naming the task otherwise.
nlohmann::ordered_json read_result(std::size_t k, const std::string& text, const std::string& case_name, const Distribution& run) {
  auto damaged = [&](const std::string& what) { return std::invalid_argument(run.origin(k) + ": a damaged result (" + what + ")"); };
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(text, nullptr, false);
  auto is_string = [&](const nlohmann::ordered_json& o, const char* key) { return o.contains(key) && o[key].is_string(); };
  if (j.is_discarded() || !j.is_object() || !is_string(j, "pattern") || !is_string(j, "cell") || !is_string(j, "text") || !j.contains("json") ||
      !j["json"].is_object())
    throw damaged("not the JSON of an explored case");
  const nlohmann::ordered_json& r = j["json"];
  if (!is_string(r, "case") || r["case"].get<std::string>() != case_name) throw damaged("not a result of case " + case_name);
  if (!is_string(r, "reach") || !is_string(r, "pattern")) throw damaged("no verdict");
  const std::string reach = r["reach"].get<std::string>(), cell = j["cell"].get<std::string>();
  if (reach != "yes" && reach != "no (proved)" && reach != "case impossible" && reach != "not found") throw damaged("'" + reach.substr(0, 40) + "' is not a verdict");
  if (j["text"].get<std::string>().find("  verdict: " + reach + ":") == std::string::npos || cell.rfind(reach == "yes" ? "yes " : reach, 0) != 0)
    throw damaged("its texts do not say its verdict, " + reach);
  std::optional<cln::cl_RA> ratio;
  if (r.contains("ratio")) {
    try {
      if (!r["ratio"].is_string() || r["ratio"].get<std::string>().size() > 4096) throw std::invalid_argument("");
      ratio = numeric::parse_rational(r["ratio"].get<std::string>());
    } catch (const std::exception&) {
      throw damaged("its U1+/a is not a fraction");
    }
  }
  const bool witness = j.contains("witness");
  if (witness != (r.contains("witness") && ratio.has_value())) throw damaged("a witness without its exact solve");
  if (reach == "yes" && !(witness && *ratio > 1)) throw damaged("the verdict yes without a witness where U1+ > a");
  if (reach != "yes" && ratio && *ratio > 1) throw damaged("the verdict " + reach + " with a witness where U1+ > a");
  if ((reach == "no (proved)" || reach == "case impossible") &&
      !(r.contains("clash") && r["clash"].is_object() && r["clash"].contains("superball") && r["clash"]["superball"] == (reach == "no (proved)")))
    throw damaged("the verdict " + reach + " without its proof");
  if (witness) {
    const nlohmann::ordered_json& w = j["witness"];
    if (!w.is_array() || w.size() != 2 || !w[0].is_string() || !w[1].is_string()) throw damaged("a damaged witness");
    const std::string name = w[0].get<std::string>();
    if (name.find('/') != std::string::npos || name.rfind("explore_", 0) != 0 || name.size() < case_name.size() + 18 ||
        name.compare(name.size() - case_name.size() - 10, std::string::npos, "_case" + case_name + ".toml") != 0)
      throw damaged("'" + name.substr(0, 60) + "' is not the file name of a witness of case " + case_name);
  }
  return j;
}

}  // namespace

void add_explore(CLI::App& app, Action& action) {
  struct Options {
    SelectionOptions selection;
    bool all_patterns = false, json = false, quiet = false;
    std::string box = "1e-3:1e3", out, output;
    verify::ExploreOptions explore;
    DistributeOptions distribute;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("explore", "Is the superball reachable for a pattern of M in a case? A witness checked exactly, or a proof that it is not");
  cmd->footer(
      "What it does.  For a pattern of M (which couplings are in play) and an evolution case (paper §4), it looks\n"
      "for parameters where the case is the actual evolution and U1+ > a.  The derived exact conditions of the\n"
      "case (each open contact opens, each closed contact's reaction <= 0) and the minors of M (positive\n"
      "semi-definite) define the feasible set; the search maximises U1+/a there (the derived velocity formula).\n"
      "It is a penalty method: each condition's value is normalised by the sum of the absolute values of its\n"
      "terms, any violation makes a point worse than every feasible one; Nelder-Mead runs from --starts points\n"
      "(half from the paper's regime m1 ~ eps, K14 ~ 1/eps at eps = 1/100, half uniform in the box).  The best\n"
      "points are rounded to rationals (7 significant digits) and solved exactly (rationals, the case NOT\n"
      "imposed): the case must come out as the actual evolution; if not, the search steps inward (larger margins\n"
      "on the conditions) and retries.  Same seed, same result.\n\n"
      "The box.  a = 1 (the velocities after are linear in a) and the bottom body fixed (m_n = infinity); every\n"
      "mass and K in [LOW, HIGH] of --box on a log scale; each coupling t * sqrt(K_p K_q) with t in [-1, 1], so\n"
      "its 2x2 minor of M holds.  \"Largest U1+/a found\" is a statement about that box: in the paper's regime\n"
      "U1+/a is unbounded (§4.1 gets a/(2 eps)), so a wider box gives a larger number.  Any box with\n"
      "0 < LOW < HIGH, both normal doubles, is searched (1e-300:1e300 too): a point where a condition overflows\n"
      "or underflows in double counts as infeasible, and a witness is still confirmed exactly.\n\n"
      "Without a witness it tries to prove impossibility: nonnegative weights in {0, 1, 2} on the conditions'\n"
      "polynomials N_i and Q = t * x^T M x (t in {0, 1, 2}, x in {-1, 0, 1} on the coupled pairs) such that\n"
      "-(sum w_i N_i) - Q has only nonnegative terms (even powers of couplings): then the weighted conditions\n"
      "cannot hold together when M is positive semi-definite.  Failing that, the weights become polynomial\n"
      "multipliers (nonnegative combinations of 1, m_i, K_p) on the N_i and on the 2x2 minor forms\n"
      "K_p + K_q +- 2 alpha, found by a linear programme and checked exactly.  It prints the clashing\n"
      "inequalities and the identity, for the exact conditions and for their leading-order (asymptotic) forms.\n"
      "Verdicts: yes (a witness), no (proved), case impossible (the case is never actual, proved), not found\n"
      "(with the best U1+/a seen where the case is actual, and whether the leading-order conditions clash).\n"
      "--all-patterns (64 cells) takes about 10 s with the default budget.\n\n"
      "Progress.  A progress bar is shown on standard error when it is a terminal, for runs longer than a second\n"
      "(not with --quiet).  Ctrl-C stops the search and exits with 130 and one line, writing nothing.\n\n"
      "Examples:\n"
      "  superball explore --alphas 3 --case 1                the §4.1 remark: alpha_3 alone, like alpha_2\n"
      "  superball explore --alphas 1,6 --case 1              proved impossible, with the clash\n"
      "  superball explore --alphas 4 --case 3.3 --out witnesses   writes the witness scene file\n"
      "  superball explore --alphas 5 --all --json            every case of one pattern, for programs\n"
      "  superball explore --all-patterns                     the table: each alpha_k and {alpha_1, alpha_6} x every case\n"
      "  superball explore --alphas 2 --case 1 --box 1e-2:1e2 --starts 40 --seed 7\n"
      "Check a witness: superball solve FILE --precision exact\n\n"
      "Clusters (docs/CLUSTER.md): the cases (with --all-patterns the 64 cells) are the tasks.  Under MPI\n"
      "(`mpirun -n P superball explore ...`, built with -DSUPERBALL_WITH_MPI=ON) the ranks take them as they become\n"
      "free and rank 0 writes; --shard I/N explores the tasks k with k mod N = I-1 into a part file for\n"
      "`superball merge`; --checkpoint DIR keeps each finished one.  The same bytes every way.");
  add_selection_options(cmd, o->selection, false);
  cmd->add_flag("--all-patterns", o->all_patterns, "Every single alpha_k (k = 1..7) and {alpha_1, alpha_6} against every case of n = 4, as one table");
  cmd->add_option("--seed", o->explore.seed, "Seed of the starting points")->capture_default_str();
  cmd->add_option("--starts", o->explore.starts, "Local searches (Nelder-Mead) per case, 1 to " + std::to_string(verify::max_starts))->capture_default_str();
  cmd->add_option("--evaluations", o->explore.evaluations, "Objective evaluations per local search, 10 to " + std::to_string(verify::max_evaluations))
      ->capture_default_str();
  cmd->add_option("--box", o->box, "LOW:HIGH, the range of every mass and K (log scale): 0 < LOW < HIGH, both normal doubles")->capture_default_str();
  cmd->add_option("--out", o->out, "Write each witness scene file into this folder (created if missing)")->check(non_empty());
  cmd->add_flag("--json", o->json, "Print JSON for programs");
  cmd->add_option("--output,-o", o->output, "Write the report to this file instead of standard output")->check(non_empty());
  cmd->add_flag("--quiet,-q", o->quiet, "No progress bar on standard error");
  add_distribute_options(cmd, o->distribute, "case (with --all-patterns: cell)");
  cmd->callback([o, cmd, &action] {
    action = [o, cmd]() -> int {
      std::tie(o->explore.box_low, o->explore.box_high) = verify::parse_box(o->box);
      o->explore.check();
      const SelectionOptions& sel = o->selection;
      std::ostringstream command;
      command << "superball explore";
      // The tasks: the cells of the table (pattern by pattern, case by case)
      // or the cases chosen, each explored on its own (explore_case()).
      verify::PatternTable table;
      std::optional<Selection> selection;
      std::vector<ContactSet> cases;
      if (o->all_patterns) {
        present::check_all_patterns(sel.typed());
        table.options = o->explore;
        table.patterns = verify::table_patterns();
        for (const NamedCase& c : Vocabulary::paper().cases()) {
          table.cases.push_back(c.name);
          cases.push_back(c.closed);
        }
        command << " --all-patterns";
      } else {
        present::require_case(sel.typed(), true);
        selection = resolve(sel);
        cases = selection->cases;
        command << (sel.alphas_text.empty() ? "" : " --alphas " + sel.alphas_text) << (sel.coupling.empty() ? "" : " --coupling " + sel.coupling)
                << (sel.scene.empty() ? "" : " --scene " + sel.scene) << (sel.case_name.empty() ? "" : " --case " + sel.case_name)
                << (sel.closed.empty() ? "" : " --closed " + sel.closed) << (sel.all ? " --all" : "");
      }
      command << " --seed " << o->explore.seed << " --starts " << o->explore.starts << " --evaluations " << o->explore.evaluations << " --box " << o->box;
      const std::size_t columns = cases.size(), count = o->all_patterns ? table.patterns.size() * columns : columns;
      // The table's derivers, one per pattern, made when a task first needs it (a process computes few rows).
      std::map<std::size_t, std::unique_ptr<symbolic::Deriver>> derivers;
      auto deriver = [&](std::size_t row) -> const symbolic::Deriver& {
        if (!o->all_patterns) return *selection->deriver;
        auto& d = derivers[row];
        if (!d) d = std::make_unique<symbolic::Deriver>(symbolic::Pattern::paper(table.patterns[row]), symbolic::Obstacle::Infinite);
        return *d;
      };
      // Ctrl-C is polled as the search goes (its progress) and stops it.
      const InterruptHandler interrupt;
      std::optional<TaskProgress> bar;
      auto label = [&](std::size_t k) {
        const std::string name = "case " + Vocabulary::paper().case_name(cases[k % columns]);
        if (!o->all_patterns) return name;
        std::string pattern;
        for (int a : table.patterns[k / columns]) pattern += (pattern.empty() ? "alpha" : ",alpha") + std::to_string(a);
        return pattern + " " + name;
      };
      // A task's text: the result rendered every way the output may need it (JSON).
      auto task = [&](std::size_t k) {
        verify::ExploreOptions options = o->explore;
        const auto shown = bar ? bar->for_task(static_cast<int>(k), label(k)) : nullptr;
        options.progress = [&shown](long long done, long long planned) {
          if (InterruptHandler::requested()) throw symbolic::Interrupted("interrupted");
          if (shown) shown(done, planned);
        };
        const verify::ExploreResult r = verify::explore_case(deriver(k / columns), cases[k % columns], options);
        const present::RenderedCell cell = present::render(r);
        nlohmann::ordered_json j;
        j["pattern"] = cell.pattern;
        j["cell"] = cell.text;
        j["json"] = cell.json;
        j["text"] = present::to_text(r);
        if (r.scene) j["witness"] = {witness_name(r), present::witness_file(r, command.str())};
        return j.dump() + "\n";
      };
      Distribution run(run_identity(*cmd), distribute_options(o->distribute), count);
      if (run.local()) bar.emplace("explore", static_cast<int>(count), !o->quiet && run.writes_output());
      std::vector<std::vector<present::RenderedCell>> cells;
      std::vector<nlohmann::ordered_json> results;
      std::string text;
      std::vector<std::pair<std::string, std::string>> witnesses;
      try {
        run.run(task, [&](std::size_t k, std::string&& piece) {
          nlohmann::ordered_json j = read_result(k, piece, Vocabulary::paper().case_name(cases[k % columns]), run);
          if (j.contains("witness")) witnesses.emplace_back(j["witness"][0].get<std::string>(), j["witness"][1].get<std::string>());
          if (o->all_patterns) {
            if (k % columns == 0) cells.emplace_back();
            cells.back().push_back({j["pattern"].get<std::string>(), j["cell"].get<std::string>(), j["json"]});
          } else if (o->json) {
            results.push_back(j["json"]);
          } else {
            text += j["text"].get<std::string>() + "\n";
          }
        });
      } catch (const symbolic::Interrupted&) {
        bar.reset();  // the bar erased before the line
        std::cerr << "superball: explore: interrupted (Ctrl-C): stopped before the end, nothing written\n";
        return kInterruptedExit;
      }
      bar.reset();
      if (!run.writes_output()) return ok;  // a part file, or a rank other than 0
      if (o->all_patterns) {
        text = o->json ? present::to_json(table, cells).dump(2) + "\n" : present::to_text(table, cells);
      } else if (o->json) {
        nlohmann::ordered_json j = nlohmann::ordered_json::array();
        for (auto& r : results) j.push_back(std::move(r));
        text = (results.size() == 1 ? j[0] : j).dump(2) + "\n";
      }
      if (!o->out.empty()) {
        std::error_code error;
        std::filesystem::create_directories(o->out, error);
        if (error) throw OutputError("--out: cannot create folder '" + o->out + "': " + error.message());
        for (const auto& [name, file] : witnesses) write_output((std::filesystem::path(o->out) / name).string(), file);
      }
      write_output(o->output, text);
      return ok;
    };
  });
}

}  // namespace superball::cli
