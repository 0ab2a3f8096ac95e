#pragma once
/// \file symbols.hpp
/// The GiNaC symbols of one pattern and their names in the three notations
/// the tool writes: ASCII (JSON, any CAS: m1, K12, K1_10, alpha2, c_12_14, a),
/// text (m₁, K₁₂, α₂, c₁₂,₁₄) and LaTeX (`m_{1}`, `K_{12}`, `\alpha_{2}`, `c_{12,14}`).
///
/// Masses, diagonal coefficients K and the fall speed a are GiNaC
/// possymbols (positive); couplings are plain symbols (any sign, real).

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "superball/symbolic/pattern.hpp"
#include "superball/symbolic/export.hpp"
SUPERBALL_SYMBOLIC_API_BEGIN

namespace superball::symbolic {

/// The notation of a printed name or expression: plain ASCII (JSON and any
/// CAS; GiNaC's default printing), text with Unicode subscripts, or LaTeX.
enum class Style { Ascii, Text, Latex };

/// What a symbol stands for.
enum class SymbolKind { Mass, Diagonal, Coupling, FallSpeed };

/// One symbol of a pattern and its names.
struct SymbolInfo {
  /// What the symbol stands for: a mass, a diagonal K, a coupling, the fall speed.
  SymbolKind kind = SymbolKind::Mass;
  GiNaC::ex symbol;       ///< the GiNaC symbol
  int body = 0;           ///< Mass: the body (1-based)
  ///@{
  /// Diagonal: first == second; Coupling: the two pairs.
  Pair first, second;     ///< Diagonal: first == second; Coupling: the two pairs
  ///@}
  int alpha = 0;          ///< Coupling, n = 4: the paper's k of α_k, else 0
  int rank = 0;           ///< printing order: masses, K's, couplings, a
  ///@{
  /// The symbol's name in ASCII (m1, K12, alpha2, a), in text (m₁, K₁₂, α₂) and in LaTeX.
  std::string ascii, text, latex;
  ///@}
  /// The name in \p style.
  const std::string& name(Style style) const { return style == Style::Ascii ? ascii : style == Style::Text ? text : latex; }
};

/// One term c · Π x_k^e_k of an expanded polynomial, x_k the k-th symbol of
/// Symbols::all().
struct Monomial {
  GiNaC::numeric coefficient;              ///< rational, non-zero
  std::vector<std::pair<int, int>> powers;  ///< (index k in Symbols::all(), exponent > 0)
};

/// The symbols of a pattern: m_1..m_n (m_n only for a finite obstacle),
/// K_p for the declared diagonal entries, one symbol per declared coupling
/// and the fall speed a.
class Symbols {
 public:
  /// Create the symbols of \p pattern (checked by Pattern::check()).
  Symbols(const Pattern& pattern, Obstacle obstacle);

  /// The pattern the symbols were made for (checked and sorted).
  const Pattern& pattern() const { return pattern_; }
  /// Fixed obstacle (no m_n) or finite mass m_n.
  Obstacle obstacle() const { return obstacle_; }
  /// n, the number of bodies.
  int bodies() const { return pattern_.bodies; }

  /// m_i (1-based).  Throws std::invalid_argument("Symbols::mass(): ...")
  /// for the fixed obstacle (m_n = ∞ has no symbol) or a body out of range.
  const GiNaC::ex& mass(int body) const;
  /// K_p; throws std::invalid_argument("Symbols::diagonal(): ...") if not declared.
  const GiNaC::ex& diagonal(const Pair& p) const;
  /// The coupling of p and q (either order); throws std::invalid_argument("Symbols::coupling(): ...") if not declared.
  const GiNaC::ex& coupling(const Pair& p, const Pair& q) const;
  /// The entry M_pq: K_p when p == q, the coupling otherwise, 0 when not declared (never a symbol).
  GiNaC::ex entry(const Pair& p, const Pair& q) const;
  /// The fall speed a (bodies 1..n−1 fall at −a, the bottom body is at rest).
  const GiNaC::ex& fall_speed() const { return a_; }

  /// Every symbol, in printing order.
  const std::vector<SymbolInfo>& all() const { return all_; }
  /// The record of symbol \p s; throws std::invalid_argument("Symbols::info(): ...") for a foreign symbol.
  const SymbolInfo& info(const GiNaC::ex& s) const;
  /// The record of symbol \p s, or nullptr when it is not a symbol of this pattern.
  const SymbolInfo* find(const GiNaC::ex& s) const;
  /// Whether \p s is one of the couplings.
  bool is_coupling(const GiNaC::ex& s) const;
  /// The symbol whose ASCII name is \p name; throws std::invalid_argument("Symbols::by_name(): ...").
  const GiNaC::ex& by_name(const std::string& name) const;
  /// Name → symbol table, for GiNaC::parser.
  GiNaC::symtab table() const;
  /// The terms of the polynomial \p p (expanded first) in these symbols, for
  /// code that evaluates it without GiNaC.  Throws std::invalid_argument(
  /// "Symbols::monomials(): ...") when p is not a polynomial with rational
  /// coefficients in these symbols.
  std::vector<Monomial> monomials(const GiNaC::ex& p) const;

 private:
  void add(SymbolInfo info);

  Pattern pattern_;
  Obstacle obstacle_;
  GiNaC::ex a_;
  std::vector<SymbolInfo> all_;
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> index_;
};

/// "12" for the pair (1, 2), "1_10" when a body number has two digits or more.
std::string pair_code(const Pair& p);

}  // namespace superball::symbolic

SUPERBALL_SYMBOLIC_API_END
