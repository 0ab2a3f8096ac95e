// `superball verify`: the derived conditions of evolution cases against
// exact solutions over the asymptotic regime (superball::verify), with the
// points where they disagree written as scene files.

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "commands.hpp"
#include "distribute.hpp"
#include "progress.hpp"
#include "selection.hpp"
#include "superball/cases/number.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/present/verification.hpp"
#include "superball/verify/verification.hpp"

namespace superball::cli {
namespace {

/// A file name for a case name ("3.2", "{2-3,3-4}").
std::string file_part(const std::string& name) {
  std::string out;
  for (char c : name)
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') out += c;
    else if (c == ',' || c == '/') out += '_';
  return out.empty() ? "none" : out;
}

/// \p k with leading zeros to 4 digits, so files list in run order.
std::string numbered(std::size_t k) {
  std::string s = std::to_string(k);
  return std::string(s.size() < 4 ? 4 - s.size() : 0, '0') + s;
}

}  // namespace

void add_verify(CLI::App& app, Action& action) {
  struct Options {
    SelectionOptions selection;
    std::string epsilons = "1e-2,1e-3,1e-4,1e-5,1e-6", out;
    int samples = verify::VerifyOptions{}.samples, boundary_pairs = verify::VerifyOptions{}.boundary_pairs, threads = 0;
    std::uint64_t seed = 1;
    bool json = false, quiet = false;
    DistributeOptions distribute;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("verify", "Check a case's derived conditions against exact solutions at sampled points, over epsilon");
  cmd->footer(
      "What it does.  For the case and pattern (chosen as in `derive`), parameter points of the paper's asymptotic\n"
      "regime are drawn at each epsilon (m1 ~ eps, K1n ~ 1/eps, m_n ~ 1/eps for a finite obstacle, the rest O(1);\n"
      "M positive semi-definite, exact rationals; a function of --seed only, whatever --threads).  Each point is\n"
      "solved exactly by the numeric backend, and the derived conditions (superball, evolution, contact) are\n"
      "compared with it, in their exact form (with --obstacle finite: the finite-m_n form) and asymptotic form.\n"
      "Besides the drawn points, for each condition up to --boundary-pairs segments between drawn points on\n"
      "opposite sides of it are bisected (exactly) down to 2^-20 of their length: both ends, one per side, are\n"
      "points near its boundary.  When a side has fewer drawn points than that, points of the other side are moved\n"
      "toward it (random moves of coordinates within the regime); a side still empty is said to be not reached,\n"
      "with the reason when the asymptotic form always (or never) holds: that side vanishes as eps -> 0.\n\n"
      "The table over eps.  The truth is \"the exact solution is in this case and U1+ > a\"; the conditions hold\n"
      "(H) or fail (F) and the truth is true (T) or false (F): H&T and F&F agree, H&F and F&T disagree.  'exact\n"
      "agree' must be every point (else the derivation has a defect: exit 1, with a line on stderr).  'asymptotic agree' on the drawn\n"
      "points tends to every point as eps -> 0, since the asymptotic form is the limit of the exact one; on the\n"
      "points near a boundary (within 2^-20) the two forms' boundaries are O(eps) apart, so there it agrees on\n"
      "one side only (about half) until eps is well below 2^-20 (try --epsilons 1e-9).\n"
      "Per condition.  Points on each side of it (decided by the exact solution with the case imposed), how many\n"
      "of them are near its boundary, and the agreement of each form with that condition alone.\n"
      "Every point where a form disagrees is written to --out as a scene file (its comment says what disagreed\n"
      "and how to rerun it); nothing is written when there is none.  A progress bar is shown on a terminal for\n"
      "runs longer than a second (not with --quiet).\n\n"
      "Examples:\n"
      "  superball verify --case 1 --alphas 2                       the paper's §4.1 case\n"
      "  superball verify --all --alphas 2 --threads 2\n"
      "  superball verify --case 3.2 --alphas 5 --out disagreements  then: superball solve disagreements/FILE --precision exact\n"
      "  superball verify --case 1 --alphas 2 --obstacle finite --epsilons 1/100,1/10000 --samples 2000 --seed 7\n"
      "  superball verify --closed 2-3 --bodies 5 --pairs near2 --coupling near2 --json\n\n"
      "Clusters (docs/CLUSTER.md): the cases are the tasks.  Under MPI (built with -DSUPERBALL_WITH_MPI=ON)\n"
      "`mpirun -n P superball verify --all ...` hands the cases out to the ranks, each verifying its case on its\n"
      "--threads, rank 0 writing the report and the scene files; --shard I/N verifies the cases k with\n"
      "k mod N = I-1 into a part file for `superball merge`; --checkpoint DIR keeps each verified case.  The\n"
      "same bytes every way.  One case alone (--case K) is spread over the ranks too: its blocks of 400 drawn\n"
      "points, then its boundary searches, are handed out to them (each on its --threads).");
  add_selection_options(cmd, o->selection);
  cmd->add_option("--epsilons", o->epsilons, "Values of eps in (0, 1), comma-separated (decimals, 1e-3 or fractions 1/1000)")->capture_default_str();
  cmd->add_option("--samples", o->samples, "Points drawn per eps, 1 to " + std::to_string(verify::max_verify_samples))->capture_default_str();
  cmd->add_option("--boundary-pairs", o->boundary_pairs, "Segments bisected per condition and eps, 0 to " + std::to_string(verify::max_boundary_pairs))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the pseudo-random points")->capture_default_str();
  cmd->add_option("--threads,-j", o->threads,
                  "Worker threads (default 0: all cores, " + std::to_string(std::thread::hardware_concurrency()) + " here; at most " +
                      std::to_string(numeric::max_threads) + ")");
  cmd->add_option("--out", o->out, "Write each disagreeing point as a scene file in this folder (created)")->check(non_empty());
  cmd->add_flag("--json", o->json, "Print JSON for programs");
  cmd->add_flag("--quiet,-q", o->quiet, "No progress bar on standard error");
  add_distribute_options(cmd, o->distribute, "case");
  cmd->callback([o, cmd, &action] {
    action = [o, cmd] {
      verify::VerifyOptions options;
      options.epsilons = verify::parse_epsilons(o->epsilons);
      options.samples = o->samples;
      options.boundary_pairs = o->boundary_pairs;
      options.seed = o->seed;
      options.threads = o->threads;
      options.check();
      if (!o->out.empty() && std::filesystem::exists(o->out) && !std::filesystem::is_directory(o->out))
        throw OutputError("--out " + o->out + ": exists and is not a folder");
      const Selection selection = resolve(o->selection);
      const std::size_t count = selection.cases.size();
      // One task per case: its verification as plain text, "A" or "D" (the
      // exact conditions agree or not), then each disagreement's scene file
      // ("LENGTH NAME" and the text; NAME a file name, written in --out, if
      // given, by the process that writes the output: the task says what,
      // never where), then the case's report (text, or JSON as the array's
      // dump(2) would write it), written in case order.
      auto task = [&](std::size_t k, const std::function<void(long long, long long)>& progress) {
        verify::VerifyOptions mine = options;
        mine.progress = progress;
        const verify::Verification v = verify::verify_case(*selection.deriver, selection.cases[k], mine);
        std::string text = v.exact_agrees() ? "A\n" : "D\n";
        for (std::size_t i = 0; i < v.disagreements.size(); ++i) {
          const verify::Disagreement& d = v.disagreements[i];
          const std::string name = "case-" + file_part(v.case_name) + "-eps-" +
                                   file_part(verify::epsilon_name(v.epsilons[static_cast<std::size_t>(d.epsilon_index)].epsilon)) + "-" + numbered(i + 1) + ".toml";
          const std::string scene = write_scene(d.scene, present::describe(v, d) + "\nrerun: superball solve " + name + " --precision exact");
          text += std::to_string(scene.size()) + " " + name + "\n" + scene;
        }
        text += "report\n";
        if (!o->json) return text + present::to_text(v) + "\n";
        const std::string element = present::to_json(v).dump(2);
        if (count == 1) return text + element + "\n";
        text += "  ";
        for (char ch : element) {
          text += ch;
          if (ch == '\n') text += "  ";
        }
        return text;
      };
      Distribution run(run_identity(*cmd), distribute_options(o->distribute), count);
      // One case over several ranks: every rank takes part in its verification
      // (its blocks of points handed out as tasks, run_everywhere()), so that
      // the ranks share the one task of the case; the case's text is then the
      // same on every rank, whichever the Distribution gives the task to.
      std::optional<std::string> shared;
      if (count == 1 && mpi_size() > 1 && !merged_run && !run.todo().empty()) {
        options.runner = run_everywhere;
        shared = task(0, nullptr);
      }
      const bool writes = run.writes_output();
      bool exact_agrees = true;
      int written = 0;
      std::string text = o->json && count != 1 ? (count ? "[\n" : "[]\n") : "";
      {
        TaskProgress progress("verify", static_cast<int>(count), !o->quiet && writes);
        auto label = [&](std::size_t k) {
          return "case " + Vocabulary::paper().case_name(selection.cases[k]) + (count > 1 ? " (" + std::to_string(k + 1) + "/" + std::to_string(count) + ")" : "");
        };
        run.run([&](std::size_t k) { return shared ? *shared : task(k, run.local() ? progress.for_task(static_cast<int>(k), label(k)) : nullptr); },
                [&](std::size_t k, std::string&& piece) {
                  // The task's text read back as data (it may come from a part or a checkpoint).
                  auto damaged = [&](const std::string& what) { return std::invalid_argument(run.origin(k) + ": a damaged result (" + what + ")"); };
                  if (piece.size() < 2 || (piece[0] != 'A' && piece[0] != 'D') || piece[1] != '\n') throw damaged("no verdict of the exact conditions");
                  exact_agrees = exact_agrees && piece[0] == 'A';
                  const std::string prefix = "case-" + file_part(Vocabulary::paper().case_name(selection.cases[k])) + "-eps-";
                  std::size_t at = 2;
                  while (piece.compare(at, 7, "report\n") != 0) {  // the scene files
                    const std::size_t space = piece.find(' ', at), eol = piece.find('\n', at);
                    if (space == std::string::npos || eol == std::string::npos || space > eol || space == at || space - at > 12 ||
                        piece.find_first_not_of("0123456789", at) != space)
                      throw damaged("a damaged scene file line");
                    const std::size_t size = std::stoull(piece.substr(at, space - at));
                    const std::string name = piece.substr(space + 1, eol - space - 1);
                    if (name.find('/') != std::string::npos || name.rfind(prefix, 0) != 0 || name.size() < prefix.size() + 5 ||
                        name.compare(name.size() - 5, 5, ".toml") != 0)
                      throw damaged("'" + name.substr(0, 60) + "' is not the file name of a disagreement of this case");
                    if (size > piece.size() - eol - 1) throw damaged("a scene file cut short");
                    if (!o->out.empty()) {
                      if (written == 0) {
                        std::error_code error;
                        std::filesystem::create_directories(o->out, error);
                        if (error) throw OutputError("--out " + o->out + ": cannot create the folder: " + error.message());
                      }
                      const std::string path = (std::filesystem::path(o->out) / name).string();
                      std::string scene = piece.substr(eol + 1, size);
                      const std::string rerun = "# rerun: superball solve " + name + " ";
                      const std::size_t line = scene.find(rerun);
                      if (line != std::string::npos) scene.replace(line, rerun.size(), "# rerun: superball solve " + path + " ");
                      write_output(path, scene);
                      ++written;
                    }
                    at = eol + 1 + size;
                  }
                  text += piece.substr(at + 7);
                  if (o->json && count > 1) text += k + 1 < count ? ",\n" : "\n";
                });
      }
      if (!writes) return ok;  // a part file, or a rank other than 0
      if (o->json && count > 1) text += "]\n";
      if (!o->json && !o->out.empty()) text += std::to_string(written) + " scene files written to " + o->out + "\n";
      write_output("", text);
      if (exact_agrees) return ok;
      // A mathematical outcome, not a failure of the tool: the derived exact conditions disagree with exact solutions.
      std::cerr << "superball: the exact conditions disagree with the exact solution at some points (see 'exact agree' above"
                << (o->out.empty() ? "; --out DIR writes them as scene files)\n" : ")\n");
      return numerical_failure;
    };
  });
}

}  // namespace superball::cli
