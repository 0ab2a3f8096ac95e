#pragma once
/// \file derivation.hpp
/// One evolution case solved exactly (paper §2–§4, n bodies): velocities
/// after the collision, reactions on the closed contacts and the conditions
/// under which the case is the actual evolution and gives the superball.
///
/// Model (numeric/src/collision/collision.cpp is the same model in numbers).  Bodies
/// 1 (top) … n (bottom); before the collision u_i = −a for i < n and u_n = 0.
/// With K = DᵀMD (D the pair incidence, M the dissipation matrix of §3) and
/// A = diag(m) + K, the equations of motion (5) with the constitutive laws
/// (6)–(12) read, for every body that is not a fixed obstacle,
///     m_i (W_i − u_i) + Σ_j K_ij (W_j + u_j) = λ_i − λ_{i−1},
/// W = U⁺ the velocities after, λ_c = −R_c the reaction on the contact
/// (c, c+1), zero on open contacts.  A case closes some contacts: bodies
/// joined by closed contacts form a cluster with one velocity.  With Z the
/// cluster incidence, the velocities solve the reduced system
///     (ZᵀAZ) V = Zᵀ(diag(m) u − K u),
/// and the reaction on a closed contact is the running sum of the equations
/// of its cluster from the cluster's top body down to the contact.

#include <ginac/ginac.h>

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/symbolic/pattern.hpp"
#include "superball/symbolic/symbols.hpp"
#include "superball/symbolic/export.hpp"
SUPERBALL_SYMBOLIC_API_BEGIN

namespace superball::symbolic {

/// The order in a small ε of each parameter (paper §4: m₁ very small, m₄ and
/// K₁₄ very large): parameter p behaves like ε^order(p); unlisted ones are O(1).
class Scaling {
 public:
  /// The paper's regime: m₁ ~ ε, m_n ~ 1/ε (finite obstacle only), K_1n ~ 1/ε
  /// (when K_1n is declared).
  static Scaling paper(const Symbols& symbols);
  /// Parse "m1=1,m4=-1,K14=-1" (ASCII names, integer or rational orders) or
  /// "none" (everything O(1)).  Throws std::invalid_argument("Scaling::parse(): ...")
  /// for an unknown name or a malformed order.
  static Scaling parse(const std::string& text, const Symbols& symbols);

  /// The order of the symbol \p s (0 when unlisted).
  GiNaC::numeric order(const Symbols& symbols, const GiNaC::ex& s) const;
  /// "m₁ ~ ε, K₁₄ ~ ε^-1" in \p style ("m1 ~ eps^1" in ASCII, "m_{1} \sim \varepsilon^{1}" in LaTeX).
  std::string describe(const Symbols& symbols, Style style) const;
  /// The listed (ASCII name, order) entries.
  const std::map<std::string, GiNaC::numeric>& entries() const { return order_; }

 private:
  std::map<std::string, GiNaC::numeric> order_;
};

/// What a condition says (paper §4).
enum class ConditionKind {
  Superball,  ///< U₁⁺ > a
  Evolution,  ///< an open contact opens: U_i⁺ > U_{i+1}⁺
  Contact,    ///< a closed contact does not interpenetrate: R ≤ 0
  Psd         ///< a principal minor of M is >= 0 (K > 0 for a single pair)
};
/// The kind's name: "superball", "evolution", "contact", "psd".
const char* to_string(ConditionKind kind);

/// The relation of a condition "P REL 0".
enum class Relation { Greater, GreaterEqual };

/// Whether a condition can hold: it depends on the parameters, or it holds
/// (fails) for every admissible parameter (positive masses, K's and a).
enum class Verdict { Depends, Always, Never };
/// The verdict's name: "depends", "always", "never".
const char* to_string(Verdict v);

/// A polynomial of a case named once (S₁, S₂, … in the order the readable
/// forms first use it), so that the conditions can divide by it or group
/// by it ("where S₁ = m₂ + K₁₂ + K₂₃ + K₂₄").
struct NamedPart {
  int index = 1;          ///< the k of S_k
  GiNaC::ex value;        ///< an expanded polynomial
  bool positive = true;   ///< every term positive (even powers of couplings): S_k > 0; else a diagonal entry of ZᵀAZ
};

/// A condition "P REL 0" written the way a researcher writes it.  Two shapes:
///
/// - **isolated** (subject ≠ 0): the coupling x the condition is about on the
///   left.  With P of degree 1 in x,  P = σ g S x − (Q S + R),  σ = ±1, g > 0
///   a positive integer times a monomial in positive symbols, S > 0 a named
///   part with every term positive (or 1), so that, dividing by S,
///       P REL 0  ⟺  σ g x REL Q + R/S      (−α₃ > 2m₁ + K₁₃ + K₁₂(2m₂ + K₂₃)/S₁);
/// - **grouped** (subject = 0): P = Q S + R with S a named part of the case
///   (one already named, or a diagonal entry of ZᵀAZ) and far fewer terms in
///   Q and R than in P, so that
///       P REL 0  ⟺  Q S REL −R             ((m₃ + K₂₃ − K₁₃ − K₃₄)S₁ ≥ K₂₃(2K₁₂ + K₂₃ + 2K₂₄)).
///
/// Q and R come from dividing by S as a polynomial of degree 1 in one of its
/// symbols y with coefficient 1 (R free of y), the y giving the fewest terms.
/// The identity is checked exactly on the expanded polynomials when the form
/// is made (Deriver::derive() throws std::logic_error otherwise).
struct Readable {
  GiNaC::ex subject = 0;    ///< σ g x: "−α₂", "2m₂α₃"; 0 for the grouped shape
  GiNaC::ex quotient = 0;   ///< Q
  GiNaC::ex remainder = 0;  ///< R (isolated: 0 when S = 1)
  int named = 0;            ///< the k of the named part S = S_k, 0 when S = 1
};

/// The reduced system (ZᵀAZ)V = Zᵀb of a case, eliminated cluster by cluster
/// from the obstacle up (Gaussian elimination without square roots,
/// ZᵀAZ = LPLᵀ): what lets a condition of thousands of monomials be written
/// in a few lines.  With b_ij = (ZᵀAZ)_ij, r_i = (Zᵀb)_i and clusters
/// numbered 1 (top) … k, "t before j" meaning t is eliminated first (t > j):
///
///     p_j  = b_jj − Σ_{t before j} l_jt² p_t                   (pivots, > 0: ZᵀAZ is positive definite)
///     l_ij = (b_ij − Σ_{t before j} l_it l_jt p_t) / p_j      (i after j; only where structurally ≠ 0)
///     y_j  = r_j − Σ_{t before j} l_jt y_t
///     V_j  = y_j / p_j − Σ_{i after j} l_ij V_i                (back substitution, the top cluster first)
///
/// so det(ZᵀAZ) = Π p_j and V₁ = y₁/p₁: the whole stack below the top
/// cluster enters its velocity through p₁ and y₁ only.  For banded patterns
/// (near, near2) the multipliers stay in the band, so a case has O(k)
/// definitions of a few terms each.  Deriver::derive() checks the
/// definitions against the Cramer solution exactly modulo the prime
/// 2⁶¹ − 1 at a random point (a wrong definition passes with probability
/// below degree/(2⁶¹ − 1), Schwartz–Zippel).
struct Elimination {
  int size = 0;                    ///< k, the free clusters
  std::vector<GiNaC::ex> matrix;   ///< b_ij, row-major k×k (0-based clusters), expanded polynomials
  std::vector<GiNaC::ex> rhs;      ///< r_i
  std::vector<char> multiplier;    ///< l_ij present (i after j), row-major k×k
  std::vector<int> order;          ///< the clusters (0-based) in elimination order: k−1 (bottom) first
  /// The scaling's small parameters (order > 0), set to 0 in the definitions
  /// for the asymptotic forms that say so (EliminatedForm::limit); empty when
  /// no asymptotic form is written that way.
  std::vector<GiNaC::ex> small;
};

/// A condition written through the elimination: Σ_c coefficients_c V_c +
/// constant REL 0, which is the condition divided by det(ZᵀAZ) > 0.  For
/// the reaction on a closed contact it is λ = −R (the running sum of the
/// cluster's equations of motion).
struct EliminatedForm {
  std::vector<GiNaC::ex> coefficients;  ///< one polynomial per free cluster (0 where absent)
  GiNaC::ex constant = 0;               ///< a polynomial
  /// The definitions taken with Elimination::small at 0: the ε⁰ part of the
  /// condition, which is its dominant balance (the asymptotic form).
  bool limit = false;
};

/// One form of a condition: numerator / denominator REL 0, with the
/// denominator 1 whenever its sign was proved and cleared.  Under
/// Forms::Printed the numerator of a form written through the elimination
/// (`eliminated` set) is left 0.
struct ConditionForm {
  GiNaC::ex numerator = 0;    ///< an expanded polynomial
  GiNaC::ex denominator = 1;  ///< 1, or a polynomial whose sign was not proved
  /// Whether the condition holds for every admissible parameter, for none, or depends on them.
  Verdict verdict = Verdict::Depends;
  std::optional<Readable> readable;  ///< the isolated form, when a coupling can be isolated (sign proved, depends)
  /// The form through the case's elimination, when the polynomial (and its
  /// readable form) has more than max_inline_terms (asymptotic) or
  /// max_inline_exact_terms (exact, finite) terms.
  std::optional<EliminatedForm> eliminated;
  bool sign_proved() const;   ///< denominator == 1
};

/// A condition on the parameters, in its exact and asymptotic forms.
struct Condition {
  /// What the condition is about: the superball, a case's evolution, a contact, M's positive semi-definiteness.
  ConditionKind kind = ConditionKind::Superball;
  std::string about;  ///< "U1 > a", "2-3" (the contact), or "1-2,1-4" (the pairs of a minor)
  /// The relation to 0: numerator/denominator REL 0.
  Relation relation = Relation::Greater;
  ConditionForm exact;                 ///< m_n = ∞ (for a finite obstacle: the limit m_n → ∞)
  std::optional<ConditionForm> finite; ///< finite obstacle: the condition with m_n
  ConditionForm asymptotic;            ///< the dominant balance (plus --order corrections) of `finite` when set, else of `exact`
  GiNaC::numeric leading_order = 0;    ///< power of ε of the dominant balance
  GiNaC::numeric descended = 0;        ///< orders of ε lost because the leading terms of the parts cancel (in the same form)
  int orders_kept = 1;                 ///< number of orders of ε kept in `asymptotic`
  std::string proof;                   ///< how the denominator's sign was proved, or "sign not proved: ..."
  GiNaC::ex removed = 1;               ///< positive factor divided out of the numerator
};

/// A rational function numerator/denominator, normalised (gcd cancelled),
/// the denominator positive on the admissible parameters when proved.
struct Fraction {
  ///@{
  /// The numerator and the denominator (both left 0 under Forms::Printed
  /// when the fraction is written through the case's elimination).
  GiNaC::ex numerator = 0, denominator = 1;
  ///@}
  /// The terms of the numerator as an expanded polynomial, whether it is
  /// built or not: a report writes the fraction through the case's
  /// elimination when it has more than max_inline_exact_terms of them.
  std::size_t terms = 0;
  /// numerator / denominator as one GiNaC expression.
  GiNaC::ex value() const { return numerator / denominator; }
};

/// One evolution case solved, checked and turned into conditions.
struct Derivation {
  /// The symbols of the pattern the case was derived for.
  std::shared_ptr<const Symbols> symbols;
  /// The evolution case: the contacts that stay closed.
  ContactSet closed;
  std::string case_name;             ///< the paper's name (n = 4) or "{2-3,3-4}"
  std::vector<Fraction> velocities;  ///< U₁⁺ … U_n⁺
  std::vector<Fraction> reactions;   ///< R on contact (c, c+1), 0 where open
  GiNaC::ex determinant;             ///< det(ZᵀAZ), > 0 (1 when no body is free)
  int free_clusters = 0;             ///< size of the reduced system
  std::vector<Condition> conditions; ///< superball, evolution, contact, then psd
  std::vector<NamedPart> named;      ///< the positive parts the readable forms divide by
  /// The elimination that long forms are written through (ConditionForm::eliminated);
  /// set when a velocity, a reaction or a condition of the case is long.
  std::optional<Elimination> elimination;
  /// λ = −R on each closed contact through the elimination (empty coefficients where open or when not set).
  std::vector<EliminatedForm> reactions_eliminated;
  std::string check;                 ///< what the substitution check verified
  /// Whether the case can be the actual evolution: Never when one of its
  /// evolution or contact conditions fails for every admissible parameter
  /// (the case's conditions clash), Always when they all hold, else Depends.
  Verdict actual = Verdict::Depends;
  std::string actual_reason;         ///< for Never: the "about" of the first condition that never holds
};

/// Most moving clusters (groups of bodies joined by closed contacts, the
/// fixed obstacle's excluded) a case may have: the reduced system's
/// determinants are expanded with every minor memoised by its set of columns,
/// which takes at most this many.
inline constexpr int max_moving_clusters = 20;

/// Most bodies a derivation takes: every case of the pattern solvable, that
/// is `--closed none` with max_moving_clusters moving bodies (21 with the
/// fixed obstacle, 20 with a finite one).
int max_bodies(Obstacle obstacle);

/// Throws std::invalid_argument("check_bodies(): n = N: ...") when a
/// pattern of \p bodies bodies cannot be derived with \p obstacle: fewer
/// than 2, or more than max_bodies(), in one line that gives the rule.
void check_bodies(int bodies, Obstacle obstacle);

/// Which forms of a case Deriver::derive() builds in GiNaC.
enum class Forms {
  /// Every form: velocities, reactions and conditions, also those long
  /// enough to be written through the case's elimination.
  All,
  /// The forms a compact report prints (`derive` without `--expanded`, in
  /// text or JSON): a velocity or reaction of more than
  /// max_inline_exact_terms terms that is written through the elimination,
  /// and a condition's form written through it, keep their polynomial only
  /// (checked on the polynomials, as every result is) and are not built in
  /// GiNaC, nor read back; their GiNaC numerators are left 0.  The same
  /// report, in a fraction of the time and memory of a long case.
  Printed,
};

/// Solves evolution cases for one pattern and one obstacle, with the
/// asymptotic regime and order used for the asymptotic forms.
class Deriver {
 public:
  /// \p scaling defaults to Scaling::paper(); \p order >= 0 is the number of
  /// correction orders kept beyond the dominant balance.  Throws
  /// std::invalid_argument("Deriver::Deriver(): ...") for order < 0 and
  /// check_bodies()'s for a pattern of too many bodies.
  Deriver(const Pattern& pattern, Obstacle obstacle, std::optional<Scaling> scaling = std::nullopt, int order = 0);

  /// Solve the case \p closed (paper §4): reduced system (ZᵀAZ)V = Zᵀb by
  /// fraction-free determinants (Cramer with det(ZᵀAZ) > 0), reactions by
  /// running sums, every result substituted back into the unreduced equations
  /// (throws std::logic_error("Deriver::derive(): ...") if a residual is not
  /// zero), then the conditions.  Throws std::invalid_argument for a case of
  /// another number of bodies.
  Derivation derive(const ContactSet& closed) const;
  /// The polynomial half of derive(\p closed), to run ahead in another
  /// process (symbolic::derive_cases()): the solution by Cramer's rule, the
  /// check that it satisfies the equations of motion, and the proofs of
  /// which numerators are coprime with det(ZᵀAZ).  Returns them as compact
  /// binary text for derive(\p closed, text), which then does only the rest
  /// (the results in GiNaC, their check against the solution, the
  /// conditions' forms).  Throws as derive() does.
  std::string prepare(const ContactSet& closed) const;
  /// prepare(\p closed) in \p pieces parts to run side by side: part
  /// \p piece (0 … pieces − 1) solves the case, checks the equations of
  /// motion of the free bodies i ≡ piece (mod pieces) and proves the
  /// coprimality of the numerators q ≡ piece (mod pieces); part 0 also
  /// checks the contacts and carries the solution.  join_prepared() of the
  /// parts in order is prepare(\p closed), byte for byte.  Throws
  /// std::invalid_argument("Deriver::prepare(): ...") unless
  /// 0 <= piece < pieces, and as prepare() does.
  std::string prepare(const ContactSet& closed, int piece, int pieces) const;
  /// The text of prepare() from its parts (prepare(closed, k, pieces.size())
  /// for k in order).  Throws std::invalid_argument("join_prepared(): ...")
  /// for no part, or parts of other cases, other sizes or out of order.
  static std::string join_prepared(const std::vector<std::string>& pieces);
  /// derive(\p closed) finished from \p prepared, the text of
  /// prepare(\p closed) (the same Derivation; empty: derive(\p closed)),
  /// with the forms \p forms says.  Throws
  /// std::invalid_argument("Deriver::derive(): ...") for the prepared work
  /// of another case, or one truncated.
  Derivation derive(const ContactSet& closed, const std::string& prepared, Forms forms = Forms::All) const;
  /// All 2^(n−1) cases, mask order (bit c closes contact (c+1, c+2)).
  std::vector<Derivation> derive_all() const;

  /// The symbols of the pattern (shared with every Derivation).
  const Symbols& symbols() const { return *symbols_; }
  /// The same, shared.
  std::shared_ptr<const Symbols> shared_symbols() const { return symbols_; }
  /// The regime of the asymptotic forms.
  const Scaling& scaling() const { return scaling_; }
  /// Correction orders kept beyond the dominant balance.
  int order() const { return order_; }
  /// The positive semi-definiteness conditions of M for the pattern (§3):
  /// one principal minor >= 0 per connected set of pairs of the coupling
  /// graph (a minor on a disconnected set is the product of its parts), so
  /// together they are equivalent to M ⪰ 0; a single pair reads K_p > 0 as
  /// in the paper.
  const std::vector<Condition>& psd() const { return psd_; }

  /// The asymptotic form of the polynomial condition \p p: the terms of the
  /// lowest ε-orders (1 + order() of them), positive factors removed.
  /// \p leading receives the lowest order.
  GiNaC::ex asymptotic(const GiNaC::ex& p, GiNaC::numeric* leading = nullptr) const;

 private:
  // The rules on polynomials (conditions, verdicts, readable forms) live in
  // the implementation; they read the ε-orders and couplings below.
  std::shared_ptr<const Symbols> symbols_;
  Scaling scaling_;
  int order_ = 0;
  std::vector<Condition> psd_;
  std::vector<GiNaC::numeric> orders_;  ///< the ε-order of each symbol, by index in Symbols::all()
  std::vector<int> couplings_;          ///< the indices of the couplings in Symbols::all()
};

/// The ε-order of the expanded polynomial \p p (lowest over its terms) under
/// \p scaling; throws std::invalid_argument("epsilon_order(): ...") for p = 0.
GiNaC::numeric epsilon_order(const GiNaC::ex& p, const Symbols& symbols, const Scaling& scaling);

/// Conditions with more terms than this get no readable form (Readable):
/// at 6 bodies a division of such a polynomial by each candidate part was
/// measured to cost about a quarter of the derivation, for forms that stay
/// hundreds of terms long.
inline constexpr std::size_t max_readable_terms = 1000;

/// An asymptotic form with more terms than this (its readable form counted
/// as quotient, remainder and named part) is written through the case's
/// elimination when it can be (Elimination, EliminatedForm::limit); the
/// expanded polynomial stays in the JSON.  The asymptotic forms are the ones
/// a reader compares (the paper's conditions are asymptotic).
inline constexpr std::size_t max_inline_terms = 16;

/// Cases with fewer free clusters than this are never written through their
/// elimination (with one unknown velocity, V₁ = y₁/p₁ is the formula itself).
/// Two is enough to pay: at 6 bodies, cases of two clusters have conditions
/// of hundreds of terms (their entries are sums over the clusters' bodies).
inline constexpr int min_eliminated_clusters = 2;

/// An exact (or finite-obstacle) condition form, a velocity, a reaction or
/// det(ZᵀAZ) with more terms than this is written through the elimination:
/// exact forms are references, kept expanded longer (the paper's four bodies
/// with all seven couplings stay expanded), and no line passes about 5,000
/// characters at 6 or 7 bodies.
inline constexpr std::size_t max_inline_exact_terms = 100;

/// Polynomials with more terms than this are not factorised by
/// strip_positive_factors() (multivariate factorisation would dominate the
/// cost of a derivation; the content and the common monomial are still removed).
inline constexpr std::size_t max_factor_terms = 40;

/// \p p with its positive factors divided out: the positive rational content,
/// the monomial of positive symbols common to every term, and (for at most
/// max_factor_terms terms) every irreducible factor that is a sum of terms
/// with positive coefficients in positive symbols and even powers of
/// couplings.  \p removed receives the product divided out (positive for
/// all admissible parameters).
GiNaC::ex strip_positive_factors(const GiNaC::ex& p, const Symbols& symbols, GiNaC::ex* removed = nullptr);

/// Whether the expanded polynomial \p p is > 0 for every admissible
/// parameter point (positive masses, K's, a; real couplings): every term has
/// a positive coefficient, even powers of couplings, and one term has no coupling.
bool certainly_positive(const GiNaC::ex& p, const Symbols& symbols);

/// Whether the expanded polynomial \p p is >= 0 for every admissible point:
/// every term has a positive coefficient and even powers of couplings.
bool certainly_nonnegative(const GiNaC::ex& p, const Symbols& symbols);

/// Whether the conditions "p REL 0" and "q REL 0" are the same: p/q is
/// positive for every admissible parameter point (a positive rational times
/// a product of positive symbols).
bool same_condition(const GiNaC::ex& p, const GiNaC::ex& q, const Symbols& symbols);

/// The reference point used to fix the sign of a factor of det(ZᵀAZ): every
/// mass, K and a equal to 1, every coupling 0 (M = identity, positive definite).
GiNaC::exmap reference_point(const Symbols& symbols);

}  // namespace superball::symbolic

SUPERBALL_SYMBOLIC_API_END
