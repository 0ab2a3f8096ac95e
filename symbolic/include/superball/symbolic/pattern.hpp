#pragma once
/// \file pattern.hpp
/// Which entries of the dissipation matrix M are in play (paper §3): the
/// diagonal coefficients K_ij and the couplings between two pairs.  Only
/// declared entries become symbols; an absent entry is exactly zero from the
/// start.

#include <string>
#include <utility>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/symbolic/export.hpp"
SUPERBALL_SYMBOLIC_API_BEGIN

namespace superball::symbolic {

/// A coupling of M between two different pairs, stored with first < second.
using PairCoupling = std::pair<Pair, Pair>;

/// Whether the bottom body is a fixed obstacle (m_n = ∞, its velocity stays
/// u_n = 0) or a body of finite mass m_n.
enum class Obstacle { Infinite, Finite };

/// The shape of M: the number of bodies, the pairs with a diagonal
/// coefficient K_p and the couplings between pairs.  Values are never part
/// of a pattern.
struct Pattern {
  /// The number of bodies n.
  int bodies = 4;
  std::vector<Pair> diagonal;           ///< pairs p with a symbol K_p, sorted
  std::vector<PairCoupling> couplings;  ///< coupled pairs (p, q), p < q, sorted

  /// The paper's matrix M (§3, n = 4): K_ij on the six pairs and the
  /// couplings α_k for k in \p alphas (1..7, vocabulary of cases/paper).
  /// Throws std::invalid_argument("Pattern::paper(): ...") for an unknown k.
  static Pattern paper(const std::vector<int>& alphas);

  /// \p bodies bodies with K_ij on every pair i < j and the given couplings.
  /// Throws std::invalid_argument("Pattern::all_pairs(): ...") for bodies < 2
  /// or a coupling outside the bodies.
  static Pattern all_pairs(int bodies, const std::vector<PairCoupling>& couplings = {});

  /// K_ij on the pairs with j − i <= \p reach ("near" chains), no coupling.
  /// Throws std::invalid_argument("Pattern::near(): ...") for bodies < 2 or reach < 1.
  static Pattern near(int bodies, int reach);

  /// The nearest-and-next-nearest pattern: K_ij for j − i <= 2 and, for
  /// every pair (i, i+2), its couplings with the two nearest pairs inside it,
  /// (i, i+1) and (i+1, i+2).  Throws std::invalid_argument for bodies < 2.
  static Pattern nearest_and_next_nearest(int bodies);

  /// The declared entries of a scene (values ignored).  Throws
  /// std::invalid_argument("Pattern::from_scene(): ...") for a scene with fewer than 2 bodies.
  static Pattern from_scene(const Scene& scene);

  /// Parse a list of pairs "1-2,2-3" or a name: "all", "near" (j − i = 1),
  /// "near2" (j − i <= 2).  Throws std::invalid_argument("Pattern::parse_pairs(): ...").
  static std::vector<Pair> parse_pairs(const std::string& text, int bodies);

  /// Parse couplings "1-2/1-4,1-3/1-4" or "near2" (see nearest_and_next_nearest()).
  /// Throws std::invalid_argument("Pattern::parse_couplings(): ...").
  static std::vector<PairCoupling> parse_couplings(const std::string& text, int bodies);

  /// Sort and check: pairs inside 1..bodies, no duplicates, couplings join
  /// two different pairs.  Throws std::invalid_argument("Pattern::check(): ...").
  void check();

  /// Every pair that appears in the pattern (diagonal or coupled), sorted.
  std::vector<Pair> pairs() const;
  /// Whether K_p is declared.
  bool has_diagonal(const Pair& p) const;
  /// "K: 1-2 1-3 …; couplings: 1-2/1-4 …".
  std::string describe() const;
};

}  // namespace superball::symbolic

SUPERBALL_SYMBOLIC_API_END
