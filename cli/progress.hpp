#pragma once
/// \file progress.hpp
/// Progress of a long command on standard error, and Ctrl-C.  Step by step
/// ("derive: case 3 of 16 ({2-3,4-5})"): on a terminal, one line redrawn in
/// place, shown only once the command has run for kProgressDelay and erased
/// at the end; nothing when standard error is not a terminal or with
/// --quiet.  With --progress, from the first step whatever standard error
/// is: one line per step when it is not a terminal (a log file), the redrawn
/// line on a terminal.  Or as a bar over tasks (`verify`, `explore`), on a
/// terminal only.  InterruptHandler turns Ctrl-C into a request the command
/// polls, so that it stops cleanly and exits with kInterruptedExit.

#include <CLI/CLI.hpp>

#include <chrono>
#include <condition_variable>
#include <csignal>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace superball::cli {

/// How long a command runs before its progress appears on a terminal.
inline constexpr std::chrono::milliseconds kProgressDelay{2000};

/// When progress is shown (--quiet, the default, --progress).
enum class ProgressMode { Quiet, Auto, Always };

/// The flags --quiet and --progress, exclusive.
struct ProgressOptions {
  bool quiet = false, progress = false;
  ProgressMode mode() const { return quiet ? ProgressMode::Quiet : progress ? ProgressMode::Always : ProgressMode::Auto; }
};

/// Register --quiet,-q and --progress on \p cmd, writing into \p o; \p noun
/// names a step in the help ("case").
void add_progress_options(CLI::App* cmd, ProgressOptions& o, const std::string& noun);

/// The steps of one command on standard error (see the file's comment).  A
/// timer thread shows the current step once kProgressDelay has passed, so
/// that a single long step is seen too.  Writes are serialised.
class StepProgress {
 public:
  /// Progress of \p steps steps, each line "COMMAND: NOUN k of STEPS (what)";
  /// on a terminal (by default) shown from kProgressDelay after \p started
  /// (a command's stages, each with its own progress, as one run).
  StepProgress(std::string command, std::string noun, int steps, ProgressMode mode,
               std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now());
  StepProgress(const StepProgress&) = delete;
  StepProgress& operator=(const StepProgress&) = delete;
  /// Stops the timer and erases the terminal line, if drawn.
  ~StepProgress();
  /// Step \p k (1-based) of the total starts; \p what says which ("case 2.2 ({3-4})").
  void step(int k, const std::string& what);
  /// What follows the steps ("writing 8 cases as text"), shown as a step is.
  void note(const std::string& what);

 private:
  void draw();  // under lock_

  std::string command_, noun_;
  int steps_;
  bool terminal_, shown_, active_;
  bool drawn_ = false, done_ = false;
  std::string current_;
  std::mutex lock_;
  std::condition_variable wake_;
  std::thread timer_;
};

/// The bar of a command whose tasks report (done, planned) as they go
/// (`verify`, `explore`): "COMMAND LABEL [#####     ] 42%" on standard
/// error, drawn only when \p shown (not --quiet), standard error is a
/// terminal and the run has lasted kBarDelay; redrawn at most every
/// kBarPeriod, erased at the end.
class TaskProgress {
 public:
  /// The bar is drawn only after this long, and redrawn at most this often.
  static constexpr std::chrono::milliseconds kBarDelay{1000}, kBarPeriod{100};
  /// A bar for \p tasks tasks of \p command ("verify").
  TaskProgress(std::string command, int tasks, bool shown);
  TaskProgress(const TaskProgress&) = delete;
  TaskProgress& operator=(const TaskProgress&) = delete;
  /// Erases the bar, if drawn.
  ~TaskProgress();
  /// The progress of task \p task (0-based), shown as \p label; empty when no bar is drawn.
  std::function<void(long long, long long)> for_task(int task, const std::string& label);

 private:
  std::string command_;
  int tasks_;
  bool terminal_, drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

/// The exit code of a run stopped by Ctrl-C (128 + SIGINT, as a shell reports it).
inline constexpr int kInterruptedExit = 128 + SIGINT;

/// SIGINT handled while this object lives (not where the caller ignores it,
/// e.g. a background job of a shell without job control): the first one
/// asks the run to stop (requested() becomes true; the command polls it,
/// stops and exits with kInterruptedExit); a second one does what SIGINT did
/// before (Output's: remove its temporary and end the process).
class InterruptHandler {
 public:
  InterruptHandler();
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;
  /// Whether Ctrl-C asked the run to stop.
  static bool requested();

 private:
  bool installed_ = false;
};

}  // namespace superball::cli
