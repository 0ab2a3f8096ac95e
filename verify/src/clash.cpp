// The clash proofs of explore_case() (clash.hpp) and the audit's
// impossibility certificate (explore.hpp).
#include "clash.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "simplex.hpp"
#include "superball/symbolic/format.hpp"

namespace superball::verify::detail::explore {

using namespace superball::symbolic;

namespace {

/// The rounding of the linear programme's solution to fractions (largest denominator, distance).
constexpr long rational_denominator = 1000;
constexpr double rational_tolerance = 1e-7;

/// One condition of the case usable in a certificate: a numerator of proved sign.
struct Usable {
  const Condition* condition;
  const ConditionForm* form;
};

/// The form Σ_c μ_c·(K_p + K_q ± 2c) over the couplings c (of pairs p, q)
/// that cancels every term of \p p linear in a coupling: μ_c = |P_c|/2 with
/// P_c the coefficient of c¹ in p, when P_c has one certain sign (then each
/// μ_c >= 0 and each bracket is a quadratic form of the 2×2 minor of M on
/// p, q, >= 0 when M is positive semi-definite).  nullopt when some P_c has
/// no certain sign or the pattern has no coupling.
std::optional<std::pair<GiNaC::ex, std::string>> minor_multiples(const GiNaC::ex& p, const Symbols& sy) {
  GiNaC::ex value = 0;
  std::string text;
  for (const PairCoupling& c : sy.pattern().couplings) {
    if (!sy.pattern().has_diagonal(c.first) || !sy.pattern().has_diagonal(c.second)) return std::nullopt;
    const GiNaC::ex& alpha = sy.coupling(c.first, c.second);
    const GiNaC::ex linear = GiNaC::expand(p.coeff(alpha, 1));
    if (linear.is_zero()) continue;
    int sign = 0;
    if (certainly_nonnegative(linear, sy)) sign = 1;
    else if (certainly_nonnegative(GiNaC::expand(-linear), sy)) sign = -1;
    else return std::nullopt;
    const GiNaC::ex mu = GiNaC::expand(sign * linear / 2);
    const GiNaC::ex bracket = sy.diagonal(c.first) + sy.diagonal(c.second) + 2 * sign * alpha;
    value += mu * bracket;
    text += (text.empty() ? "" : " + ") + std::string("(") + format_polynomial(mu, sy, Style::Text) + ")·(" +
            format_polynomial(GiNaC::expand(bracket), sy, Style::Text) + ")";
  }
  if (text.empty()) return std::nullopt;
  return std::make_pair(GiNaC::expand(value), text);
}

/// The clash of the conditions \p usable weighted by \p multipliers (0 for
/// unused ones; numbers or polynomials >= 0), with −Σ multiplierᵢ·Nᵢ = Q + rest.
Clash make_clash(const std::vector<Usable>& usable, const std::vector<GiNaC::ex>& multipliers, const std::string& q_text,
                 const GiNaC::ex& rest, bool asymptotic, const Symbols& sy) {
  Clash clash;
  clash.asymptotic = asymptotic;
  std::string names;
  for (std::size_t i = 0; i < usable.size(); ++i) {
    if (multipliers[i].is_zero()) continue;
    const Condition& c = *usable[i].condition;
    clash.superball = clash.superball || c.kind == ConditionKind::Superball;
    const std::string name = "N" + std::to_string(clash.conditions.size() + 1);
    const bool number = GiNaC::is_a<GiNaC::numeric>(multipliers[i]);
    const std::string factor = format_polynomial(multipliers[i], sy, Style::Text);
    clash.conditions.push_back(name + " (" + (number ? "weight " : "multiplier ") + factor + "), " + condition_title(c, Style::Text) + ": " +
                               format_condition(*usable[i].form, c.relation, sy, Style::Text));
    const bool one = number && (multipliers[i] - 1).is_zero();
    names += (names.empty() ? "" : " + ") + (one ? "" : number ? factor + "·" : "(" + factor + ")·") + name;
  }
  clash.identity = "with each Nᵢ the condition's polynomial (Nᵢ > 0 or >= 0 as stated): −(" + names + ") = " + (q_text.empty() ? "" : "Q + ") +
                   "(" + format_polynomial(rest, sy, Style::Text) + ")" + (q_text.empty() ? "" : ", Q = " + q_text) +
                   "; every term of the bracket is >= 0" + (q_text.empty() ? "" : " and Q >= 0 when M is positive semi-definite") +
                   ", each multiplier is >= 0, so " + names + " <= 0, while the conditions make it > 0";
  return clash;
}

/// \p v as a fraction of denominator at most rational_denominator (continued
/// fractions), or nullopt when none is within rational_tolerance.
std::optional<GiNaC::numeric> small_fraction(double v) {
  if (std::fabs(v) < rational_tolerance) return GiNaC::numeric(0);
  long p0 = 0, q0 = 1, p1 = 1, q1 = 0;
  double x = v;
  for (int k = 0; k < 40; ++k) {
    const double a = std::floor(x);
    if (std::fabs(a) > static_cast<double>(rational_denominator) * 1e6) break;  // also keeps the casts in range
    const long p2 = static_cast<long>(a) * p1 + p0, q2 = static_cast<long>(a) * q1 + q0;
    if (q2 > rational_denominator) break;
    p0 = p1, q0 = q1, p1 = p2, q1 = q2;
    if (std::fabs(v - static_cast<double>(p1) / static_cast<double>(q1)) < rational_tolerance) return GiNaC::numeric(p1, q1);
    if (x - a < 1e-300) break;
    x = 1 / (x - a);
  }
  return std::nullopt;
}

/// The certificate of find_clash() with polynomial multipliers, as a linear
/// programme: unknowns λ >= 0 on the products μ·Nᵢ (μ = 1 or one positive
/// symbol) and μ·(K_p + K_q ± 2c) (the 2×2 minor forms of the couplings c);
/// −Σ λ·products must have a zero coefficient on every monomial with an odd
/// power of a coupling and a nonnegative one elsewhere, and the strict
/// conditions' λ sum to 1.  The double solution is rounded to small fractions
/// and the identity checked exactly (certainly_nonnegative); nullopt otherwise.
std::optional<Clash> lp_clash(const std::vector<Usable>& usable, bool asymptotic, bool with_superball, const Symbols& sy) {
  std::vector<GiNaC::ex> mus{GiNaC::ex(1)};
  for (const SymbolInfo& i : sy.all())
    if (i.kind != SymbolKind::Coupling && i.kind != SymbolKind::FallSpeed) mus.push_back(i.symbol);
  struct Product {
    GiNaC::ex value, mu;
    int condition;  ///< index in usable, or −1 for a minor form
    bool strict;
    std::string bracket;  ///< minor form: "K₁₂ + K₁₃ + 2α₁"
    GiNaC::ex form;
  };
  std::vector<Product> products;
  bool any_strict = false, has_superball = false;
  for (std::size_t i = 0; i < usable.size(); ++i) {
    const bool superball = usable[i].condition->kind == ConditionKind::Superball;
    if (superball && !with_superball) continue;
    has_superball = has_superball || superball;
    const bool strict = usable[i].condition->relation == Relation::Greater;
    any_strict = any_strict || strict;
    for (const GiNaC::ex& mu : mus) products.push_back({GiNaC::expand(mu * usable[i].form->numerator), mu, static_cast<int>(i), strict, "", 0});
  }
  if (!any_strict || (with_superball && !has_superball)) return std::nullopt;
  for (const PairCoupling& c : sy.pattern().couplings) {
    if (!sy.pattern().has_diagonal(c.first) || !sy.pattern().has_diagonal(c.second)) continue;
    for (int sign : {1, -1}) {
      const GiNaC::ex form = sy.diagonal(c.first) + sy.diagonal(c.second) + 2 * sign * sy.coupling(c.first, c.second);
      for (const GiNaC::ex& mu : mus)
        products.push_back({GiNaC::expand(mu * form), mu, -1, false, format_polynomial(GiNaC::expand(form), sy, Style::Text), form});
    }
  }
  // Rows: one per monomial; a product enters with its coefficient.
  std::map<std::vector<std::pair<int, int>>, std::vector<double>> rows;
  for (std::size_t j = 0; j < products.size(); ++j)
    for (Monomial& m : sy.monomials(products[j].value)) {
      std::sort(m.powers.begin(), m.powers.end());  // GiNaC's order of the factors varies between runs
      auto& row = rows[m.powers];
      row.resize(products.size(), 0.0);
      row[j] += m.coefficient.to_double();
    }
  std::vector<std::vector<double>> eq, le;
  std::vector<double> b;
  for (auto& [powers, row] : rows) {
    row.resize(products.size(), 0.0);
    bool odd = false;
    for (const auto& [k, e] : powers) odd = odd || (sy.all()[static_cast<std::size_t>(k)].kind == SymbolKind::Coupling && e % 2);
    if (odd) {
      eq.push_back(row);
      b.push_back(0);
    } else {
      le.push_back(row);  // Σ λ·coefficient <= 0: the negation's coefficient is >= 0
    }
  }
  std::vector<double> normal(products.size(), 0.0);
  // Normalisation: the strict conditions' λ sum to 1 (a nonzero multiplier is a sum of positive terms, so > 0).
  for (std::size_t j = 0; j < products.size(); ++j) normal[j] = products[j].strict ? 1 : 0;
  eq.push_back(normal);
  b.push_back(1);
  const auto x = feasible_point(eq, b, le, products.size());
  if (!x) return std::nullopt;
  // Exact check with the rounded multipliers, scaled to integers.
  std::vector<GiNaC::numeric> lambdas;
  GiNaC::numeric common = 1;
  for (std::size_t j = 0; j < products.size(); ++j) {
    const auto lambda = small_fraction((*x)[j]);
    if (!lambda || *lambda < 0) return std::nullopt;
    lambdas.push_back(*lambda);
    common = GiNaC::lcm(common, lambda->denom());
  }
  std::vector<GiNaC::ex> multipliers(usable.size(), GiNaC::ex(0));
  std::map<std::string, std::pair<GiNaC::ex, GiNaC::ex>> forms;  // bracket text → (its multiplier, the bracket)
  GiNaC::ex sum = 0, q = 0;
  for (std::size_t j = 0; j < products.size(); ++j) {
    const GiNaC::numeric lambda_j = lambdas[j] * common;
    const GiNaC::numeric* lambda = &lambda_j;
    if (lambda->is_zero()) continue;
    const Product& p = products[j];
    if (p.condition >= 0) {
      multipliers[static_cast<std::size_t>(p.condition)] += *lambda * p.mu;
      sum += *lambda * p.value;
    } else {
      auto& slot = forms[p.bracket];
      slot.first += *lambda * p.mu;
      slot.second = p.form;
      q += *lambda * p.value;
    }
  }
  bool strict = false;
  for (std::size_t i = 0; i < usable.size(); ++i) {
    multipliers[i] = GiNaC::expand(multipliers[i]);
    strict = strict || (usable[i].condition->relation == Relation::Greater && certainly_positive(multipliers[i], sy));
  }
  // A strict condition with a multiplier > 0 (nonzero sum of 1 and positive symbols) makes the sum > 0.
  if (!strict) return std::nullopt;
  const GiNaC::ex rest = GiNaC::expand(-sum - q);
  if (!certainly_nonnegative(rest, sy)) return std::nullopt;
  std::string q_text;
  for (const auto& [bracket, f] : forms)
    q_text += (q_text.empty() ? "" : " + ") + std::string("(") + format_polynomial(GiNaC::expand(f.first), sy, Style::Text) + ")·(" + bracket + ")";
  return make_clash(usable, multipliers, q_text, rest, asymptotic, sy);
}

}  // namespace

std::string signed_pairs(const std::vector<int>& x, const std::vector<Pair>& pairs) {
  std::string v;
  for (std::size_t r = 0; r < pairs.size(); ++r)
    if (x[r]) v += (v.empty() ? "" : ", ") + std::string(x[r] > 0 ? "+" : "-") + "e(" + pairs[r].name() + ")";
  return v;
}

GiNaC::ex quadratic_form(const std::vector<int>& x, const std::vector<Pair>& pairs, const Symbols& sy) {
  GiNaC::ex form = 0;
  for (std::size_t r = 0; r < pairs.size(); ++r)
    for (std::size_t c = 0; c < pairs.size(); ++c)
      if (x[r] && x[c]) form += x[r] * x[c] * sy.entry(pairs[r], pairs[c]);
  return GiNaC::expand(form);
}

bool next_signs(std::vector<int>& x) {
  std::size_t i = 0;
  while (i < x.size() && x[i] == 1) x[i++] = -1;
  if (i == x.size()) return false;
  ++x[i];
  return true;
}

std::optional<Clash> find_clash(const Derivation& d, const Symbols& sy, bool asymptotic) {
  std::vector<Usable> usable;
  for (const Condition& c : d.conditions) {
    if (c.kind == ConditionKind::Psd) continue;
    const ConditionForm& form = asymptotic ? c.asymptotic : c.exact;
    if (form.sign_proved()) usable.push_back({&c, &form});
  }
  std::stable_partition(usable.begin(), usable.end(), [](const Usable& u) { return u.condition->kind != ConditionKind::Superball; });
  // The quadratic forms: only coupled pairs matter (an uncoupled pair adds t·K_p to the bracket's negative side).
  std::vector<Pair> pairs;
  for (const PairCoupling& c : sy.pattern().couplings)
    for (const Pair& p : {c.first, c.second})
      if (std::find(pairs.begin(), pairs.end(), p) == pairs.end()) pairs.push_back(p);
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.name() < b.name(); });
  struct Form {
    GiNaC::ex value;
    std::string text;  ///< "" for 0, else "t·xᵀMx, x = …"
  };
  std::vector<Form> forms{{GiNaC::ex(0), ""}};
  if (!pairs.empty() && pairs.size() <= 8) {
    std::vector<int> x(pairs.size(), -1);
    do {
      const auto first = std::find_if(x.begin(), x.end(), [](int v) { return v != 0; });
      if (first == x.end() || *first < 0) continue;  // x and −x give the same form
      const GiNaC::ex q = quadratic_form(x, pairs, sy);
      for (int t : {1, 2}) forms.push_back({GiNaC::expand(t * q), std::to_string(t) + "·xᵀMx, x = " + signed_pairs(x, pairs)});
    } while (next_signs(x));
  }
  const std::size_t n = usable.size();
  std::vector<std::vector<int>> weights;
  std::vector<int> w(n, 0);
  for (;;) {
    std::size_t i = 0;
    while (i < n && w[i] == 2) w[i++] = 0;
    if (i == n) break;
    ++w[i];
    weights.push_back(w);
  }
  // Fewer conditions first, the superball condition last (it is the last usable one).
  auto key = [&](const std::vector<int>& v) {
    int used = 0, total = 0;
    for (int x : v) used += x > 0, total += x;
    const bool superball = n > 0 && usable.back().condition->kind == ConditionKind::Superball && v.back() > 0;
    return std::make_tuple(superball, used, total);
  };
  std::stable_sort(weights.begin(), weights.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  // Without the superball condition first: a clash there proves the case never actual.
  for (const bool with_superball : {false, true}) {
    for (const std::vector<int>& wt : weights) {
      if (std::get<0>(key(wt)) != with_superball) continue;
      bool strict = false;
      GiNaC::ex sum = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (wt[i]) {
          sum += wt[i] * usable[i].form->numerator;
          strict = strict || usable[i].condition->relation == Relation::Greater;
        }
      if (!strict) continue;
      sum = GiNaC::expand(sum);
      std::vector<Form> candidates = forms;
      if (const auto m = minor_multiples(-sum, sy)) candidates.push_back({m->first, m->second});
      for (const Form& q : candidates) {
        const GiNaC::ex rest = GiNaC::expand(-sum - q.value);
        if (!certainly_nonnegative(rest, sy)) continue;
        std::vector<GiNaC::ex> multipliers(wt.begin(), wt.end());
        return make_clash(usable, multipliers, q.text, rest, asymptotic, sy);
      }
    }
    if (auto clash = lp_clash(usable, asymptotic, with_superball, sy)) return clash;
  }
  return std::nullopt;
}

}  // namespace superball::verify::detail::explore

namespace superball::verify {

std::string impossibility_certificate(const GiNaC::ex& s_poly, const symbolic::Symbols& sy) {
  const std::vector<Pair> pairs = sy.pattern().pairs();
  const std::size_t k = pairs.size();
  if (k > 10) return "";
  std::vector<int> x(k, -1);
  do {
    const GiNaC::ex form = detail::explore::quadratic_form(x, pairs, sy);
    if (!form.is_zero())
      for (int t : {1, 2}) {
        const GiNaC::ex rest = GiNaC::expand(-s_poly - t * form);
        if (symbolic::certainly_nonnegative(rest, sy))
          return "the superball condition reads S > 0 with -S = " + std::to_string(t) + "·xᵀMx + (" +
                 symbolic::format_polynomial(rest, sy, symbolic::Style::Text) + "), x = " + detail::explore::signed_pairs(x, pairs) +
                 ": every term of the bracket is >= 0 and xᵀMx >= 0 when M is positive semi-definite, so S <= 0";
      }
  } while (detail::explore::next_signs(x));
  return "";
}

}  // namespace superball::verify
