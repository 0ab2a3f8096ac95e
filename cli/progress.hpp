#pragma once
/// \file progress.hpp
/// Progress of a long command on standard error, step by step ("derive: case
/// 3 of 16 ({2-3,4-5})"), the way `verify` shows its bar: on a terminal, one
/// line redrawn in place, shown only once the command has run for
/// kProgressDelay and erased at the end; nothing when standard error is not
/// a terminal or with --quiet.  With --progress, from the first step
/// whatever standard error is: one line per step when it is not a terminal
/// (a log file), the redrawn line on a terminal.

#include <CLI/CLI.hpp>

#include <chrono>
#include <condition_variable>
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
  /// Progress of \p steps steps, each line "COMMAND: NOUN k of STEPS (what)".
  StepProgress(std::string command, std::string noun, int steps, ProgressMode mode);
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

}  // namespace superball::cli
