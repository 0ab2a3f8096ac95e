#pragma once
/// \file explore.hpp
/// Is the superball reachable for a pattern of M in an evolution case (paper
/// §4)?  A search for a witness guided by the derived conditions, confirmed
/// by an exact solve, and — when none is found — a search for a proof that
/// the conditions cannot hold together (the clash).
///
/// The search.  The obstacle is fixed (m₄ = ∞) and a = 1 (the velocities
/// after the collision are linear in a, so U₁⁺/a does not depend on it).
/// Every other coordinate lives in a box: each mass and K in [low, high]
/// (ExploreOptions::box_low, box_high) in log scale, each coupling a
/// fraction t ∈ [−1, 1] of √(K_p K_q) so its 2×2 minor of M holds.  The case
/// is actual where its derived exact conditions hold (evolution: each open
/// contact opens; contact: each closed contact's reaction is <= 0) and M is
/// positive semi-definite (the pattern's minors).  The search maximises
/// U₁⁺/a, the derived velocity formula of the case, over that set: a penalty
/// on the violated conditions (each value numerator/denominator divided by
/// the sum of the absolute values of its numerator's terms, so it lies in
/// [−1, 1]) makes every infeasible point worse than every feasible one;
/// Nelder–Mead in the box coordinates from several starts (points of the
/// paper's regime, RegimeSampler at ε = 1/100, and uniform box points).  The
/// best points are rounded to nearby rationals and confirmed by an exact
/// solve (CollisionSolver<cl_RA>::compute, the case not imposed): the case
/// must be the actual evolution; the superball is reached when U₁⁺ > a.
/// The result is "the largest U₁⁺/a found in the box": in the paper's
/// regime U₁⁺/a is unbounded (§4.1 gets a/(2ε)), so the number says more
/// about the box than about the pattern.  Deterministic given the seed.
///
/// The proof.  If the case's conditions Nᵢ > 0 (or >= 0; denominators of
/// proved sign cleared) and the superball condition S > 0 are weighted by
/// wᵢ ∈ {0, 1, 2} and −Σ wᵢNᵢ = Q + R with every term of R certainly
/// nonnegative (symbolic::certainly_nonnegative) and Q >= 0 wherever M ⪰ 0 —
/// Q = t·xᵀMx with x ∈ {−1, 0, 1} on the coupled pairs and t ∈ {0, 1, 2}, or
/// Q = Σ μ_c·(K_p + K_q ± 2c) over the couplings c of pairs p, q, with μ_c
/// a polynomial of certain sign chosen to cancel the terms linear in c
/// (a 2×2 minor's quadratic form times a multiplier) — then Σ wᵢNᵢ <= 0: the
/// weighted conditions cannot hold together when one of them is strict.
/// When no such weights exist, the weights become polynomial multipliers
/// (nonnegative combinations of 1 and single masses and K's) on the
/// conditions and on the 2×2 minor forms, found by a linear programme (the
/// coefficients of −Σ must be >= 0, and 0 on odd powers of couplings),
/// rounded to fractions and checked exactly.
/// Without the superball condition that proves the case never actual.  The
/// same search on the leading-order (asymptotic) forms says whether the
/// paper's asymptotic conditions clash too.
///
/// The reports of a result (text, JSON, the table, witness files) are
/// present/explore.hpp's.

#include <cln/rational.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/verify/export.hpp"
SUPERBALL_VERIFY_API_BEGIN

namespace superball::verify {

/// How explore_case() searches.
struct ExploreOptions {
  std::uint64_t seed = 1;  ///< of the starting points (the search is deterministic given it)
  int starts = 24;         ///< local searches: half from the paper's regime, half uniform in the box
  int evaluations = 1000;  ///< objective evaluations per local search (Nelder–Mead)
  double box_low = 1e-3;   ///< every mass and K in [box_low, box_high]
  /// The upper end of the box (see box_low).
  double box_high = 1e3;
  /// Called with (steps done, steps planned) as explore_case() goes; may be
  /// empty.  A step is an objective evaluation of the local searches, each
  /// search counted at its full budget once it ends, and one step more for
  /// the exact confirmation and the proofs: planned = starts × evaluations
  /// + 1.  It is called at least every explore_progress_evaluations
  /// evaluations (the confirmation's steps inward included, then with done
  /// unchanged), between the confirmation and each proof, and with (planned,
  /// planned) at the end.  It may throw to stop the exploration (Ctrl-C): the
  /// exception leaves explore_case() as it is.  The result does not depend
  /// on it.  explore_all_patterns() counts the steps of every cell.
  std::function<void(long long, long long)> progress;

  /// Throws std::invalid_argument("ExploreOptions::check(): ...") naming
  /// the option unless starts is from 1 to max_starts, evaluations from 10
  /// to max_evaluations and 0 < box_low < box_high with both ends normal
  /// doubles (box_low >= 2.2250738585072014e-308, box_high finite): any such
  /// box is searched; a point where a condition's terms overflow or
  /// underflow in double counts as infeasible, and every witness is
  /// confirmed exactly.
  void check() const;
};

/// ExploreOptions::progress is called at least this often (objective evaluations).
inline constexpr int explore_progress_evaluations = 1024;

/// The most local searches per case (ExploreOptions::starts).
inline constexpr int max_starts = 100000;
/// The most objective evaluations per local search (ExploreOptions::evaluations).
inline constexpr int max_evaluations = 10000000;

/// "1e-3:1e3" into (box_low, box_high): two decimal numbers; throws
/// std::invalid_argument("box: 'TEXT' is not LOW:HIGH …").  Their rule is
/// ExploreOptions::check()'s.
std::pair<double, double> parse_box(const std::string& text);

/// The box of \p options in words (for reports).
std::string describe_box(const ExploreOptions& options);

/// What the exploration of one case concluded.
enum class Reach {
  Yes,             ///< a witness: the case actual and U₁⁺ > a, confirmed exactly
  Impossible,      ///< proved: the case's conditions and U₁⁺ > a clash for every M ⪰ 0
  CaseImpossible,  ///< proved: the case itself is never the actual evolution
  NotFound         ///< neither a witness nor a proof
};
/// The reach in words: "yes", "no (proved)", "case impossible", "not found".
const char* to_string(Reach r);

/// Conditions that cannot hold together, and the identity that shows it.
struct Clash {
  bool asymptotic = false;              ///< the leading-order forms (else the exact ones)
  bool superball = false;               ///< the superball condition is among them
  std::vector<std::string> conditions;  ///< "N1 (weight 1), superball (U₁⁺ > a): −2α₁ > …", one per weighted condition
  std::string identity;                 ///< "−(N1 + …) = Q + (…), Q = …" and why that is <= 0
};

/// The search's effort and what it met.
struct ExploreStats {
  int starts = 0;            ///< local searches run
  int evaluations = 0;       ///< objective evaluations (double)
  int feasible_starts = 0;   ///< local searches that ended with the case's conditions holding (double)
  int superball_starts = 0;  ///< … and U₁⁺ > a
  int exact_solves = 0;      ///< rational points solved exactly
  int inward_steps = 0;      ///< rounded points the exact solve rejected, retried further inside
  double best_double = 0;    ///< largest U₁⁺/a in double over the feasible local results (0 if none)
};

/// The exploration of one pattern in one case.
struct ExploreResult {
  std::string pattern;        ///< the couplings in play, e.g. "α₁, α₆" ("no coupling" when none)
  std::string pattern_ascii;  ///< the same in ASCII, e.g. "alpha1,alpha6" ("none")
  std::string case_name; ///< the paper's name, or "{2-3,3-4}"
  /// The case explored.
  ContactSet closed;
  /// What the exploration established.
  Reach reach = Reach::NotFound;
  std::string box;       ///< describe_box() of the options used
  /// The seed of the random starts.
  std::uint64_t seed = 0;
  /// The best point confirmed exactly (the case actual there), whether or
  /// not U₁⁺ > a: ASCII name → exact value (a included).
  std::vector<std::pair<std::string, cln::cl_RA>> witness;
  std::optional<Scene> scene;   ///< the witness as a scene (ParameterSpace::scene)
  cln::cl_RA ratio = 0;         ///< U₁⁺/a at the witness, exact
  cln::cl_RA u1 = 0;            ///< U₁⁺ at the witness, exact
  /// What the search did (starts, evaluations, …).
  ExploreStats stats;
  std::optional<Clash> clash;             ///< the exact conditions, when proved
  std::optional<Clash> asymptotic_clash;  ///< the leading-order forms, when they clash (searched when no witness)
};

/// Explore the case \p closed of \p deriver's pattern (fixed obstacle only):
/// search for a witness, confirm it exactly, and without one look for a
/// clash (see the file comment).  Throws std::invalid_argument(
/// "explore_case(): ...") for a finite obstacle, a case of another number of
/// bodies, and ExploreOptions::check()'s for bad options.
ExploreResult explore_case(const symbolic::Deriver& deriver, const ContactSet& closed, const ExploreOptions& options = {});

/// The table of `--all-patterns`: each single α_k (k = 1..7) and the pair
/// {α₁, α₆} of §4.1's remark against every case of n = 4 (fixed obstacle).
struct PatternTable {
  /// The options every cell was explored with (without their progress).
  ExploreOptions options;
  std::vector<std::vector<int>> patterns;       ///< rows
  std::vector<std::string> cases;               ///< columns: the paper's case names
  std::vector<std::vector<ExploreResult>> cells;  ///< [row][column]
};

/// The patterns of the table (rows).
std::vector<std::vector<int>> table_patterns();

/// Explore every pattern of table_patterns() in every case of the paper's
/// vocabulary, with \p options for each cell.
PatternTable explore_all_patterns(const ExploreOptions& options = {});

/// The audit's certificate for one superball condition: −S = t·xᵀMx + (terms
/// >= 0) for some x ∈ {−1, 0, 1}^pairs and t ∈ {1, 2}; then S <= 0 wherever M
/// is positive semi-definite, so "S > 0" is impossible.  Returns the proof
/// in words, or "" when no such x, t exists (at most 10 pairs are tried).
std::string impossibility_certificate(const GiNaC::ex& s_poly, const symbolic::Symbols& sy);

}  // namespace superball::verify

SUPERBALL_VERIFY_API_END
