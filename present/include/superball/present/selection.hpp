#pragma once
/// \file selection.hpp
/// A pattern of M, an obstacle, an asymptotic regime and evolution cases
/// chosen by name, as the commands that work on derivations (`derive`,
/// `verify`, `explore`) and the Python module take them.  Shared by the two
/// fronts.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "superball/numeric/memory.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/estimate.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// The most correction orders kept beyond the dominant balance (SelectionOptions::order).
inline constexpr int max_order = 20;

/// The number of bodies of a selection that gives none (SelectionOptions::bodies).
inline constexpr int default_bodies = 4;
/// The pairs with a diagonal K of a selection that gives none (SelectionOptions::pairs).
inline constexpr const char* default_pairs = "all";

/// The choice of a pattern, an obstacle, a regime and cases (the command's
/// --bodies, --case, … and Python's keywords of the same names).  The text
/// fields are read against the number of bodies by the library when the
/// choice is resolved: pairs by symbolic::Pattern::parse_pairs(), coupling by
/// Pattern::parse_couplings(), scaling by Scaling::parse(), closed by
/// ContactSet::parse(), case_name by the paper's vocabulary.  An option not
/// given is empty (nullopt, "" or no alpha), so that a scene's pattern can
/// refuse one given with it.
struct SelectionOptions {
  std::optional<int> bodies;     ///< n; not given: default_bodies (with scene: the scene's)
  int order = 0;                 ///< correction orders kept, 0 to max_order
  ///@{
  /// The chosen case.
  std::string case_name, closed;  ///< the paper's case name (n = 4), or the closed contacts ("2-3,3-4", "none")
  ///@}
  std::vector<int> alphas;       ///< the paper's couplings α_k in play (n = 4; parse_alphas()); empty: none
  std::string coupling;          ///< couplings of pairs ("1-2/1-4,2-3/2-4", "near2"); empty: none
  std::optional<std::string> pairs;  ///< the pairs with a diagonal K; not given: default_pairs
  std::string scene;             ///< a scene file whose declared entries of M are the pattern; empty: none
  std::string scaling;           ///< orders in ε ("m1=1,K14=-1"); empty: the default regime
  symbolic::Obstacle obstacle = symbolic::Obstacle::Infinite;  ///< parse_obstacle()
  bool all = false;              ///< every case

  /// Throws std::invalid_argument("SelectionOptions::check(): ...") naming
  /// the option when order is not from 0 to max_order, when more than one
  /// of case_name, closed and all is given, or when scene is given with
  /// bodies, alphas, coupling or pairs (the scene's pattern is the whole
  /// pattern).  resolve() calls it.
  void check() const;
};

/// The rule of the commands that need cases (derive, verify; explore
/// unless \p or_all_patterns): throws std::invalid_argument("require_case():
/// give a case: case, closed or all[, or all_patterns]") when \p o chooses none.
void require_case(const SelectionOptions& o, bool or_all_patterns = false);

/// The rule of explore's all_patterns, which chooses the patterns and cases
/// itself: throws std::invalid_argument("check_all_patterns(): ...") when
/// \p o names a case, closed contacts, all, alphas, a coupling or a scene.
void check_all_patterns(const SelectionOptions& o);

/// "infinite" or "finite" as symbolic::Obstacle; throws
/// std::invalid_argument("parse_obstacle(): obstacle must be infinite or finite, got 'TEXT'").
symbolic::Obstacle parse_obstacle(const std::string& text);

/// A pattern, obstacle and regime resolved, with the chosen cases.
struct Selection {
  /// The pattern, obstacle and regime, ready to derive.
  std::unique_ptr<symbolic::Deriver> deriver;
  std::vector<ContactSet> cases;  ///< --case / --closed: one; --all: every case in mask order; none given: empty
};

/// Resolve \p o; throws std::invalid_argument naming the option that is wrong.
Selection resolve(const SelectionOptions& o);

/// What `superball derive` writes (--format).
enum class DeriveFormat { Text, Latex, Json };

/// "text", "latex" or "json"; throws std::invalid_argument
/// ("parse_derive_format(): format must be text, latex or json, got 'TEXT'").
DeriveFormat parse_derive_format(const std::string& text);

/// How the derivation of a selection's cases will run (the command's and
/// the Python module's derive).
struct DerivePlan {
  symbolic::Estimate estimate;  ///< symbolic::estimate_derivation()
  int workers = 1;              ///< worker processes: at most the jobs asked and the cases, as many as the memory holds
  std::string text;             ///< "deriving every case of 8 bodies, a pattern of width 3: about 4 min 16 s on one core, 2 workers, about 2.7 GB each (22.7 GB available)"
};

/// The plan for \p s over at most \p jobs worker processes (0: one per
/// core; numeric::check_threads(jobs, "jobs") refuses the others) with
/// \p available memory (numeric::available_memory()).  Throws std::invalid_argument
/// ("derive(): deriving every case of 9 bodies, a pattern of width 3 holds
/// about 24 GB (one process, …); this machine has 22.7 GB available
/// (MemAvailable); derive fewer bodies or a narrower pattern") when even one
/// process does not fit: the only size refused.
DerivePlan plan_derivation(const Selection& s, int jobs, const numeric::Memory& available);

/// Parse "1,6" into {1, 6}: comma-separated indices 1..7; throws
/// std::invalid_argument("parse_alphas(): alphas: ...") on an empty item, a
/// word or an index out of 1..7.
std::vector<int> parse_alphas(const std::string& text);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
