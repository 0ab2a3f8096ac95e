#pragma once
/// \file memory.hpp
/// How much memory a computation may still take, read in one place, so that
/// a command that would hold more refuses with one line before it starts
/// instead of ending in std::bad_alloc.

#include <cstdint>
#include <string>
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// Memory that may still be allocated, and what limits it.
struct Memory {
  double bytes = 0;    ///< bytes that may still be allocated
  std::string source;  ///< what sets that number, for messages: "MemAvailable", "ulimit -v", "ulimit -d"
};

/// The memory this process may still allocate: the smallest of the
/// machine's MemAvailable (/proc/meminfo) and what the address-space and
/// data limits (getrlimit(RLIMIT_AS), `ulimit -v`; RLIMIT_DATA, `ulimit -d`)
/// leave above what the process maps already (VmSize, VmData of
/// /proc/self/status).  Where none of these can be read: unlimited (an
/// infinite number of bytes, source "unknown").
Memory available_memory();

/// \p bytes for people, with one decimal: "512 B", "9.6 GB", "11.0 MB" (powers of 1000).
std::string bytes_text(double bytes);

/// Throws std::invalid_argument("FUNCTION: WHAT holds about B (PER); this
/// machine has A available (SOURCE); ADVICE") when \p bytes exceeds
/// \p available.bytes, e.g. "map(): a 10000 x 10000 grid holds about 17 GB
/// (168 bytes per point); this machine has 5.1 GB available (MemAvailable);
/// use a coarser grid".  \p per says how the estimate is made.
void check_memory(const std::string& function, const std::string& what, double bytes, const std::string& per, const Memory& available,
                  const std::string& advice);

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
