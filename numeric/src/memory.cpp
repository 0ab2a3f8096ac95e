#include "superball/numeric/memory.hpp"

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace superball::numeric {
namespace {

/// The value in kB of the line "NAME: value kB" of a /proc file, in bytes; -1 when absent.
double proc_field(const char* file, const std::string& name) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(name + ":", 0) == 0) {
      std::istringstream words(line.substr(name.size() + 1));
      double kb = -1;
      if (words >> kb) return kb * 1024;
    }
  return -1;
}

/// What the limit \p resource leaves above \p used bytes, into \p m when it is less.
void limit(Memory& m, int resource, double used, const char* source) {
  struct rlimit r {};
  if (::getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY || used < 0) return;
  const double left = static_cast<double>(r.rlim_cur) > used ? static_cast<double>(r.rlim_cur) - used : 0;
  if (left < m.bytes) m = {left, source};
}

}  // namespace

Memory available_memory() {
  Memory m{std::numeric_limits<double>::infinity(), "unknown"};
  const double available = proc_field("/proc/meminfo", "MemAvailable");
  if (available >= 0) m = {available, "MemAvailable"};
  limit(m, RLIMIT_AS, proc_field("/proc/self/status", "VmSize"), "ulimit -v");
  limit(m, RLIMIT_DATA, proc_field("/proc/self/status", "VmData"), "ulimit -d");
  return m;
}

std::string bytes_text(double bytes) {
  static const char* const units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000 && u + 1 < static_cast<int>(sizeof units / sizeof units[0])) bytes /= 1000, ++u;
  char text[64];
  std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return text;
}

void check_memory(const std::string& function, const std::string& what, double bytes, const std::string& per, const Memory& available,
                  const std::string& advice) {
  if (bytes <= available.bytes) return;
  throw std::invalid_argument(function + ": " + what + " holds about " + bytes_text(bytes) + " (" + per + "); this machine has " +
                              bytes_text(available.bytes) + " available (" + available.source + "); " + advice);
}

}  // namespace superball::numeric
