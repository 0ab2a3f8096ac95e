#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <utility>

namespace superball::cli {
namespace {

volatile std::sig_atomic_t interrupt_requested = 0;
struct sigaction interrupt_previous {};

/// The first SIGINT asks the run to stop; a second one does what SIGINT did before.
extern "C" void request_interrupt(int signal) {
  if (interrupt_requested) {
    ::sigaction(signal, &interrupt_previous, nullptr);
    std::raise(signal);
    return;
  }
  interrupt_requested = 1;
}

}  // namespace

InterruptHandler::InterruptHandler() {
  interrupt_requested = 0;
  if (::sigaction(SIGINT, nullptr, &interrupt_previous) != 0 || interrupt_previous.sa_handler == SIG_IGN) return;
  struct sigaction act {};
  act.sa_handler = request_interrupt;
  sigemptyset(&act.sa_mask);
  installed_ = ::sigaction(SIGINT, &act, nullptr) == 0;
}

InterruptHandler::~InterruptHandler() {
  if (installed_) ::sigaction(SIGINT, &interrupt_previous, nullptr);
}

bool InterruptHandler::requested() { return interrupt_requested != 0; }

TaskProgress::TaskProgress(std::string command, int tasks, bool shown)
    : command_(std::move(command)), tasks_(tasks), terminal_(shown && ::isatty(STDERR_FILENO) == 1) {}

TaskProgress::~TaskProgress() {
  if (drawn_) std::cerr << "\r\033[K" << std::flush;
}

std::function<void(long long, long long)> TaskProgress::for_task(int task, const std::string& label) {
  if (!terminal_) return {};
  return [this, task, label](long long done, long long planned) {
    const auto now = std::chrono::steady_clock::now();
    if (now - start_ < kBarDelay || (drawn_ && now - last_ < kBarPeriod && done < planned)) return;
    last_ = now;
    drawn_ = true;
    const double f = (task + static_cast<double>(done) / static_cast<double>(std::max(planned, 1LL))) / tasks_;
    constexpr int width = 30;
    const int full = static_cast<int>(f * width);
    std::cerr << "\r" << command_ << " " << label << " [" << std::string(static_cast<std::size_t>(full), '#')
              << std::string(static_cast<std::size_t>(width - full), ' ') << "] " << static_cast<int>(100 * f) << "%\033[K" << std::flush;
  };
}

void add_progress_options(CLI::App* cmd, ProgressOptions& o, const std::string& noun) {
  CLI::Option* quiet = cmd->add_flag("--quiet,-q", o.quiet, "No progress on standard error");
  cmd->add_flag("--progress", o.progress,
                "Progress on standard error from the start, one line per " + noun +
                    " when it is not a terminal (by default: on a terminal only, after " +
                    std::to_string(std::chrono::duration_cast<std::chrono::seconds>(kProgressDelay).count()) + " s)")
      ->excludes(quiet);
}

StepProgress::StepProgress(std::string command, std::string noun, int steps, ProgressMode mode, std::chrono::steady_clock::time_point started)
    : command_(std::move(command)),
      noun_(std::move(noun)),
      steps_(steps),
      terminal_(::isatty(STDERR_FILENO) == 1),
      shown_(mode == ProgressMode::Always),
      active_(mode == ProgressMode::Always || (mode == ProgressMode::Auto && terminal_)) {
  if (!active_ || shown_) return;
  timer_ = std::thread([this, started] {
    std::unique_lock<std::mutex> hold(lock_);
    if (wake_.wait_until(hold, started + kProgressDelay, [this] { return done_; })) return;
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
