#pragma once
/// \file selection.hpp
/// A pattern of M, an obstacle, an asymptotic regime and evolution cases
/// chosen by name, as the commands that work on derivations (`derive`,
/// `verify`, `explore`) and the Python module take them.  Shared by the two
/// fronts; not installed.

#include <memory>
#include <string>
#include <vector>

#include "superball/numeric/memory.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/estimate.hpp"

namespace superball::present {

/// The raw option values (the command line's --bodies, --case, … with the same names).
struct SelectionOptions {
  int bodies = 4, order = 0;
  std::string case_name, closed, alphas, coupling, pairs = "all", scene, obstacle = "infinite", scaling;
  bool all = false;
};

/// A pattern, obstacle and regime resolved, with the chosen cases.
struct Selection {
  std::unique_ptr<symbolic::Deriver> deriver;
  std::vector<ContactSet> cases;  ///< --case / --closed: one; --all: every case in mask order; none given: empty
};

/// Resolve \p o; throws std::invalid_argument naming the option that is wrong.
Selection resolve(const SelectionOptions& o);

/// How the derivation of a selection's cases will run (the command's and
/// the Python module's derive).
struct DerivePlan {
  symbolic::Estimate estimate;  ///< symbolic::estimate_derivation()
  int workers = 1;              ///< worker processes: at most the jobs asked and the cases, as many as the memory holds
  std::string text;             ///< "deriving every case of 8 bodies, a pattern of width 3: about 4 min 16 s on one core, 2 workers, about 2.7 GB each (22.7 GB available)"
};

/// The plan for \p s over at most \p jobs worker processes with \p available
/// memory (numeric::available_memory()).  Throws std::invalid_argument
/// ("derive(): deriving every case of 9 bodies, a pattern of width 3 holds
/// about 24 GB (one process, …); this machine has 22.7 GB available
/// (MemAvailable); derive fewer bodies or a narrower pattern") when even one
/// process does not fit: the only size refused.
DerivePlan plan_derivation(const Selection& s, int jobs, const numeric::Memory& available);

/// Parse "1,6" into {1, 6}; throws std::invalid_argument naming --alphas.
std::vector<int> parse_alphas(const std::string& text);

}  // namespace superball::present
