#include "gnuplot.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "commands.hpp"

namespace superball::cli {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

std::string script(const std::string& stem, const Plot& p, const std::string& terminal, const std::string& ext) {
  std::ostringstream gp;
  gp << "set terminal " << terminal << "\nset output " << quoted(stem + "." + ext) << '\n'
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
    gp << (k ? ", " : "") << quoted(stem + ".dat") << " index " << k << " using 1:2 with "
       << (p.series[k].points ? "points pt 7 ps 0.8" : "lines lw 2") << " title " << quoted(p.series[k].title);
  gp << '\n';
  return gp.str();
}

}  // namespace

void draw(const std::string& dir, const std::string& stem, const Plot& p) {
  std::ostringstream dat;
  dat.precision(17);
  for (const Series& s : p.series) {
    dat << "# " << s.title << '\n';
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) dat << s.x[i] << ' ' << s.y[i] << '\n';
    dat << "\n\n";
  }
  write_file_atomically(dir + "/" + stem + ".dat", dat.str());
  const std::string gp = script(stem, p, "pngcairo size 900,560 font 'DejaVu Sans,11'", "png") +
                         script(stem, p, "svg size 900,560 dynamic font 'DejaVu Sans,11'", "svg");
  write_file_atomically(dir + "/" + stem + ".gp", gp);
  const std::string command = "cd " + quoted(dir) + " && gnuplot " + quoted(stem + ".gp") + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("draw(): cannot run gnuplot");
  std::string output;
  char buf[256];
  while (std::fgets(buf, sizeof buf, pipe)) output += buf;
  const int status = ::pclose(pipe);
  if (status != 0)
    throw std::runtime_error("draw(): gnuplot failed on " + dir + "/" + stem + ".gp (install Debian's gnuplot-nox): " +
                             output.substr(0, output.find('\n')));
}

}  // namespace superball::cli
