#include "gnuplot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <sstream>
#include <string_view>

#include "commands.hpp"

extern char** environ;

namespace superball::cli {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

/// The script of one figure in \p terminal: into \p output (a quoted file
/// name, or "" for gnuplot's standard output), the data read from \p data.
std::string script(const std::string& data, const Plot& p, const std::string& terminal, const std::string& output) {
  std::ostringstream gp;
  gp << "set terminal " << terminal << "\nset output " << output << '\n'
     << "set title " << quoted(p.title) << "\nset xlabel " << quoted(p.xlabel) << "\nset ylabel " << quoted(p.ylabel) << '\n'
     << "set grid\nset key " << p.key << "\nset format y '%g'\n";
  if (p.logx) gp << "set logscale x\nset format x '10^{%L}'\n";
  if (p.logy) gp << "set logscale y\nset format y '10^{%L}'\n";
  int arrow = 1;
  for (const Marker& m : p.markers) {
    const std::string from = m.vertical ? "first " + std::to_string(m.at) + ", graph 0" : "graph 0, first " + std::to_string(m.at);
    const std::string to = m.vertical ? "first " + std::to_string(m.at) + ", graph 1" : "graph 1, first " + std::to_string(m.at);
    gp << "set arrow " << arrow++ << " from " << from << " to " << to << " nohead lc rgb '#555555' dt " << (m.dashed ? 2 : 1) << '\n';
    if (!m.label.empty())
      gp << "set label " << quoted(m.label) << " at "
         << (m.vertical ? "first " + std::to_string(m.at) + ", graph " + std::to_string(m.label_height) + " rotate by 90 right offset " +
                              (m.label_right ? "1.2" : "-0.8") + ",0"
                        : "graph 0.02, first " + std::to_string(m.at) + " offset 0,0.6")
         << " font ',9' tc rgb '#333333'\n";
  }
  gp << "plot ";
  for (std::size_t k = 0; k < p.series.size(); ++k)
    gp << (k ? ", " : "") << quoted(data) << " index " << k << " using 1:2 with "
       << (p.series[k].points ? "points pt 7 ps 0.8" : "lines lw 2") << " title " << quoted(p.series[k].title);
  gp << '\n';
  return gp.str();
}

/// Everything \p fd gives until its end.
std::string read_all(int fd) {
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace

// gnuplot never opens the figure file: it prints the figure, which is written through Output.
void render(const std::string& gp, const std::string& path) {
  int in[2], out[2], err[2];
  if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0)
    throw OutputError(path + ": cannot run gnuplot: " + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err[1], STDERR_FILENO);
  char name[] = "gnuplot";
  char* argv[] = {name, nullptr};
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  for (int fd : {in[0], out[1], err[1]}) ::close(fd);
  if (spawned != 0) {
    for (int fd : {in[1], out[0], err[0]}) ::close(fd);
    throw OutputError(path + ": cannot run gnuplot (install Debian's gnuplot-nox): " + std::strerror(spawned));
  }
  // The script is a few kilobytes (below a pipe's buffer) and gnuplot draws only at its end, so writing it
  // whole before reading cannot block; a gnuplot that ends early shows in its status below.
  const sighandler_t previous = std::signal(SIGPIPE, SIG_IGN);
  for (std::string_view rest = gp; !rest.empty();) {
    const ssize_t n = ::write(in[1], rest.data(), rest.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    rest.remove_prefix(static_cast<std::size_t>(n));
  }
  ::close(in[1]);
  std::signal(SIGPIPE, previous);
  const std::string figure = read_all(out[0]), messages = read_all(err[0]);
  ::close(out[0]);
  ::close(err[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || figure.empty())
    throw OutputError(path + ": gnuplot failed: " + messages.substr(0, messages.find('\n')));
  write_output(path, figure);
}

void draw(const std::string& dir, const std::string& stem, const Plot& p) {
  std::ostringstream dat;
  dat.precision(17);
  for (const Series& s : p.series) {
    dat << "# " << s.title << '\n';
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) dat << s.x[i] << ' ' << s.y[i] << '\n';
    dat << "\n\n";
  }
  const std::string base = dir + "/" + stem;
  write_output(base + ".dat", dat.str());
  const std::string png = "pngcairo size 900,560 font 'DejaVu Sans,11'", svg = "svg size 900,560 dynamic font 'DejaVu Sans,11'";
  // The script beside the figures redraws both by hand (`cd DIR && gnuplot STEM.gp`).
  write_output(base + ".gp", script(stem + ".dat", p, png, quoted(stem + ".png")) + script(stem + ".dat", p, svg, quoted(stem + ".svg")));
  render(script(base + ".dat", p, png, ""), base + ".png");
  render(script(base + ".dat", p, svg, ""), base + ".svg");
}

}  // namespace superball::cli
