#pragma once
/// \file format.hpp
/// Writing derivations the way a person writes them: a condition "P > 0"
/// becomes an inequality with positive-coefficient terms on both sides
/// (−α₂ > 2m₁ + K₁₂ + K₁₃), a velocity a fraction with its common factor in
/// front (a(K₁₄ + α₂ − m₁)/(m₁ + …)).  Text uses Unicode subscripts, LaTeX is
/// written here term by term (GiNaC would print relations literally), ASCII
/// is GiNaC's input syntax with the names m1, K12, alpha2, c_12_14, a.  All
/// three styles print the terms in one canonical order (GiNaC's own term
/// order is not reproducible between processes), so every output is the same
/// from run to run.  No global print state changes.  These are the
/// formula-level forms; the reports of a derivation (text, LaTeX document,
/// JSON) are present/derivation.hpp's.

#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/symbols.hpp"
#include "superball/symbolic/export.hpp"
SUPERBALL_SYMBOLIC_API_BEGIN

namespace superball::symbolic {

/// The expanded polynomial \p p in \p style: terms with positive
/// coefficients first, each group in the order masses, K's, couplings, a.
/// ASCII: "2*m1*K12^2 - alpha2", readable by GiNaC::parser.  Throws std::invalid_argument
/// ("format_polynomial(): ...") when \p p is not a polynomial in \p symbols.
std::string format_polynomial(const GiNaC::ex& p, const Symbols& symbols, Style style);

/// The normalised fraction \p f: numerator with its rational content and
/// common monomial in front, "/" or \\frac, parentheses where needed.  In
/// LaTeX a long fraction is "a(…)/(…)" with plain parentheses (TeX may break
/// an inline formula after the + and − inside them, never inside \\left( … \\right)).
std::string format_fraction(const Fraction& f, const Symbols& symbols, Style style);

/// The condition "\p p REL 0" as an inequality (paper §4 style).  Rule:
/// positive-coefficient terms on the left, the others (negated) on the
/// right; when the right side is the shorter one (or as short and holding
/// the couplings) the sides swap and the relation turns (m₁ < K₁₄ + α₂);
/// when no term is positive the couplings stay on the left with their sign
/// (−α₂ > 2m₁ + K₁₂ + K₁₃).  ASCII gives "EXPR > 0" (EXPR as format_polynomial).
std::string format_condition(const GiNaC::ex& p, Relation relation, const Symbols& symbols, Style style);

/// A condition form, with its unproved denominator if it has one
/// ("(N)/(D) > 0 (sign of the denominator not proved)").
std::string format_condition(const ConditionForm& form, Relation relation, const Symbols& symbols, Style style);

/// A polynomial as FACTOR·(REST): its rational content and common
/// monomial, with the sign taken out when every term is negative, and the
/// primitive rest in the canonical order (a long fraction's numerator
/// written over a display's rows: present/derivation.hpp's LaTeX report).
struct CommonFactor {
  bool negative = false;  ///< every term is negative: the polynomial is −FACTOR·(REST)
  std::string factor;     ///< "1" when there is no common factor
  std::string rest;       ///< the terms left, joined with their signs
  bool rest_is_one = false;  ///< the polynomial is ±FACTOR alone
};
/// \p p split into its common factor and the rest, in \p style.
CommonFactor format_common_factor(const GiNaC::ex& p, const Symbols& symbols, Style style);

/// One formula in the three notations.
struct StyledText {
  ///@{
  /// The formula in ASCII (JSON, any CAS), in text (Unicode) and in LaTeX.
  std::string ascii, text, latex;
  ///@}
};

/// format_condition() of \p form in the three styles at once (the terms
/// are walked and sorted once: a condition of thousands of terms costs a
/// third).
StyledText format_condition_styles(const ConditionForm& form, Relation relation, const Symbols& symbols);

/// S₁ (text), S_{1} (LaTeX), S1 (ASCII): the name of the named part \p k of a case.
std::string named_part_name(int k, Style style);

/// The isolated form of a condition, "σ g x REL Q + R/S" (derivation.hpp,
/// Readable): −α₃ > 2m₁ + K₁₃ + K₁₂(2m₂ + K₂₃)/S₁.  ASCII is GiNaC's syntax
/// with the named part as S1.
std::string format_readable(const Readable& r, Relation relation, const Symbols& symbols, Style style);

/// A condition form as a person reads it: its isolated form when it has one,
/// else format_condition().
std::string format_form(const ConditionForm& form, Relation relation, const Symbols& symbols, Style style);

/// V₁ (text), V_{1} (LaTeX), V1 (ASCII): the velocity of free cluster \p c
/// (1 = the top one) in a case's Elimination.
std::string cluster_velocity_name(int c, Style style);

/// The definitions of the elimination \p e (derivation.hpp, Elimination) as
/// (name, value) pairs: for each cluster in elimination order its pivot p,
/// its multipliers l and its eliminated right-hand side y, then the cluster
/// velocities V by back substitution ("p₄ = m₄ + K₂₄ + K₃₄ + K₄₅ − l₄₅²p₅",
/// "l₃₄ = (−K₃₄ − l₃₅l₄₅p₅)/p₄", "V₁ = y₁/p₁").
std::vector<std::pair<std::string, std::string>> elimination_definitions(const Elimination& e, const Symbols& symbols, Style style);

/// The condition "Σ_c ℓ_c V_c + β REL 0" of \p f as an inequality with the
/// negative pieces moved right: "V₄ > V₅", "V₁ > a".
std::string format_eliminated(const EliminatedForm& f, Relation relation, const Symbols& symbols, Style style);

/// The value Σ_c ℓ_c V_c + β of \p f, negated when \p negate (a reaction R = −λ).
std::string format_linear(const EliminatedForm& f, const Symbols& symbols, Style style, bool negate = false);

/// det(ZᵀAZ) of the elimination \p e as the product of its pivots: "p₁p₂p₃" (text),
/// "p_{1} p_{2} p_{3}" (LaTeX), "p1*p2*p3" (ASCII).
std::string format_pivot_product(const Elimination& e, Style style);

/// ε^k in \p style: "ε^-1" (text), "\\varepsilon^{-1}" (LaTeX), "eps^-1" (ASCII).
std::string epsilon_power(const GiNaC::numeric& k, Style style);

/// m₄ (text), m_{4} (LaTeX), m4 (ASCII): the mass of \p body, a symbol or not
/// (the fixed obstacle's m_n = ∞).
std::string mass_name(int body, Style style);
/// U₁⁺ (text), U_{1}^{+} (LaTeX), U1 (ASCII).
std::string velocity_name(int body, Style style);
/// R₂₃ (text), R_{23} (LaTeX), R2_3 (ASCII): the reaction on contact \p contact.
std::string reaction_name(const Pair& contact, Style style);
/// What the condition says in words: "superball (U₁⁺ > a)", "contact 2-3 stays closed (R₂₃ ≤ 0)", …
std::string condition_title(const Condition& c, Style style);

}  // namespace superball::symbolic

SUPERBALL_SYMBOLIC_API_END
