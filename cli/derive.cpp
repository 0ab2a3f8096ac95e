// `superball derive`: solve evolution cases symbolically (superball::symbolic)
// and print the velocities, reactions and conditions as text, LaTeX or JSON.
#include <nlohmann/json.hpp>

#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "distribute.hpp"
#include "progress.hpp"
#include "selection.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/memory.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/present/derivation.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/format.hpp"
#include "superball/symbolic/workers.hpp"

namespace superball::cli {

using namespace superball::symbolic;
using present::derivation_json;
using present::latex_document;
using present::report;
using present::report_psd;

void add_derive(CLI::App& app, Action& action) {
  struct Options {
    SelectionOptions selection;
    ProgressOptions progress;
    DistributeOptions distribute;
    std::string format = "text", output;
    int jobs = 0;
    bool expanded = false, task_cpu = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("derive", "Solve evolution cases symbolically: velocities, reactions and the conditions, exact and asymptotic");
  cmd->footer(
      "What it does.  A case says which adjacent contacts stay closed after the collision (paper §4).  For the\n"
      "case, the equations of motion (5) with the constitutive laws (6)-(12) are solved exactly with GiNaC:\n"
      "bodies joined by closed contacts share one velocity, the reduced system (Z^T A Z) V = Z^T b is solved by\n"
      "fraction-free determinants, the reactions come from running sums, and everything is substituted back into\n"
      "the unreduced equations.  Then the paper's conditions: superball (U1+ > a), actual evolution (each open\n"
      "contact opens, U_i+ > U_i+1+), non-interpenetration (each closed contact's reaction <= 0) and M positive\n"
      "semi-definite (its principal minors).  A denominator is cleared only when its sign is proved (it divides\n"
      "det(Z^T A Z) > 0); otherwise the output says \"sign not proved\".  Each condition is given exactly (bottom\n"
      "body fixed: m_n = infinity) and asymptotically (dominant balance for --scaling, plus --order corrections).\n\n"
      "The pattern.  Only declared entries of M are symbols; absent ones are exactly 0.  For 4 bodies the paper's\n"
      "names: K on the six pairs and the couplings alpha_1..alpha_7 (--alphas).  For any n: K on --pairs\n"
      "(all, near = j-i=1, near2 = j-i<=2, or a list) and couplings --coupling i-j/k-l,... (or near2: each pair\n"
      "(i,i+2) with (i,i+1) and (i+1,i+2)).  Or --scene FILE: the declared entries of a scene (values ignored).\n\n"
      "Examples:\n"
      "  superball derive --case 1 --alphas 2                   the paper's §4.1: U1+, -alpha2 > 2m1 + K12 + K13, ...\n"
      "  superball derive --case 2.1 --alphas 1,6 --format latex\n"
      "  superball derive --all --alphas 1,2,3,4,5,6,7 --format json -o all.json\n"
      "  superball derive --closed 2-3 --alphas 5 --order 1      one more order of epsilon\n"
      "  superball derive --case 1 --alphas 2 --scaling m1=1,K14=-1,alpha2=-1\n"
      "  superball derive --bodies 5 --pairs near2 --coupling near2 --all\n"
      "  superball derive --scene cases/scenes/paper-fig5-alpha5.toml --case 3.2 --obstacle finite\n"
      "  superball derive --bodies 6 --pairs near2 --all --progress 2> progress.log\n\n"
      "Progress.  A derivation that runs longer than " + std::to_string(std::chrono::duration_cast<std::chrono::seconds>(kProgressDelay).count()) +
      " s shows on standard error, when it is a terminal, the case it is\n"
      "at (\"derive: case 3 of 16 ({2-3,4-5})\"; LaTeX then \"derive: writing 16 cases as latex\"; with several workers\n"
      "first \"derive: preparing the 7 largest cases: 3 of 7 done\", the first of their two stages), on one line\n"
      "redrawn in place and erased before the output is written; nothing is shown when standard error is not a terminal or\n"
      "with --quiet.  --progress shows it from the first case, one line each when standard error is not a\n"
      "terminal (a log).\n\n"
      "Size.  Any number of bodies is derived (2 to 21, the engine's bound), but the time grows steeply with n\n"
      "and the pattern's width (1 for near, 2 for near2, 3 with its couplings, n-1 for all).  Before a run\n"
      "estimated over " + std::to_string(std::chrono::duration_cast<std::chrono::seconds>(kProgressDelay).count()) +
      " s one line says its estimate (not with --quiet), from the growth measured per width\n"
      "(docs/SYMBOLIC.md, Limits): \"derive: deriving every case of 7 bodies, a pattern of width 3: about 8.6 s on\n"
      "one core, 2 workers, about 166.4 MB each (23.9 GB available)\".  Only a run whose one process would not fit in\n"
      "the memory available is refused (exit 2); fewer workers are used when they would not all fit.  Ctrl-C\n"
      "stops the workers and exits with 130 and one line, writing nothing (no partial output file).\n\n"
      "JSON.  Compact by default: a form the case writes through its elimination (long forms, from about 5\n"
      "bodies) is given only that way (`eliminated`, `elimination.definitions`; a velocity as \"V1\"), readable forms\n"
      "kept, and with several cases the conditions on M (the same in every case) are in the first case only;\n"
      "--expanded adds every expanded form too, and those conditions in every case (8 bodies, near2 with couplings:\n"
      "1.68 GB instead of about 12 MB).\n\n"
      "Workers.  Text and JSON: the cases are derived in --jobs worker processes (all cores by default; GiNaC is\n"
      "not thread-safe, so processes, each a copy of this one) and written in case order as they come: the output\n"
      "does not depend on --jobs; the memory is that of the cases being derived at once (one per worker).  LaTeX\n"
      "derives every case here, in order.\n\n"
      "Clusters (text and JSON; docs/CLUSTER.md).  Under MPI (built with -DSUPERBALL_WITH_MPI=ON), `mpirun -n P\n"
      "superball derive ...` or `srun superball derive ...` hands the cases out to the ranks one at a time, rank 0\n"
      "computing too, each rank one case at a time; rank 0 writes, the same bytes as one process.  --shard I/N\n"
      "derives the cases k with k mod N = I-1 into a part file, `superball merge` joins the N parts (a Slurm job\n"
      "array).  --checkpoint DIR keeps each derived case in DIR: the same command run again after a kill derives\n"
      "only those missing.\n\n"
      "Names (JSON and --scaling): m1..mn, K12 (K1_10 past 9 bodies), alpha1..alpha7 (n = 4), c_12_14 for a\n"
      "coupling of the pairs 1-2 and 1-4, a for the fall speed, U1.. for the velocities after.");
  add_selection_options(cmd, o->selection);
  cmd->add_option("--format,-f", o->format, "text, latex (a complete document) or json")->capture_default_str();
  cmd->add_option("--output,-o", o->output, "Write to this file instead of standard output")->check(non_empty());
  cmd->add_flag("--expanded", o->expanded,
                "JSON: every form expanded too, also those written through the elimination, and the conditions on M in every case (1.7 GB at 8 bodies against about 12 MB)");
  add_progress_options(cmd, o->progress, "case");
  add_distribute_options(cmd, o->distribute, "case");
  cmd->add_option("--jobs,-j", o->jobs,
                  "Worker processes (default 0: all cores; at most " + std::to_string(numeric::max_threads) + "); the output does not depend on it")
      ->capture_default_str();
  // Hidden: how evenly the work is split (the share of the largest task), for measurements.
  cmd->add_flag("--task-cpu", o->task_cpu, "After the run, say on standard error the CPU of the tasks and the largest one's share")->group("");
  cmd->callback([o, cmd, &action] {
    action = [o, cmd]() -> int {
      const present::DeriveFormat format = present::parse_derive_format(o->format);
      const Selection selection = resolve(o->selection);
      const Deriver& deriver = *selection.deriver;
      // Refuse only what cannot fit in memory; say the estimate before a long run.
      const present::DerivePlan plan = present::plan_derivation(selection, o->jobs, numeric::available_memory());
      const ProgressMode mode = o->progress.mode();
      if (mpi_rank() == 0 && mode != ProgressMode::Quiet && plan.estimate.seconds * 1000 >= kProgressDelay.count())
        std::cerr << "derive: " << plan.text << "; Ctrl-C stops it\n";
      try {
        // Each case is written as soon as it is derived and then dropped (a
        // 7- or 8-body --all would otherwise hold every case and the whole
        // JSON tree): into the output file's temporary with -o, else into one
        // string written once the progress line is erased.  LaTeX needs every
        // case at once (latex_document).
        const bool to_file = !o->output.empty() && o->output != "-" && o->output != "/dev/stdout";
        std::optional<Output> file;
        if (to_file) file.emplace(o->output);
        std::string text;
        auto emit = [&](const std::string& piece) {
          if (file)
            file->write(piece);
          else
            text += piece;
        };
        const std::size_t count = selection.cases.size();
        const bool json = format == present::DeriveFormat::Json, latex = format == present::DeriveFormat::Latex;
        const bool shared = count > 1;  // text: the conditions on M, the same in every case, once before them
        auto name = [&](std::size_t k) {
          const ContactSet& c = selection.cases[k];
          const std::string paper = Vocabulary::paper().case_name(c);
          return paper == c.to_string() ? paper : paper + " " + c.to_string();
        };
        if (latex && (!o->distribute.shard.empty() || !o->distribute.checkpoint.empty() || mpi_size() > 1))
          throw std::invalid_argument("derive: --format latex writes one document of every case, derived in one process: "
                                      "--shard, --checkpoint and MPI apply to text and json");
        if (latex) {  // latex_document() needs every case: derived here, in order
          const InterruptHandler interrupt;
          StepProgress progress("derive", "case", static_cast<int>(count), o->progress.mode());
          std::vector<Derivation> kept;
          for (std::size_t k = 0; k < count; ++k) {
            if (InterruptHandler::requested()) throw Interrupted("interrupted");
            progress.step(static_cast<int>(k + 1), name(k));
            kept.push_back(deriver.derive(selection.cases[k]));
          }
          progress.note("writing " + std::to_string(count) + (count == 1 ? " case" : " cases") + " as latex");
          emit(latex_document(kept, deriver));
        } else {
          // One case's text: its report, or its JSON as the array's dump(2) would
          // write it (each line indented by two more).  Runs in a worker process.
          std::vector<nlohmann::ordered_json> psd;  // JSON: the conditions on M, made once per process
          std::vector<std::string> prepared(count);  // the largest cases' first stage (prepare_todo()), inherited by the workers
          auto task = [&](std::size_t k) {
            const Derivation d = deriver.derive(selection.cases[k], prepared[k], present::printed_forms(o->expanded));
            if (!json) return report(d, deriver, Style::Text, !shared) + "\n";
            // Compact, several cases: the conditions on M in the first case only (as the text writes them once).
          const std::string element = derivation_json(d, deriver, psd, o->expanded, o->expanded || !shared || k == 0).dump(2);
            if (!shared) return element + "\n";
            std::string indented = "  ";
            indented.reserve(element.size() + element.size() / 16);
            for (char ch : element) {
              indented += ch;
              if (ch == '\n') indented += "  ";
            }
            return indented;
          };
          Distribution run(run_identity(*cmd), distribute_options(o->distribute), count);
          std::optional<Workers> workers;  // forked before the progress starts its thread
          // A checkpoint the worker cannot write crosses back as a TaskError and is an OutputError again here (exit 3).
          auto in_worker = [&, kept = run.keeping(task)](std::size_t j) {
            try {
              return kept(run.todo()[j]);
            } catch (const OutputError& e) {
              throw TaskError(output_error, e.what());
            }
          };
          const InterruptHandler interrupt;  // Ctrl-C stops the first stage too
          const auto started = std::chrono::steady_clock::now();  // a terminal's line appears kProgressDelay after this, whatever the stage
          std::vector<double> first_cpu;
          std::vector<std::size_t> first;  // the cases prepared in the first stage
          if (run.local()) {
            {
              // The first stage's line: its thread starts once that stage's workers are forked and ends before the second stage's are.
              std::optional<StepProgress> preparing;
              auto shown = [&](std::size_t done, std::size_t total) {
                if (!run.writes_output()) return;
                if (!preparing) preparing.emplace("derive", "case", static_cast<int>(count), o->progress.mode(), started);
                preparing->note("preparing the " + (total == 1 ? std::string("largest case") : std::to_string(total) + " largest cases") + ": " +
                                std::to_string(done) + " of " + std::to_string(total) + " done");
              };
              first = prepare_todo(deriver, selection.cases, run.todo(), plan.workers, prepared, &InterruptHandler::requested, shown, &first_cpu);
            }
            workers.emplace(run.todo().size(), plan.workers, in_worker);
          }
          const bool writes = run.writes_output();
          std::optional<StepProgress> progress;
          if (writes) progress.emplace("derive", "case", static_cast<int>(count), o->progress.mode(), started);
          if (writes && json && shared) emit("[\n");
          if (writes && !json && shared) emit(report_psd(deriver, Style::Text) + "\n");
          if (count && progress) progress->step(1, name(0));
          run.run(
              task,
              [&](std::size_t k, std::string&& piece) {
                // The case shown is the one the output waits for next, as when the cases run one after the other.
                if (k + 1 < count && progress) progress->step(static_cast<int>(k + 2), name(k + 1));
                emit(json && shared ? piece + (k + 1 < count ? ",\n" : "\n") : piece);
              },
              [&](const std::vector<std::size_t>&, const Distribution::Task&, const Distribution::Deliver& deliver) {
                try {
                  workers->run(deliver, &InterruptHandler::requested);
                } catch (const TaskError& e) {
                  throw OutputError(e.what());
                }
              });
          if (o->task_cpu && workers) {  // the first stage's tasks, then one per case
            std::vector<double> cpu = first_cpu;
            const std::vector<PrepareTask> tasks = prepare_tasks(deriver, selection.cases, first);  // first_cpu's tasks
            cpu.insert(cpu.end(), workers->task_cpu_seconds().begin(), workers->task_cpu_seconds().end());
            std::cerr << "derive: "
                      << task_cpu_summary(cpu, [&](std::size_t j) {
                           if (j >= tasks.size()) return name(run.todo()[j - tasks.size()]);
                           const PrepareTask& t = tasks[j];
                           return "prepare " + name(t.case_index) +
                                  (t.parts > 1 ? " (part " + std::to_string(t.part + 1) + " of " + std::to_string(t.parts) + ")" : "");
                         })
                      << "\n";
          }
          if (!writes) return ok;  // a part file, or a rank other than 0
          if (json && shared) emit("]\n");
        }  // either way the progress line is erased before anything is written to standard output
        if (file)
          file->commit();
        else
          write_output(o->output, text);
      } catch (const Interrupted&) {  // the workers are stopped, the progress line erased, the output's temporary removed
        std::cerr << "superball: derive: interrupted (Ctrl-C): stopped before the end, nothing written\n";
        return kInterruptedExit;
      }
      return ok;
    };
  });
}

}  // namespace superball::cli
