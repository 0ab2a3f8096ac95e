#pragma once
/// \file selection.hpp
/// A pattern of M, an obstacle, an asymptotic regime and evolution cases
/// chosen by name, as the commands that work on derivations (`derive`,
/// `verify`, `explore`) and the Python module take them.  Shared by the two
/// fronts; not installed.

#include <memory>
#include <string>
#include <vector>

#include "superball/symbolic/derivation.hpp"

namespace superball::present {

/// The raw option values (the command line's --bodies, --case, … with the same names).
struct SelectionOptions {
  int bodies = 4, order = 0;
  std::string case_name, closed, alphas, coupling, pairs = "all", scene, obstacle = "infinite", scaling;
  bool all = false, no_limit = false;
};

/// A pattern, obstacle and regime resolved, with the chosen cases.
struct Selection {
  std::unique_ptr<symbolic::Deriver> deriver;
  std::vector<ContactSet> cases;  ///< --case / --closed: one; --all: every case in mask order; none given: empty
};

/// Resolve \p o; throws std::invalid_argument naming the option that is wrong,
/// or, unless --no-limit, when the pattern has more bodies than the
/// derivation handles in about 10 s (detail::body_limit()).
Selection resolve(const SelectionOptions& o);

namespace detail {

/// The largest n whose derivation was measured to take about 10 s at most
/// (docs/SYMBOLIC.md, "Limits"), for a pattern of width \p width (the bodies
/// its widest entry joins are that far apart, plus one with couplings), for
/// one case or for every case (\p all_cases).
int body_limit(int width, bool all_cases);

}  // namespace detail

/// Parse "1,6" into {1, 6}; throws std::invalid_argument naming --alphas.
std::vector<int> parse_alphas(const std::string& text);

}  // namespace superball::present
