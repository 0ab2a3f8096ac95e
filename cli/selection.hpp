#pragma once
/// \file selection.hpp
/// The options that choose a pattern of M, an obstacle, an asymptotic regime
/// and evolution cases, shared by the commands that work on derivations
/// (`derive`, `verify`, `explore`).

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

#include "superball/symbolic/derivation.hpp"

namespace superball::cli {

/// The raw option values.
struct SelectionOptions {
  int bodies = 4, order = 0;
  std::string case_name, closed, alphas, coupling, pairs = "all", scene, obstacle = "infinite", scaling;
  bool all = false, no_limit = false;
};

/// Register --bodies, --case/--closed/--all (one of them required when
/// \p require_case), --alphas, --coupling, --pairs, --scene, --obstacle,
/// --scaling, --order and --no-limit on \p cmd, writing into \p o.
void add_selection_options(CLI::App* cmd, SelectionOptions& o, bool require_case = true);

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

}  // namespace superball::cli
