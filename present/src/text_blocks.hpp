#pragma once
/// \file text_blocks.hpp
/// What the reports of many points (a map's grid, a sweep's rows) share:
/// numbers and CSV fields as text, the exact values of a grid in decimal,
/// and the formatting of rows on threads, in blocks given in order to a
/// TextSink.  Internal to superball_present.

#include <algorithm>
#include <cmath>
#include <future>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "superball/numeric/parallel.hpp"
#include "superball/numeric/scalar.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/present/text_sink.hpp"

namespace superball::present::detail {

/// \p x in decimal to \p digits significant digits (numeric::to_decimal()).
inline std::string decimal(const cln::cl_RA& x, int digits = 17) { return numeric::to_decimal(x, digits); }

/// A CSV field, quoted (RFC 4180) when it holds a comma or a quote: the case
/// of a scene of other than 4 bodies is its closed contacts, "{1-2,2-3}".
inline std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// \p x to \p digits significant digits, "nan" for a NaN, appended to \p out.
inline void append_number(std::string& out, double x, int digits = 17) {
  if (std::isnan(x))
    out += "nan";
  else
    numeric::append_to(out, x, digits);
}
/// append_number() as a string of its own.
inline std::string number(double x, int digits = 17) {
  std::string out;
  append_number(out, x, digits);
  return out;
}

/// The text of \p key in \p cache (a few entries, searched in order), made by make() on first use.
template <class Key, class Make>
const std::string& cached(std::vector<std::pair<Key, std::string>>& cache, const Key& key, const Make& make) {
  for (const auto& [k, text] : cache)
    if (k == key) return text;
  cache.emplace_back(key, make());
  return cache.back().second;
}

/// decimal(numeric::Grid(from, to, steps)(k), 10) for k = first … first + count − 1,
/// on \p threads threads, 64 values a task: each thread computes from its own
/// copies of the ends, read from their texts (made here): CLN's numbers are
/// not shared between threads.
inline std::vector<std::string> decimals(const cln::cl_RA& from, const cln::cl_RA& to, int steps, int first, int count, int threads) {
  constexpr int per_task = 64;
  const std::string low = numeric::to_string(from), high = numeric::to_string(to);
  struct Ends {
    cln::cl_RA from, to;
  };
  const auto parts = numeric::parallel_map(
      static_cast<std::size_t>((count + per_task - 1) / per_task), threads,
      [&] { return Ends{numeric::parse_rational(low), numeric::parse_rational(high)}; },
      [&](const Ends& ends, std::size_t t) {
        const int k0 = first + static_cast<int>(t) * per_task, k1 = std::min(first + count, k0 + per_task);
        std::vector<std::string> texts;
        for (const cln::cl_RA& v : numeric::linspace(ends.from, ends.to, steps, k0, k1 - k0)) texts.push_back(decimal(v, 10));
        return texts;
      });
  std::vector<std::string> all;
  all.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

/// The points a task of in_blocks() formats: enough that a task's overhead
/// is small beside them, few enough that the threads share the last ones
/// evenly.
constexpr std::size_t output_block = 4096;

/// The text of \p count points made by block(state, out, from, to) (the
/// points from … to − 1, appended to the std::string out) on \p threads
/// threads, \p per_task points a task, and given to \p sink in order, a
/// window of tasks at a time (the memory held is that of a window, not of
/// the whole text).  Each thread has its own State, made empty: block() must
/// touch no CLN object.  With several threads, a window is given to \p sink
/// by a thread of its own while the next is formatted; a window's texts
/// are kept for the window after next, so that their storage, once grown,
/// is neither copied nor given back and faulted in again.
template <class State, class Block>
void in_blocks(std::size_t count, int threads, const Block& block, const TextSink& sink, std::size_t per_task = output_block) {
  const std::size_t tasks = (count + per_task - 1) / per_task;
  const int n = numeric::thread_count(threads);
  const std::size_t window = 8 * static_cast<std::size_t>(n);
  std::vector<std::string> texts[2];
  std::future<void> writing;  // the sink's work on the window before
  for (std::size_t first = 0, w = 0; first < tasks; first += window, ++w) {
    const std::size_t size = std::min(window, tasks - first);
    std::vector<std::string>& mine = texts[w % 2];
    mine.resize(std::max(mine.size(), size));
    numeric::parallel_map(size, threads, [] { return State{}; }, [&](State& state, std::size_t t) {
      const std::size_t from = (first + t) * per_task;
      // Made in a string of this thread's stack, its storage the slot's: the
      // slots' own strings lie side by side, and appending to them from two
      // threads would share their cache lines.
      std::string out;
      out.swap(mine[t]);
      out.clear();
      block(state, out, from, std::min(count, from + per_task));
      out.swap(mine[t]);
      return true;
    });
    auto write = [&sink, &mine, size] {
      for (std::size_t t = 0; t < size; ++t) sink(mine[t]);
    };
    if (writing.valid()) writing.get();  // the window before written: its texts are free for the next window
    if (n <= 1) {
      write();
      continue;
    }
    try {
      writing = std::async(std::launch::async, write);
    } catch (const std::system_error&) {  // no thread to be had: written here
      write();
    }
  }
  if (writing.valid()) writing.get();
}

}  // namespace superball::present::detail
