#include "progress.hpp"

#include <unistd.h>

#include <iostream>
#include <utility>

namespace superball::cli {

void add_progress_options(CLI::App* cmd, ProgressOptions& o, const std::string& noun) {
  CLI::Option* quiet = cmd->add_flag("--quiet,-q", o.quiet, "No progress on standard error");
  cmd->add_flag("--progress", o.progress,
                "Progress on standard error from the start, one line per " + noun +
                    " when it is not a terminal (by default: on a terminal only, after " +
                    std::to_string(std::chrono::duration_cast<std::chrono::seconds>(kProgressDelay).count()) + " s)")
      ->excludes(quiet);
}

StepProgress::StepProgress(std::string command, std::string noun, int steps, ProgressMode mode)
    : command_(std::move(command)),
      noun_(std::move(noun)),
      steps_(steps),
      terminal_(::isatty(STDERR_FILENO) == 1),
      shown_(mode == ProgressMode::Always),
      active_(mode == ProgressMode::Always || (mode == ProgressMode::Auto && terminal_)) {
  if (!active_ || shown_) return;
  timer_ = std::thread([this] {
    std::unique_lock<std::mutex> hold(lock_);
    if (wake_.wait_for(hold, kProgressDelay, [this] { return done_; })) return;
    shown_ = true;
    if (!current_.empty()) draw();
  });
}

StepProgress::~StepProgress() {
  {
    std::lock_guard<std::mutex> hold(lock_);
    done_ = true;
    if (drawn_ && terminal_) std::cerr << "\r\033[K" << std::flush;
  }
  wake_.notify_all();
  if (timer_.joinable()) timer_.join();
}

void StepProgress::step(int k, const std::string& what) {
  if (!active_) return;
  std::lock_guard<std::mutex> hold(lock_);
  current_ = command_ + ": " + noun_ + " " + std::to_string(k) + " of " + std::to_string(steps_) + " (" + what + ")";
  if (shown_) draw();
}

void StepProgress::note(const std::string& what) {
  if (!active_) return;
  std::lock_guard<std::mutex> hold(lock_);
  current_ = command_ + ": " + what;
  if (shown_) draw();
}

void StepProgress::draw() {
  if (terminal_)
    std::cerr << "\r" << current_ << "\033[K" << std::flush;
  else
    std::cerr << current_ << '\n' << std::flush;
  drawn_ = true;
}

}  // namespace superball::cli
