#include "superball/symbolic/derivation.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <cln/rational.h>

#include "poly.hpp"
#include "polynomial.hpp"
#include "superball/cases/error.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/format.hpp"

namespace superball::symbolic {
namespace {

std::string show(const GiNaC::ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

/// Polynomial `p` with the lowest ε-orders kept: (order, polynomial) per level, ascending.
std::vector<std::pair<GiNaC::numeric, GiNaC::ex>> levels(const GiNaC::ex& p, const Symbols& symbols, const Scaling& scaling) {
  std::vector<std::pair<GiNaC::numeric, GiNaC::ex>> out;
  for (const detail::Term& t : detail::terms(GiNaC::expand(p))) {
    GiNaC::numeric w = 0;
    for (const auto& [s, e] : t.powers) w += scaling.order(symbols, s) * e;
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& level) { return level.first == w; });
    if (it == out.end())
      out.emplace_back(w, t.coefficient * t.monomial());
    else
      it->second += t.coefficient * t.monomial();
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  return out;
}

Verdict verdict_of(const GiNaC::ex& p, Relation rel, const Symbols& symbols) {
  if (p.is_zero()) return rel == Relation::GreaterEqual ? Verdict::Always : Verdict::Never;
  if (rel == Relation::Greater ? certainly_positive(p, symbols) : detail::certainly_nonnegative(p, symbols)) return Verdict::Always;
  if (rel == Relation::Greater ? detail::certainly_nonnegative(-p, symbols) : certainly_positive(-p, symbols)) return Verdict::Never;
  return Verdict::Depends;
}

/// Connected sets of vertices of an undirected graph (ESU enumeration, each
/// set once), at most `cap` of them; returns false when the cap was hit.
bool connected_sets(const std::vector<std::vector<int>>& adjacent, std::size_t cap, std::vector<std::vector<int>>& out) {
  const int v = static_cast<int>(adjacent.size());
  auto adjacent_to = [&](int x, int y) { return std::find(adjacent[x].begin(), adjacent[x].end(), y) != adjacent[x].end(); };
  struct Frame {
    std::vector<int> set, extension;
  };
  for (int root = 0; root < v; ++root) {
    std::vector<Frame> stack{{{root}, {}}};
    for (int w : adjacent[root])
      if (w > root) stack.back().extension.push_back(w);
    while (!stack.empty()) {
      Frame f = std::move(stack.back());
      stack.pop_back();
      std::vector<int> sorted = f.set;
      std::sort(sorted.begin(), sorted.end());
      out.push_back(sorted);
      if (out.size() >= cap) return false;
      while (!f.extension.empty()) {
        const int w = f.extension.back();
        f.extension.pop_back();
        Frame next{f.set, f.extension};
        next.set.push_back(w);
        for (int u : adjacent[w]) {
          if (u <= root || std::find(f.set.begin(), f.set.end(), u) != f.set.end() ||
              std::find(next.extension.begin(), next.extension.end(), u) != next.extension.end() || u == w)
            continue;
          bool exclusive = true;
          for (int s : f.set) exclusive = exclusive && !adjacent_to(s, u);
          if (exclusive) next.extension.push_back(u);
        }
        stack.push_back(std::move(next));
      }
    }
  }
  return true;
}

using detail::Poly;

/// The parts a case's readable forms name, in the order of first use, and
/// the candidates they may group by (the diagonal entries of ZᵀAZ).
struct Naming {
  std::vector<Poly> named, candidates;
  /// The k of S_k for \p s, naming it when it is new.
  int name(const Poly& s) {
    const auto k = static_cast<std::size_t>(std::find(named.begin(), named.end(), s) - named.begin());
    if (k == named.size()) named.push_back(s);
    return static_cast<int>(k) + 1;
  }
};

/// A Deriver's rules on polynomials (poly.hpp): the same rules as
/// certainly_nonnegative(), certainly_positive(), strip_positive_factors()
/// and Deriver::asymptotic(), and the conditions made with them, for
/// Deriver::derive().  Reads the deriver's ε-order of each symbol and its
/// couplings (by index in Symbols::all()): it must not outlive the deriver.
class Rules {
 public:
  Rules(const Deriver& deriver, const std::vector<GiNaC::numeric>& orders, const std::vector<int>& couplings)
      : deriver_(deriver), sy_(deriver.symbols()), couplings_(couplings) {
    for (const GiNaC::numeric& o : orders) orders_.push_back(cln::the<cln::cl_RA>(o.to_cl_N()));
    for (std::size_t k = 0; k < orders_.size(); ++k)
      if (!cln::zerop(orders_[k])) ordered_.push_back(static_cast<int>(k));
  }

  /// The condition "raw / determinant REL 0" in its exact, finite and
  /// asymptotic forms (\p parts: the polynomials whose leading orders may
  /// cancel in raw; \p eliminated: its form through the case's elimination,
  /// \p limit: whether that form gives the ε⁰ part).
  Condition make_condition(ConditionKind kind, const std::string& about, Relation relation, const Poly& raw,
                           const detail::Denominator& determinant, const std::vector<const Poly*>& parts, Naming& naming,
                           const EliminatedForm* eliminated = nullptr, bool limit = false, const bool* coprime = nullptr,
                           Forms forms = Forms::All) const;
  /// The isolated or grouped form of \p p, naming the part it divides by.
  std::optional<Readable> readable(const Poly& p, Naming& naming) const;
  /// The lowest ε-order of the terms of \p p (throws for p = 0).
  GiNaC::numeric epsilon_order(const Poly& p) const;
  /// Every term has a positive coefficient and even powers of couplings.
  bool nonnegative_terms(const Poly& p) const;
  /// nonnegative_terms(), and a term has no coupling.
  bool positive_terms(const Poly& p) const;
  /// Whether "p REL 0" holds always, never, or depending on the parameters.
  Verdict verdict(const Poly& p, Relation rel) const;
  /// \p p with its positive factors divided out (\p removed receives them).
  Poly strip(const Poly& p, GiNaC::ex* removed = nullptr) const;
  /// The terms of the lowest 1 + order() ε-orders of \p p, stripped;
  /// \p leading receives the lowest order.
  Poly dominant(const Poly& p, GiNaC::numeric* leading) const;
  /// The ε-order of term \p t of \p p (CLN's rationals: small ones are
  /// immediate, where each GiNaC::numeric is an object of its own).
  cln::cl_RA term_order(const Poly& p, std::size_t t) const;
  /// \p p divided by g, the positive integer content times the monomial of
  /// positive symbols common to its terms (g receives it).
  Poly without_positive_monomial(const Poly& p, Poly& g) const;

 private:
  const Deriver& deriver_;
  const Symbols& sy_;
  std::vector<cln::cl_RA> orders_;  ///< the ε-order of each symbol
  std::vector<int> ordered_;        ///< the symbols of a nonzero ε-order, ascending (term_order() reads only those)
  const std::vector<int>& couplings_;
};

/// M's positive semi-definiteness conditions for \p deriver's pattern (Deriver::psd()).
std::vector<Condition> psd_conditions(const Deriver& deriver);

}  // namespace

const char* to_string(ConditionKind kind) {
  switch (kind) {
    case ConditionKind::Superball: return "superball";
    case ConditionKind::Evolution: return "evolution";
    case ConditionKind::Contact: return "contact";
    case ConditionKind::Psd: break;
  }
  return "psd";
}

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::Depends: return "depends";
    case Verdict::Always: return "always";
    case Verdict::Never: break;
  }
  return "never";
}

bool ConditionForm::sign_proved() const { return denominator.is_equal(GiNaC::ex(1)); }

// ---------------------------------------------------------------- Scaling

Scaling Scaling::paper(const Symbols& symbols) {
  Scaling s;
  const int n = symbols.bodies();
  s.order_["m1"] = 1;
  if (symbols.obstacle() == Obstacle::Finite) s.order_["m" + std::to_string(n)] = -1;
  if (symbols.pattern().has_diagonal(Pair{1, n})) s.order_["K" + pair_code(Pair{1, n})] = -1;
  return s;
}

Scaling Scaling::parse(const std::string& text, const Symbols& symbols) {
  Scaling s;
  if (text == "none" || text.empty()) return s;
  std::size_t start = 0;
  for (;;) {
    const auto comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw std::invalid_argument("Scaling::parse(): '" + item + "' is not NAME=ORDER (e.g. m1=1, K14=-1)");
    const std::string name = item.substr(0, eq), value = item.substr(eq + 1);
    try {
      symbols.by_name(name);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("Scaling::parse(): " + without_function_prefix(e.what()));
    }
    GiNaC::numeric order;
    try {
      const GiNaC::ex v = GiNaC::parser()(value);
      if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_rational()) throw std::invalid_argument("");
      order = GiNaC::ex_to<GiNaC::numeric>(v);
    } catch (const std::exception&) {
      throw std::invalid_argument("Scaling::parse(): the order of " + name + " must be a rational number (got '" + value + "')");
    }
    if (s.order_.count(name)) throw std::invalid_argument("Scaling::parse(): " + name + " is given twice");
    s.order_[name] = order;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return s;
}

GiNaC::numeric Scaling::order(const Symbols& symbols, const GiNaC::ex& s) const {
  const auto it = order_.find(symbols.info(s).ascii);
  return it == order_.end() ? GiNaC::numeric(0) : it->second;
}

std::string Scaling::describe(const Symbols& symbols, Style style) const {
  if (order_.empty()) return style == Style::Latex ? "\\text{all parameters } O(1)" : "all parameters O(1)";
  std::string out;
  for (const SymbolInfo& s : symbols.all()) {
    const auto it = order_.find(s.ascii);
    if (it == order_.end()) continue;
    out += (out.empty() ? "" : ", ") + s.name(style) + (style == Style::Latex ? " \\sim " : " ~ ") + epsilon_power(it->second, style);
  }
  return out + (style == Style::Latex ? ",\\ \\text{others } O(1)" : ", others O(1)");
}

// ---------------------------------------------------------------- Deriver

int max_bodies(Obstacle obstacle) { return obstacle == Obstacle::Infinite ? max_moving_clusters + 1 : max_moving_clusters; }

void check_bodies(int bodies, Obstacle obstacle) {
  if (bodies < 2 || bodies > max_bodies(obstacle))
    throw std::invalid_argument("check_bodies(): n = " + std::to_string(bodies) + ": the symbolic derivation takes 2 to " +
                                std::to_string(max_bodies(Obstacle::Infinite)) + " bodies with a fixed obstacle, 2 to " +
                                std::to_string(max_bodies(Obstacle::Finite)) + " with a finite one (at most " +
                                std::to_string(max_moving_clusters) + " bodies moving apart: determinants of up to " +
                                std::to_string(max_moving_clusters) + " x " + std::to_string(max_moving_clusters) + ")");
}

Deriver::Deriver(const Pattern& pattern, Obstacle obstacle, std::optional<Scaling> scaling, int order)
    : symbols_((check_bodies(pattern.bodies, obstacle), std::make_shared<const Symbols>(pattern, obstacle))), order_(order) {
  if (order < 0) throw std::invalid_argument("Deriver::Deriver(): the order must be >= 0 (got " + std::to_string(order) + ")");
  scaling_ = scaling ? *scaling : Scaling::paper(*symbols_);
  for (const SymbolInfo& info : symbols_->all()) {
    orders_.push_back(scaling_.order(*symbols_, info.symbol));
    if (info.kind == SymbolKind::Coupling) couplings_.push_back(info.rank);
  }
  psd_ = psd_conditions(*this);
}

GiNaC::ex Deriver::asymptotic(const GiNaC::ex& p, GiNaC::numeric* leading) const {
  const auto ls = levels(p, *symbols_, scaling_);
  if (ls.empty()) {
    if (leading) *leading = 0;
    return 0;
  }
  if (leading) *leading = ls.front().first;
  GiNaC::ex kept = 0;
  for (std::size_t k = 0; k < ls.size() && k <= static_cast<std::size_t>(order_); ++k) kept += ls[k].second;
  const GiNaC::ex stripped = strip_positive_factors(kept, *symbols_);
  if (!GiNaC::is_a<GiNaC::numeric>(stripped)) return stripped;
  // A constant says "always" (or "never"); the dominant terms say why (K₁₄ > 0).
  GiNaC::numeric content = 0, denominators = 1;
  for (const detail::Term& t : detail::terms(kept)) {
    content = GiNaC::gcd(content, t.coefficient.numer());
    denominators = GiNaC::lcm(denominators, t.coefficient.denom());
  }
  return GiNaC::expand(kept * denominators / content);
}

bool Rules::nonnegative_terms(const detail::Poly& p) const {
  for (std::size_t t = 0; t < p.size(); ++t) {
    if (cln::minusp(p.coefficient(t))) return false;
    for (int k : couplings_)
      if (p.exponent(t, k) % 2) return false;
  }
  return true;
}

bool Rules::positive_terms(const detail::Poly& p) const {
  if (p.is_zero() || !nonnegative_terms(p)) return false;
  for (std::size_t t = 0; t < p.size(); ++t) {
    bool free = true;
    for (int k : couplings_) free = free && p.exponent(t, k) == 0;
    if (free) return true;
  }
  return false;
}

Verdict Rules::verdict(const detail::Poly& p, Relation rel) const {
  if (p.is_zero()) return rel == Relation::GreaterEqual ? Verdict::Always : Verdict::Never;
  if (rel == Relation::Greater ? positive_terms(p) : nonnegative_terms(p)) return Verdict::Always;
  if (rel == Relation::Greater ? nonnegative_terms(-p) : positive_terms(-p)) return Verdict::Never;
  return Verdict::Depends;
}

detail::Poly Rules::strip(const detail::Poly& p, GiNaC::ex* removed) const {
  const Symbols& sy = sy_;
  if (p.is_zero() || p.size() <= max_factor_terms) {  // small: the factorisation too (strip_positive_factors)
    GiNaC::ex gone = 1;
    const detail::Poly out = detail::Poly::from_ex(strip_positive_factors(p.to_ex(sy), sy, &gone), sy);
    if (removed) *removed = gone;
    return out;
  }
  // Large: the positive content and the monomial of positive symbols common to every term.
  detail::Poly g;
  detail::Poly rest = without_positive_monomial(p, g);
  if (removed) *removed = g.to_ex(sy);
  return rest;
}

detail::Poly Rules::without_positive_monomial(const detail::Poly& p, detail::Poly& g) const {
  const cln::cl_I content = p.content();
  std::vector<int> common = p.common_exponents();
  for (int k : couplings_) common[static_cast<std::size_t>(k)] = 0;
  g = detail::Poly::constant(p.vars(), content);
  for (int k = 0; k < p.vars(); ++k)
    if (common[static_cast<std::size_t>(k)]) g = g.times_power(k, common[static_cast<std::size_t>(k)]);
  return p.divided(content).divided_by_monomial(common);
}

detail::Poly Rules::dominant(const detail::Poly& p, GiNaC::numeric* leading) const {
  if (p.is_zero()) {
    if (leading) *leading = 0;
    return p;
  }
  std::vector<cln::cl_RA> weight(p.size(), 0);
  std::vector<cln::cl_RA> levels;
  for (std::size_t t = 0; t < p.size(); ++t) {
    weight[t] = term_order(p, t);
    if (std::none_of(levels.begin(), levels.end(), [&](const cln::cl_RA& w) { return w == weight[t]; })) levels.push_back(weight[t]);
  }
  std::sort(levels.begin(), levels.end(), [](const cln::cl_RA& x, const cln::cl_RA& y) { return x < y; });
  if (leading) *leading = GiNaC::numeric(levels.front());
  const cln::cl_RA& last = levels[std::min(levels.size() - 1, static_cast<std::size_t>(deriver_.order()))];
  std::vector<std::size_t> terms;
  for (std::size_t t = 0; t < p.size(); ++t)
    if (weight[t] <= last) terms.push_back(t);
  if (terms.size() == p.size()) return p;  // every term kept: p is already stripped (make_condition)
  const detail::Poly kept = p.subset(terms);
  const detail::Poly stripped = strip(kept);
  if (!stripped.is_constant()) return stripped;
  // A constant says "always" (or "never"); the dominant terms say why (K₁₄ > 0).
  return kept.divided(kept.content());
}

namespace {

using detail::Poly;

/// Whether \p q has terms of both signs.
bool mixed(const Poly& q) {
  bool plus = false, minus = false;
  for (std::size_t t = 0; t < q.size(); ++t) (cln::minusp(q.coefficient(t)) ? minus : plus) = true;
  return plus && minus;
}

/// T = Q S + R by the symbol y of S in which S is y + (terms free of y), the
/// y giving the fewest terms (terms of both signs in R count one more);
/// without such a y, Q = 0 and R = T.
std::pair<Poly, Poly> divide_by(const Poly& T, const Poly& S) {
  const int vars = T.vars();
  std::pair<Poly, Poly> best{Poly(vars), T};
  const Poly one = Poly::constant(vars, 1);
  for (int y = 0; y < vars; ++y) {
    if (S.degree(y) != 1 || S.coefficient_of(y, 1) != one) continue;
    const Poly rest = S.coefficient_of(y, 0);
    Poly Q(vars), R = T;
    for (int d = R.degree(y); d >= 1; d = R.degree(y)) {
      const Poly lead = R.coefficient_of(y, d).times_power(y, d - 1);  // L y^(d−1)
      Q += lead;
      R -= lead.times_power(y, 1) + lead * rest;
    }
    if (Q.size() + R.size() + mixed(R) < best.first.size() + best.second.size() + mixed(best.second)) best = {std::move(Q), std::move(R)};
  }
  return best;
}

/// A grouped form pays when Q and R together have at most this share of P's terms.
constexpr double grouped_gain = 0.6;

}  // namespace

std::optional<Readable> Rules::readable(const detail::Poly& p, Naming& naming) const {
  if (p.size() > max_readable_terms) return std::nullopt;  // neither shape makes such a polynomial readable; it costs
  const Symbols& sy = sy_;
  const int vars = p.vars();
  // Isolated: the coupling whose coefficient has a proved sign and that gives the fewest terms.
  struct Choice {
    int x = 0, sigma = 1;
    Poly g, S, Q, R;
    std::size_t cost = 0;
  };
  std::optional<Choice> best;
  for (int x : couplings_) {
    if (p.degree(x) != 1) continue;
    const Poly A = p.coefficient_of(x, 1);
    Choice c;
    c.x = x;
    c.sigma = cln::minusp(A.coefficient(0)) ? -1 : 1;
    const Poly positive = c.sigma < 0 ? -A : A;
    if (!positive_terms(positive)) continue;  // the sign of x's coefficient is not proved
    // g: the content and the monomial of positive symbols common to the coefficient's terms.
    c.S = without_positive_monomial(positive, c.g);
    const Poly T = -p.coefficient_of(x, 0);  // P = σ g S x − T
    if (c.S.is_constant()) {
      // Without a division the isolated form pays only when the other side has one sign
      // (−α₂ > 2m₁ + K₁₂ + K₁₃); else the two-sided form reads better (m₁ < K₁₄ + α₂).
      if (mixed(T)) continue;
      c.Q = T;
      c.R = Poly(vars);
    } else {
      std::tie(c.Q, c.R) = divide_by(T, c.S);
    }
    c.cost = c.Q.size() + c.R.size() + (c.S.is_constant() ? 0 : c.S.size());
    if (!best || c.cost < best->cost) best = std::move(c);
  }
  if (best) {
    const Choice& c = *best;
    const Poly x = Poly::variable(vars, c.x);
    if ((c.g * c.S * x).scaled(c.sigma) - (c.Q * c.S + c.R) != p)
      throw std::logic_error("Deriver::derive(): the isolated form of a condition is not the condition (P != sigma g S x - (Q S + R))");
    Readable r;
    r.subject = (c.g * x).scaled(c.sigma).to_ex(sy);
    r.quotient = c.Q.to_ex(sy);
    r.remainder = c.R.to_ex(sy);
    if (!c.S.is_constant()) r.named = naming.name(c.S);
    return r;
  }
  // Grouped: by a part already named, else by a diagonal entry of ZᵀAZ.
  std::optional<std::pair<Poly, std::pair<Poly, Poly>>> group;
  for (const std::vector<Poly>* list : {&naming.named, &naming.candidates})
    for (const Poly& S : *list) {
      auto qr = divide_by(p, S);
      if (qr.first.is_zero() || static_cast<double>(qr.first.size() + qr.second.size()) > grouped_gain * static_cast<double>(p.size())) continue;
      if (!group || qr.first.size() + qr.second.size() < group->second.first.size() + group->second.second.size()) group.emplace(S, std::move(qr));
    }
  if (!group) return std::nullopt;
  const auto& [S, qr] = *group;
  if (qr.first * S + qr.second != p)
    throw std::logic_error("Deriver::derive(): the grouped form of a condition is not the condition (P != Q S + R)");
  Readable r;
  r.quotient = qr.first.to_ex(sy);
  r.remainder = qr.second.to_ex(sy);
  r.named = naming.name(S);
  return r;
}

GiNaC::numeric Rules::epsilon_order(const detail::Poly& p) const {
  if (p.is_zero()) throw std::invalid_argument("epsilon_order(): the zero polynomial has no order");
  cln::cl_RA lowest = 0;
  for (std::size_t t = 0; t < p.size(); ++t) {
    const cln::cl_RA w = term_order(p, t);
    if (t == 0 || w < lowest) lowest = w;
  }
  return GiNaC::numeric(lowest);
}

cln::cl_RA Rules::term_order(const detail::Poly& p, std::size_t t) const {
  cln::cl_RA w = 0;
  for (const int k : ordered_) {
    if (k >= p.vars()) break;
    if (const int e = p.exponent(t, k)) w = w + orders_[static_cast<std::size_t>(k)] * e;
  }
  return w;
}

namespace {

/// Which multipliers l_ij of the elimination of the k×k matrix \p B in
/// \p order are structurally nonzero (Elimination): B_ij ≠ 0, or fill-in
/// through a cluster eliminated before j.
std::vector<char> multipliers(const std::vector<detail::Poly>& B, int k, const std::vector<int>& order) {
  const auto K = static_cast<std::size_t>(k);
  std::vector<char> present(K * K, 0);
  for (std::size_t a = 0; a < K; ++a) {
    const auto j = static_cast<std::size_t>(order[a]);
    for (std::size_t b = a + 1; b < K; ++b) {
      const auto i = static_cast<std::size_t>(order[b]);
      bool nonzero = !B[i * K + j].is_zero();
      for (std::size_t c = 0; c < a && !nonzero; ++c) {
        const auto t = static_cast<std::size_t>(order[c]);
        nonzero = present[i * K + t] && present[j * K + t];
      }
      present[i * K + j] = nonzero;
    }
  }
  return present;
}

/// The cluster velocities of the elimination (Elimination) with b_ij = \p B
/// and r_i = \p r, numbers modulo the prime ℓ = 2⁶¹ − 1; nothing when a
/// pivot vanishes modulo ℓ.
std::optional<std::vector<std::uint64_t>> eliminated_velocities(const std::vector<std::uint64_t>& B, const std::vector<std::uint64_t>& r, int k,
                                                                const std::vector<char>& present, const std::vector<int>& order) {
  namespace m = detail::mod61;
  const auto K = static_cast<std::size_t>(k);
  std::vector<std::uint64_t> p(K), y(K), V(K), l(K * K, 0);
  for (std::size_t a = 0; a < K; ++a) {
    const auto j = static_cast<std::size_t>(order[a]);
    std::uint64_t pj = B[j * K + j], yj = r[j];
    for (std::size_t c = 0; c < a; ++c) {
      const auto t = static_cast<std::size_t>(order[c]);
      if (!present[j * K + t]) continue;
      pj = m::subtract(pj, m::multiply(m::multiply(l[j * K + t], l[j * K + t]), p[t]));
      yj = m::subtract(yj, m::multiply(l[j * K + t], y[t]));
    }
    if (pj == 0) return std::nullopt;
    p[j] = pj;
    y[j] = yj;
    const std::uint64_t inverse = m::inverse(pj);
    for (std::size_t b = a + 1; b < K; ++b) {
      const auto i = static_cast<std::size_t>(order[b]);
      if (!present[i * K + j]) continue;
      std::uint64_t v = B[i * K + j];
      for (std::size_t c = 0; c < a; ++c) {
        const auto t = static_cast<std::size_t>(order[c]);
        if (present[i * K + t] && present[j * K + t]) v = m::subtract(v, m::multiply(m::multiply(l[i * K + t], l[j * K + t]), p[t]));
      }
      l[i * K + j] = m::multiply(v, inverse);
    }
  }
  for (std::size_t a = K; a-- > 0;) {
    const auto j = static_cast<std::size_t>(order[a]);
    V[j] = m::multiply(y[j], m::inverse(p[j]));
    for (std::size_t b = a + 1; b < K; ++b) {
      const auto i = static_cast<std::size_t>(order[b]);
      if (present[i * K + j]) V[j] = m::subtract(V[j], m::multiply(l[i * K + j], V[i]));
    }
  }
  return V;
}

/// Terms of an expanded polynomial.
std::size_t terms_of(const GiNaC::ex& p) { return GiNaC::is_a<GiNaC::add>(p) ? p.nops() : 1; }

}  // namespace

Condition Rules::make_condition(ConditionKind kind, const std::string& about, Relation relation, const detail::Poly& raw,
                                  const detail::Denominator& determinant, const std::vector<const detail::Poly*>& parts,
                                  Naming& naming, const EliminatedForm* eliminated, bool limit, const bool* coprime, Forms forms) const {
  const Symbols& sy = sy_;
  Condition c;
  c.kind = kind;
  c.about = about;
  c.relation = relation;
  // raw / det(ZᵀAZ) in lowest terms (at most one numer_denom per condition).
  const detail::Denominator::Reduced reduced = determinant.lowest_terms(raw, false, coprime);
  const GiNaC::ex& denominator = reduced.denominator;
  int sign = 1;
  ConditionForm form;
  if (GiNaC::is_a<GiNaC::numeric>(denominator)) {
    sign = GiNaC::ex_to<GiNaC::numeric>(denominator).csgn();
    c.proof = "the denominator is a positive number";
    if (!determinant.poly().is_constant())
      c.proof = "det(Z^T A Z) cancels: no denominator is left";
  } else if (GiNaC::ex q; reduced.whole || GiNaC::divide(determinant.value(), denominator, q)) {
    sign = reduced.whole ? determinant.sign_at_reference() : detail::evaluate(denominator, reference_point(sy)).csgn();
    if (sign == 0) throw std::logic_error("Deriver::derive(): a factor of det(Z^T A Z) vanishes at the reference point");
    c.proof = std::string("the denominator divides det(Z^T A Z), which is > 0 (Z^T A Z is positive definite: A = diag(m) + D^T M D ") +
              "with m > 0 and M positive semi-definite, Z the cluster incidence of full rank); a factor of a polynomial that never " +
              "vanishes on the connected set of admissible parameters keeps one sign there: " + (sign > 0 ? "+" : "-") +
              ", its sign at m = K = a = 1, couplings = 0";
  } else if (certainly_positive(denominator, sy)) {
    c.proof = "the denominator has only positive terms in positive parameters";
  } else {
    c.proof = "sign not proved: the denominator " + show(denominator) + " is kept";
  }
  const bool proved = c.proof.rfind("sign not proved", 0) != 0;
  const detail::Poly numerator =
      (reduced.whole ? raw.divided(reduced.content) : detail::Poly::from_ex(reduced.numerator, sy)).scaled(sign);
  // The form's numerator, as a polynomial (positive factors removed when the denominator's sign is proved).
  const detail::Poly kept = proved ? strip(numerator, &c.removed) : numerator;
  // form.numerator (kept in GiNaC): at the end, once it is known whether it is written through the elimination.
  form.denominator = proved ? GiNaC::ex(1) : GiNaC::expand(denominator);
  form.verdict = proved ? verdict(kept, relation) : Verdict::Depends;
  if (form.verdict == Verdict::Depends && proved) form.readable = readable(kept, naming);
  if (sy.obstacle() == Obstacle::Finite) {
    // m_n → ∞: for m_n large the sign is that of the leading coefficient in m_n.
    const GiNaC::ex& mn = sy.mass(sy.bodies());
    c.finite = form;
    ConditionForm limit;
    const detail::Poly lead = kept.is_zero() ? kept : strip(kept.leading_coefficient(sy.info(mn).rank));
    limit.numerator = lead.to_ex(sy);
    limit.denominator = proved ? GiNaC::ex(1) : GiNaC::expand(form.denominator.lcoeff(mn));
    limit.verdict = proved ? verdict(lead, relation) : Verdict::Depends;
    if (limit.verdict == Verdict::Depends && proved) limit.readable = readable(lead, naming);
    c.exact = limit;
  } else {
    c.exact = form;
  }
  // Asymptotic form of the condition of the regime: with a finite obstacle
  // m_n is itself an ε-order (Scaling::paper: m_n ~ 1/ε), so the dominant
  // balance is taken in the condition with m_n, not in its limit m_n → ∞
  // (either way the regime's numerator is `kept`).  An unproved denominator
  // gets its own dominant balance.
  ConditionForm& regime = c.finite ? *c.finite : c.exact;
  c.asymptotic.denominator = regime.denominator.is_equal(1) ? GiNaC::ex(1) : deriver_.asymptotic(regime.denominator);
  const detail::Poly dominant_balance = dominant(kept, &c.leading_order);
  const bool same = dominant_balance == kept && regime.sign_proved();  // every term is of the leading order: the regime's form again
  c.asymptotic.verdict = c.asymptotic.sign_proved() ? (same ? regime.verdict : verdict(dominant_balance, relation)) : Verdict::Depends;
  if (c.asymptotic.verdict == Verdict::Depends && c.asymptotic.sign_proved())
    c.asymptotic.readable = same ? regime.readable : readable(dominant_balance, naming);
  c.orders_kept = 1 + deriver_.order();
  // Long forms through the case's elimination (the expanded ones stay).
  // (\p terms: the form's numerator's, kept or dominant_balance: a
  // polynomial of k ≥ 1 terms is a GiNaC sum of k, and 0, one of 1, is no
  // form that depends on the parameters.)
  if (eliminated) {
    auto is_long = [&](const ConditionForm& f, std::size_t terms, std::size_t most) {
      if (!f.sign_proved() || f.verdict != Verdict::Depends || terms <= most) return false;
      if (!f.readable) return true;
      const Readable& r = *f.readable;
      const std::size_t named = r.named ? naming.named[static_cast<std::size_t>(r.named - 1)].size() : 0;
      return terms_of(r.quotient) + terms_of(r.remainder) + named > most;
    };
    if (is_long(regime, kept.size(), max_inline_exact_terms)) regime.eliminated = *eliminated;
    if (limit && is_long(c.asymptotic, same ? kept.size() : dominant_balance.size(), max_inline_terms)) {
      c.asymptotic.eliminated = *eliminated;
      c.asymptotic.eliminated->limit = true;
    }
  }
  // The numerators in GiNaC: every one, or (Forms::Printed) those a report
  // writes out, not through the elimination.
  const bool all = forms == Forms::All;
  if (all || !regime.eliminated || (same && !c.asymptotic.eliminated)) regime.numerator = kept.to_ex(sy);
  if (all || !c.asymptotic.eliminated) c.asymptotic.numerator = same ? regime.numerator : dominant_balance.to_ex(sy);
  // Did the leading orders of the parts cancel (the paper's superball condition)?
  if (!raw.is_zero()) {
    const GiNaC::numeric whole = epsilon_order(raw);
    GiNaC::numeric lowest = whole;
    for (const detail::Poly* p : parts) {
      if (p->is_zero()) continue;
      const GiNaC::numeric o = epsilon_order(*p);
      if (o < lowest) lowest = o;
    }
    c.descended = whole - lowest;
  }
  return c;
}

namespace {

std::vector<Condition> psd_conditions(const Deriver& deriver) {
  const Symbols& sy = deriver.symbols();
  const std::vector<Pair> pairs = sy.pattern().pairs();
  const int v = static_cast<int>(pairs.size());
  auto index = [&](const Pair& p) { return static_cast<int>(std::find(pairs.begin(), pairs.end(), p) - pairs.begin()); };
  std::vector<std::vector<int>> adjacent(static_cast<std::size_t>(v));
  for (const auto& [p, q] : sy.pattern().couplings) {
    adjacent[index(p)].push_back(index(q));
    adjacent[index(q)].push_back(index(p));
  }
  std::vector<std::vector<int>> sets;
  constexpr std::size_t cap = 4096;
  if (!connected_sets(adjacent, cap, sets))
    throw std::invalid_argument("Deriver::Deriver(): the coupling graph has more than " + std::to_string(cap) +
                                " connected sets of pairs; too many principal minors to list");
  std::sort(sets.begin(), sets.end(), [](const auto& x, const auto& y) { return x.size() != y.size() ? x.size() < y.size() : x < y; });
  std::vector<Condition> out;
  for (const auto& set : sets) {
    const auto k = static_cast<unsigned>(set.size());
    GiNaC::matrix m(k, k);
    std::string about;
    for (unsigned r = 0; r < k; ++r) {
      about += (about.empty() ? "" : ",") + pairs[static_cast<std::size_t>(set[r])].name();
      for (unsigned s = 0; s < k; ++s) m(r, s) = sy.entry(pairs[static_cast<std::size_t>(set[r])], pairs[static_cast<std::size_t>(set[s])]);
    }
    const GiNaC::ex minor = detail::determinant(m);
    const Relation rel = k == 1 ? Relation::Greater : Relation::GreaterEqual;
    if (minor.is_zero()) continue;  // an undeclared K alone: 0 >= 0
    Condition c;
    c.kind = ConditionKind::Psd;
    c.about = about;
    c.relation = rel;
    c.exact.numerator = minor;
    c.exact.verdict = verdict_of(minor, rel, sy);
    c.proof = k == 1 ? "K is a positive symbol (the paper's K > 0)" : "principal minor of M on the pairs " + about + ", no denominator";
    c.asymptotic.numerator = deriver.asymptotic(minor, &c.leading_order);
    c.asymptotic.verdict = verdict_of(c.asymptotic.numerator, rel, sy);
    c.orders_kept = 1 + deriver.order();
    if (sy.obstacle() == Obstacle::Finite) c.finite = c.exact;
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------
// Deriver::derive(), phase by phase: the clusters of the case, its equations
// as polynomials and the reduced system, the solution by Cramer's rule, the
// results stored in lowest terms, the check that they solve the equations,
// the conditions as linear forms in the cluster velocities, the elimination
// of a long case, and the case's conditions, named parts and verdict.
namespace {

using detail::Poly;

/// The clusters of a case: bodies joined by closed contacts.
struct Clusters {
  std::vector<int> of;   ///< the cluster of each body, 0-based from the top
  std::vector<int> top;  ///< the top body of each cluster
  int fixed = -1;        ///< the cluster that stays at rest (the fixed obstacle's), else −1
  int free = 0;          ///< k: the free clusters are 0..k−1 (the fixed one is the last)
};

/// Phase 1: the clusters of \p closed; with a \p fixed obstacle the bottom
/// cluster does not move (velocity u_n = 0).
Clusters clusters_of(const ContactSet& closed, bool fixed) {
  const int n = closed.bodies();
  Clusters c;
  c.of.assign(static_cast<std::size_t>(n), 0);
  c.top.assign(1, 0);
  for (int i = 1; i < n; ++i) {
    if (!closed.closed(i - 1)) c.top.push_back(i);
    c.of[static_cast<std::size_t>(i)] = static_cast<int>(c.top.size()) - 1;
  }
  const int clusters = static_cast<int>(c.top.size());
  c.fixed = fixed ? c.of[static_cast<std::size_t>(n - 1)] : -1;
  c.free = fixed ? clusters - 1 : clusters;
  return c;
}

/// The equations of a case as polynomials (poly.hpp).
struct System {
  const Symbols* sy = nullptr;
  int n = 0, vars = 0, free_bodies = 0;
  bool fixed = false;  ///< the obstacle is fixed (m_n = ∞)
  Clusters clusters;
  std::vector<Poly> K;       ///< DᵀMD, n×n row-major (declared entries only)
  std::vector<Poly> m, u;    ///< the masses (0 for a fixed obstacle) and the velocities before
  std::vector<Poly> B, rhs;  ///< the reduced system (ZᵀAZ) V = Zᵀb over the free clusters: k×k row-major, k

  std::size_t size() const { return static_cast<std::size_t>(n); }
  std::size_t k() const { return static_cast<std::size_t>(clusters.free); }
  Poly symbol(const GiNaC::ex& x) const { return Poly::variable(vars, sy->info(x).rank); }
  const Poly& Kij(int i, int j) const { return K[static_cast<std::size_t>(i) * size() + static_cast<std::size_t>(j)]; }
};

/// Phase 2: K = DᵀMD, the masses and the velocities before of the case
/// \p closed, and its reduced system (ZᵀAZ) V = Zᵀb over the free clusters.
System system_of(const Symbols& sy, const ContactSet& closed) {
  System s;
  s.sy = &sy;
  s.n = sy.bodies();
  s.fixed = sy.obstacle() == Obstacle::Infinite;
  s.free_bodies = s.fixed ? s.n - 1 : s.n;
  s.vars = static_cast<int>(sy.all().size());
  s.clusters = clusters_of(closed, s.fixed);
  const int n = s.n, vars = s.vars;
  const std::size_t N = s.size();
  s.K.assign(N * N, Poly(vars));
  auto add_outer = [&](const Pair& p, const Pair& q, const Poly& v) {
    const std::size_t pi = p.i - 1, pj = p.j - 1, qi = q.i - 1, qj = q.j - 1;
    s.K[pi * N + qi] += v;
    s.K[pi * N + qj] -= v;
    s.K[pj * N + qi] -= v;
    s.K[pj * N + qj] += v;
  };
  for (const Pair& p : sy.pattern().diagonal) add_outer(p, p, s.symbol(sy.diagonal(p)));
  for (const auto& [p, q] : sy.pattern().couplings) {
    add_outer(p, q, s.symbol(sy.coupling(p, q)));
    add_outer(q, p, s.symbol(sy.coupling(p, q)));
  }
  s.m.assign(N, Poly(vars));
  s.u.assign(N, Poly(vars));
  for (int i = 0; i < s.free_bodies; ++i) s.m[static_cast<std::size_t>(i)] = s.symbol(sy.mass(i + 1));
  for (int i = 0; i + 1 < n; ++i) s.u[static_cast<std::size_t>(i)] = -s.symbol(sy.fall_speed());
  const std::size_t Kc = s.k();
  const std::vector<int>& cluster = s.clusters.of;
  s.B.assign(Kc * Kc, Poly(vars));
  s.rhs.assign(Kc, Poly(vars));
  for (int i = 0; i < s.free_bodies; ++i) {
    const int ci = cluster[static_cast<std::size_t>(i)];
    if (ci == s.clusters.fixed) continue;
    Poly r = s.m[static_cast<std::size_t>(i)] * s.u[static_cast<std::size_t>(i)];
    for (int j = 0; j < n; ++j) {
      if (s.Kij(i, j).is_zero()) {
        if (i == j) s.B[static_cast<std::size_t>(ci) * Kc + static_cast<std::size_t>(ci)] += s.m[static_cast<std::size_t>(i)];
        continue;
      }
      r -= s.Kij(i, j) * s.u[static_cast<std::size_t>(j)];
      const int cj = cluster[static_cast<std::size_t>(j)];
      if (cj == s.clusters.fixed)
        r -= s.Kij(i, j) * s.u[N - 1];  // W_j = u_n is known
      else
        s.B[static_cast<std::size_t>(ci) * Kc + static_cast<std::size_t>(cj)] += i == j ? s.Kij(i, j) + s.m[static_cast<std::size_t>(i)] : s.Kij(i, j);
    }
    s.rhs[static_cast<std::size_t>(ci)] += r;
  }
  return s;
}

/// Row i of the equations of motion times D, without the reactions, for
/// velocities times D \p V: its inertia part m_i(V_i − u_i D) ...
Poly inertia_of(const System& s, int i, const std::vector<Poly>& V, const std::vector<Poly>& uD) {
  return s.m[static_cast<std::size_t>(i)] * (V[static_cast<std::size_t>(i)] - uD[static_cast<std::size_t>(i)]);
}
/// ... and its dissipation part Σ_j K_ij (V_j + u_j D).
Poly dissipation_of(const System& s, int i, const std::vector<Poly>& V, const std::vector<Poly>& uD) {
  Poly r(s.vars);
  for (int j = 0; j < s.n; ++j)
    if (!s.Kij(i, j).is_zero()) r += s.Kij(i, j) * (V[static_cast<std::size_t>(j)] + uD[static_cast<std::size_t>(j)]);
  return r;
}

/// The solution of a case times D = det(ZᵀAZ).
struct Solution {
  Poly D;
  Poly aD;               ///< a · D
  std::vector<Poly> uD;  ///< u_j D: the velocities before times D
  std::vector<Poly> Vh;  ///< D · V_c: the free clusters' velocities after
  std::vector<Poly> Wh;  ///< D · W_i: each body's velocity after
  std::vector<Poly> Lh, inertia, dissipation;  ///< λ_c · D on a closed contact c, and its inertia and dissipation parts
};

/// Phase 3: the velocities after by Cramer's rule, fraction-free
/// (V_c = det(B with column c replaced by rhs) / D), and λ_c · D on the
/// closed contacts as running sums from the cluster's top body.  Throws
/// std::logic_error when the reduced system is singular.
Solution solve(const System& s, const ContactSet& closed) {
  const int n = s.n, vars = s.vars, k = s.clusters.free;
  const std::size_t N = s.size(), Kc = s.k();
  const std::vector<int>& cluster = s.clusters.of;
  Solution x;
  x.D = detail::determinant(s.B, k, vars);
  if (x.D.is_zero()) throw std::logic_error("Deriver::derive(): the reduced system of case " + closed.to_string() + " is singular");
  x.aD = s.symbol(s.sy->fall_speed()) * x.D;
  x.uD.assign(N, Poly(vars));
  for (std::size_t j = 0; j < N; ++j) x.uD[j] = s.u[j] * x.D;
  x.Wh.assign(N, Poly(vars));
  x.Vh.assign(Kc, Poly(vars));
  for (std::size_t c = 0; c < Kc; ++c) {
    std::vector<Poly> Bc = s.B;
    for (std::size_t r = 0; r < Kc; ++r) Bc[r * Kc + c] = s.rhs[r];
    x.Vh[c] = detail::determinant(Bc, k, vars);
  }
  for (int i = 0; i < n; ++i) {
    const int ci = cluster[static_cast<std::size_t>(i)];
    x.Wh[static_cast<std::size_t>(i)] = ci == s.clusters.fixed ? x.uD[N - 1] : x.Vh[static_cast<std::size_t>(ci)];
  }
  x.Lh.assign(N - 1, Poly(vars));
  x.inertia.assign(N - 1, Poly(vars));
  x.dissipation.assign(N - 1, Poly(vars));
  for (int c = 0; c + 1 < n; ++c) {
    if (!closed.closed(c)) continue;
    Poly in(vars), dis(vars);
    for (int i = s.clusters.top[static_cast<std::size_t>(cluster[static_cast<std::size_t>(c)])]; i <= c; ++i) {
      in += inertia_of(s, i, x.Wh, x.uD);
      dis += dissipation_of(s, i, x.Wh, x.uD);
    }
    x.inertia[static_cast<std::size_t>(c)] = in;
    x.dissipation[static_cast<std::size_t>(c)] = dis;
    x.Lh[static_cast<std::size_t>(c)] = in + dis;
  }
  return x;
}

/// A result stored in lowest terms, with how it was reduced (content, sign)
/// so that the check can multiply it back by D.
struct Stored {
  Fraction fraction;
  detail::Denominator::Reduced reduced;
  int sign = 1;
  bool built = true;  ///< fraction is in GiNaC (else only its terms are set: Forms::Printed)
};

/// s.fraction from s.reduced, negated where s.sign < 0, with its terms.
void set_fraction(Stored& s) {
  s.fraction = {s.reduced.numerator, s.reduced.denominator};
  if (s.sign < 0) s.fraction = {GiNaC::expand(-s.fraction.numerator), GiNaC::expand(-s.fraction.denominator)};
  s.fraction.terms = terms_of(s.fraction.numerator);
  s.built = true;
}

/// The fraction of \p s, whole (numerator / content over D / content),
/// in GiNaC from its \p numerator.
void build(Stored& s, const Poly& numerator, const Symbols& sy) {
  s.reduced.numerator = numerator.divided(s.reduced.content).to_ex(sy);
  set_fraction(s);
}

/// Phase 4: \p numerator / D in lowest terms, its denominator positive at
/// the reference point \p ref.  With \p forms Printed, a numerator of more
/// than max_inline_exact_terms terms that shares no factor with D is left
/// unbuilt (Stored::built false; build() makes it): a report writes it
/// through the case's elimination.
Stored normalise(const Poly& numerator, const detail::Denominator& denominator, const GiNaC::exmap& ref, const bool* coprime, Forms forms) {
  Stored s;
  const bool leave = forms == Forms::Printed && numerator.size() > max_inline_exact_terms;
  s.reduced = denominator.lowest_terms(numerator, !leave, coprime);
  const int sign = s.reduced.whole ? denominator.sign_at_reference() : detail::evaluate(s.reduced.denominator, ref).csgn();
  s.sign = sign < 0 ? -1 : 1;
  if (leave && s.reduced.whole) {
    s.fraction = {0, 0};
    s.fraction.terms = numerator.size();
    s.built = false;
    return s;
  }
  set_fraction(s);
  return s;
}

/// Phase 5, its first half: the polynomials Wh and λD satisfy the unreduced
/// equations exactly.  Everything is multiplied by D = det(ZᵀAZ) ≠ 0 first,
/// so each identity is between polynomials, compared term by term.  Throws
/// std::logic_error on a failure.
/// \p piece of \p pieces (Deriver::prepare()): the equations of the free
/// bodies i ≡ piece (mod pieces), the contacts and the obstacle in piece 0.
void check_equations(const System& s, const ContactSet& closed, const Solution& x, int piece = 0, int pieces = 1) {
  const Symbols& sy = *s.sy;
  const int n = s.n;
  const std::size_t N = s.size();
  const std::vector<Poly>& W = x.Wh;
  const std::vector<Poly>& L = x.Lh;
  for (int i = piece; i < s.free_bodies; i += pieces) {
    Poly r = inertia_of(s, i, W, x.uD) + dissipation_of(s, i, W, x.uD);
    if (i + 1 < n) r -= L[static_cast<std::size_t>(i)];
    if (i > 0) r += L[static_cast<std::size_t>(i - 1)];
    if (!r.is_zero())
      throw std::logic_error("Deriver::derive(): case " + closed.to_string() + ": the equation of motion of body " + std::to_string(i + 1) +
                             " is not satisfied by the solution (residual " + show(GiNaC::normal(r.to_ex(sy) / x.D.to_ex(sy))) + ")");
  }
  if (piece != 0) return;
  for (int c = 0; c + 1 < n; ++c)
    if (closed.closed(c) && W[static_cast<std::size_t>(c)] != W[static_cast<std::size_t>(c + 1)])
      throw std::logic_error("Deriver::derive(): case " + closed.to_string() + ": contact " + Pair{c + 1, c + 2}.name() + " does not stay closed");
  if (s.fixed && W[N - 1] != x.uD[N - 1]) throw std::logic_error("Deriver::derive(): the fixed obstacle moves");
}

/// Phase 5, its second half: the stored fractions times D are the
/// polynomials Wh and −λD (check_equations() holds for these), read back
/// from GiNaC.  Throws std::logic_error on a failure; returns what was
/// checked, in words (Derivation::check).
std::string check_solution(const System& s, const ContactSet& closed, const Solution& x, const detail::Denominator& denominator,
                           const std::vector<Stored>& velocities, const std::vector<Stored>& reactions) {
  const Symbols& sy = *s.sy;
  const int n = s.n;
  auto times_D = [&](const Stored& st, const char* what) {
    const Fraction& f = st.fraction;
    if (st.reduced.whole) {  // numerator = ±P / content, denominator = ±D / content
      const cln::cl_I c = st.reduced.content * st.sign;
      // The denominator is usually D's own expression (content 1, sign +): no need to read it back.
      const bool own = c == 1 && f.denominator.is_equal(denominator.value());
      if (!own && Poly::from_ex(f.denominator, sy).scaled(c) != x.D)
        throw std::logic_error(std::string("Deriver::derive(): the denominator of ") + what + " is not det(Z^T A Z) over its content");
      return Poly::from_ex(f.numerator, sy).scaled(c);
    }
    GiNaC::ex q = 1;
    if (!f.denominator.is_equal(denominator.value()) && !GiNaC::divide(denominator.value(), f.denominator, q))
      throw std::logic_error(std::string("Deriver::derive(): the denominator of ") + what + " does not divide det(Z^T A Z)");
    return Poly::from_ex(GiNaC::expand(f.numerator * q), sy);
  };
  // A result left unbuilt (Forms::Printed) is its polynomial, which check_equations() checked.
  for (int i = 0; i < n; ++i)
    if (velocities[static_cast<std::size_t>(i)].built && times_D(velocities[static_cast<std::size_t>(i)], "a velocity") != x.Wh[static_cast<std::size_t>(i)])
      throw std::logic_error("Deriver::derive(): case " + closed.to_string() + ": the velocity of body " + std::to_string(i + 1) +
                             " as stored is not the solution");
  for (int c = 0; c + 1 < n; ++c)
    if (closed.closed(c) && reactions[static_cast<std::size_t>(c)].built &&
        -times_D(reactions[static_cast<std::size_t>(c)], "a reaction") != x.Lh[static_cast<std::size_t>(c)])
      throw std::logic_error("Deriver::derive(): case " + closed.to_string() + ": the reaction on contact " + Pair{c + 1, c + 2}.name() +
                             " as stored is not the solution");
  return "substituted back: the " + std::to_string(s.free_bodies) +
         " equations of motion with the reactions hold exactly (times det(Z^T A Z) they expand to 0), closed contacts keep equal "
         "velocities" + std::string(s.fixed ? ", the obstacle stays at rest" : "");
}

/// A linear form Σ_c coefficients_c V_c + constant in the cluster velocities.
struct Linear {
  std::vector<Poly> coefficients;
  Poly constant;
};

/// A condition of the case before its forms are made: raw = Σ_c ℓ_c Vh_c +
/// β D (the value times D), so that raw / D = Σ_c ℓ_c V_c + β (`form`).
struct Pending {
  ConditionKind kind;
  std::string about;
  Relation relation;
  Poly raw;
  std::vector<const Poly*> parts;  ///< the parts whose leading orders may cancel (into x of phase 3)
  Linear form;
};

/// The conditions of a case (paper §4) and the reactions as linear forms.
struct Conditions {
  std::vector<Pending> pending;        ///< superball, each open contact's opening, each closed contact's reaction
  std::vector<Linear> reaction_forms;  ///< −λ_c on each contact (zero on open ones)
};

/// Phase 6: the superball condition, the open contacts' openings and the
/// closed contacts' reactions, each as its value times D and as a linear
/// form in the cluster velocities.  The parts point into \p x.
Conditions conditions_of(const System& s, const ContactSet& closed, const Solution& x) {
  const int n = s.n;
  const std::vector<int>& cluster = s.clusters.of;
  auto linear = [&]() { return Linear{std::vector<Poly>(s.k(), Poly(s.vars)), Poly(s.vars)}; };
  auto add_velocity = [&](Linear& f, int i, const Poly& coefficient) {  // + coefficient · W_i
    const int ci = cluster[static_cast<std::size_t>(i)];
    if (ci == s.clusters.fixed)
      f.constant += coefficient * s.u[s.size() - 1];
    else
      f.coefficients[static_cast<std::size_t>(ci)] += coefficient;
  };
  const Poly one = Poly::constant(s.vars, 1);
  Conditions out;
  {
    Linear f = linear();
    add_velocity(f, 0, one);
    f.constant -= s.symbol(s.sy->fall_speed());
    out.pending.push_back({ConditionKind::Superball, "U1 > a", Relation::Greater, x.Wh[0] - x.aD, {&x.Wh[0], &x.aD}, f});
  }
  for (int c = 0; c + 1 < n; ++c) {
    if (closed.closed(c)) continue;
    Linear f = linear();
    add_velocity(f, c, one);
    add_velocity(f, c + 1, -one);
    out.pending.push_back({ConditionKind::Evolution, Pair{c + 1, c + 2}.name(), Relation::Greater,
                           x.Wh[static_cast<std::size_t>(c)] - x.Wh[static_cast<std::size_t>(c + 1)],
                           {&x.Wh[static_cast<std::size_t>(c)], &x.Wh[static_cast<std::size_t>(c + 1)]}, f});
  }
  out.reaction_forms.assign(s.size() - 1, linear());
  for (int c = 0; c + 1 < n; ++c) {
    if (!closed.closed(c)) continue;
    Linear& f = out.reaction_forms[static_cast<std::size_t>(c)];
    for (int i = s.clusters.top[static_cast<std::size_t>(cluster[static_cast<std::size_t>(c)])]; i <= c; ++i) {
      add_velocity(f, i, s.m[static_cast<std::size_t>(i)]);
      f.constant -= s.m[static_cast<std::size_t>(i)] * s.u[static_cast<std::size_t>(i)];
      for (int j = 0; j < n; ++j) {
        if (s.Kij(i, j).is_zero()) continue;
        add_velocity(f, j, s.Kij(i, j));
        f.constant += s.Kij(i, j) * s.u[static_cast<std::size_t>(j)];
      }
    }
    out.pending.push_back({ConditionKind::Contact, Pair{c + 1, c + 2}.name(), Relation::GreaterEqual, x.Lh[static_cast<std::size_t>(c)],
                           {&x.inertia[static_cast<std::size_t>(c)], &x.dissipation[static_cast<std::size_t>(c)]}, f});
  }
  return out;
}

/// Phase 7: the elimination (Elimination), when something of the case is
/// long: checked against the Cramer solution and every linear form exactly
/// at a random point, and at the same point with the small parameters at 0
/// for the asymptotic forms (then `limit[q]` is set for each condition q whose
/// ε⁰ part it gives).  \p orders: the ε-order of each symbol; \p order: the
/// orders kept beyond the dominant balance; \p epsilon_order of a polynomial.
/// nullopt when the case is short or a pivot vanishes at the point.
std::optional<Elimination> eliminate(const System& s, const ContactSet& closed, const Solution& x, const std::vector<Pending>& pending,
                                     const std::vector<GiNaC::numeric>& orders, int order,
                                     const std::function<GiNaC::numeric(const Poly&)>& epsilon_order, std::vector<char>& limit) {
  const Symbols& sy = *s.sy;
  const int k = s.clusters.free, vars = s.vars;
  const std::size_t Kc = s.k();
  bool long_case = false;
  for (const Pending& p : pending) long_case = long_case || p.raw.size() > max_inline_terms;
  for (const Poly& v : x.Vh) long_case = long_case || v.size() > max_inline_exact_terms;
  long_case = long_case && k >= min_eliminated_clusters;
  if (!long_case) return std::nullopt;
  Elimination e;
  e.size = k;
  for (int c = k; c-- > 0;) e.order.push_back(c);
  e.multiplier = multipliers(s.B, k, e.order);
  for (const Poly& b : s.B) e.matrix.push_back(b.to_ex(sy));
  for (const Poly& r : s.rhs) e.rhs.push_back(r.to_ex(sy));
  bool small_only = order == 0;  // the asymptotic forms are the ε⁰ parts: no parameter of negative order
  for (const GiNaC::numeric& o : orders) small_only = small_only && !o.is_negative();
  small_only = small_only && epsilon_order(x.D).is_zero();
  // A point modulo ℓ = 2⁶¹ − 1, drawn from the case (the output does not depend on it).
  namespace m = detail::mod61;
  std::mt19937_64 draw(0x5eedu + closed.to_string().size() * 7919u + std::hash<std::string>{}(closed.to_string()));
  std::vector<std::uint64_t> point(static_cast<std::size_t>(vars)), zeroed;
  for (auto& v : point) v = draw() % (m::prime - 1) + 1;
  zeroed = point;
  for (std::size_t q = 0; q < orders.size(); ++q)
    if (orders[q].is_positive()) zeroed[q] = 0;
  auto velocities_at = [&](const std::vector<std::uint64_t>& at) {
    std::vector<std::uint64_t> Bx, rx;
    for (const Poly& b : s.B) Bx.push_back(b.evaluate_mod(at));
    for (const Poly& r : s.rhs) rx.push_back(r.evaluate_mod(at));
    return eliminated_velocities(Bx, rx, k, e.multiplier, e.order);
  };
  auto value_at = [&](const Linear& f, const std::vector<std::uint64_t>& V, const std::vector<std::uint64_t>& at) {
    std::uint64_t v = f.constant.evaluate_mod(at);
    for (std::size_t c = 0; c < Kc; ++c)
      if (!f.coefficients[c].is_zero()) v = m::add(v, m::multiply(f.coefficients[c].evaluate_mod(at), V[c]));
    return v;
  };
  const auto V = velocities_at(point);
  if (!V) return std::nullopt;
  const std::uint64_t Dx = x.D.evaluate_mod(point);
  for (std::size_t c = 0; c < Kc; ++c)
    if (m::multiply((*V)[c], Dx) != x.Vh[c].evaluate_mod(point))
      throw std::logic_error("Deriver::derive(): case " + closed.to_string() + ": the elimination's velocity of cluster " + std::to_string(c + 1) +
                             " is not the Cramer solution");
  for (const Pending& p : pending)
    if (m::multiply(value_at(p.form, *V, point), Dx) != p.raw.evaluate_mod(point))
      throw std::logic_error("Deriver::derive(): case " + closed.to_string() + ": the condition on " + p.about +
                             " through the elimination is not the condition");
  const auto V0 = small_only ? velocities_at(zeroed) : std::nullopt;
  if (V0) {
    const std::uint64_t D0 = x.D.evaluate_mod(zeroed);
    for (std::size_t q = 0; q < pending.size(); ++q) {
      const Pending& p = pending[q];
      if (p.raw.is_zero() || !epsilon_order(p.raw).is_zero()) continue;  // the ε⁰ part vanishes: not the dominant balance
      if (m::multiply(value_at(p.form, *V0, zeroed), D0) != p.raw.evaluate_mod(zeroed))
        throw std::logic_error("Deriver::derive(): case " + closed.to_string() + ": the condition on " + p.about +
                               " through the elimination at order ε^0 is not the condition's");
      limit[q] = 1;
    }
    for (std::size_t q = 0; q < orders.size(); ++q)
      if (orders[q].is_positive()) e.small.push_back(sy.all()[q].symbol);
  }
  return e;
}

/// A linear form as the derivation keeps it (EliminatedForm).
EliminatedForm eliminated_form(const Linear& f, const Symbols& sy) {
  EliminatedForm e;
  for (const Poly& c : f.coefficients) e.coefficients.push_back(c.to_ex(sy));
  e.constant = f.constant.to_ex(sy);
  return e;
}

/// Phase 8, its end: whether something of \p d is written through its
/// elimination (present/'s report writes a velocity, a reaction or
/// det(ZᵀAZ) through it by the same count of terms), so that it is kept.
bool elimination_used(const Derivation& d) {
  bool used = terms_of(d.determinant) > max_inline_exact_terms;
  for (const Fraction& f : d.velocities) used = used || f.terms > max_inline_exact_terms;
  for (const Fraction& f : d.reactions) used = used || f.terms > max_inline_exact_terms;
  for (const Condition& c : d.conditions) used = used || c.exact.eliminated || c.asymptotic.eliminated || (c.finite && c.finite->eliminated);
  return used;
}

/// The case as a whole: never actual when one of its evolution or contact
/// conditions never holds, always when each of them always does.
void set_actual(Derivation& d) {
  d.actual = Verdict::Always;
  for (const Condition& c : d.conditions) {
    if (c.kind != ConditionKind::Evolution && c.kind != ConditionKind::Contact) continue;
    if (c.exact.verdict == Verdict::Never) {
      d.actual = Verdict::Never;
      d.actual_reason = c.about;
      break;
    }
    if (c.exact.verdict == Verdict::Depends) d.actual = Verdict::Depends;
  }
}

}  // namespace

namespace {

/// What Deriver::prepare() hands to Deriver::derive(): the solution's
/// polynomials and whether each numerator (the velocities, the closed
/// contacts' reactions, the conditions, in that order) is coprime with D.
struct Prepared {
  Solution x;
  std::vector<char> coprime;
};

/// The first bytes of a prepared case (Deriver::prepare()).
constexpr char kPreparedTag[] = "superball-prepared-1";

/// The numerators derive() reduces by D, in the order it reduces them
/// (Prepared::coprime): each body's velocity, each closed contact's −λD, each condition.
std::vector<const Poly*> reduced_numerators(const System& s, const ContactSet& closed, const Solution& x, const std::vector<Poly>& negated_reactions,
                                            const std::vector<Pending>& pending) {
  std::vector<const Poly*> out;
  for (const Poly& w : x.Wh) out.push_back(&w);
  for (int c = 0; c + 1 < s.n; ++c)
    if (closed.closed(c)) out.push_back(&negated_reactions[static_cast<std::size_t>(c)]);
  for (const Pending& p : pending) out.push_back(&p.raw);
  return out;
}

/// −λD on each contact (zero where open).
std::vector<Poly> negated(const std::vector<Poly>& Lh) {
  std::vector<Poly> out;
  for (const Poly& l : Lh) out.push_back(-l);
  return out;
}

/// The solution of \p s read back from Deriver::prepare()'s \p text.
Prepared read_prepared(const System& s, const ContactSet& closed, const std::string& text) {
  const std::size_t tag = sizeof kPreparedTag - 1;
  if (text.compare(0, tag, kPreparedTag) != 0 || text.size() < tag + closed.to_string().size() + 1 ||
      text.compare(tag, closed.to_string().size() + 1, closed.to_string() + ";") != 0)
    throw std::invalid_argument("Deriver::derive(): the prepared work is not that of case " + closed.to_string());
  std::size_t at = tag + closed.to_string().size() + 1;
  Prepared p;
  Solution& x = p.x;
  const std::size_t N = s.size();
  x.D = Poly::read(text, at, s.vars);
  x.aD = s.symbol(s.sy->fall_speed()) * x.D;
  x.uD.assign(N, Poly(s.vars));
  for (std::size_t j = 0; j < N; ++j) x.uD[j] = s.u[j] * x.D;
  for (std::size_t c = 0; c < s.k(); ++c) x.Vh.push_back(Poly::read(text, at, s.vars));
  x.Wh.assign(N, Poly(s.vars));
  for (std::size_t i = 0; i < N; ++i) {
    const int ci = s.clusters.of[i];
    x.Wh[i] = ci == s.clusters.fixed ? x.uD[N - 1] : x.Vh[static_cast<std::size_t>(ci)];
  }
  for (std::vector<Poly>* v : {&x.Lh, &x.inertia, &x.dissipation})
    for (std::size_t c = 0; c + 1 < N; ++c) v->push_back(Poly::read(text, at, s.vars));
  if (at >= text.size()) throw std::invalid_argument("Poly::read(): the record is truncated");
  p.coprime.assign(text.begin() + static_cast<std::ptrdiff_t>(at), text.end());
  return p;
}

}  // namespace

std::string Deriver::prepare(const ContactSet& closed) const { return prepare(closed, 0, 1); }

std::string Deriver::prepare(const ContactSet& closed, int piece, int pieces) const {
  const Symbols& sy = *symbols_;
  if (closed.bodies() != sy.bodies())
    throw std::invalid_argument("Deriver::prepare(): the case " + closed.to_string() + " is for " + std::to_string(closed.bodies()) +
                                " bodies, the pattern has " + std::to_string(sy.bodies()));
  if (pieces < 1 || piece < 0 || piece >= pieces)
    throw std::invalid_argument("Deriver::prepare(): part " + std::to_string(piece) + " of " + std::to_string(pieces) +
                                ": the parts are 0 to pieces - 1, pieces >= 1");
  const System s = system_of(sy, closed);
  const Solution x = solve(s, closed);
  check_equations(s, closed, x, piece, pieces);
  const detail::Denominator denominator(x.D, sy);
  const std::vector<Poly> minus_L = negated(x.Lh);
  const Conditions conditions = conditions_of(s, closed, x);
  // Part 0: the tag, the case, the solution and the flags; the others: the tag, the case and the flags.
  std::string out = kPreparedTag + closed.to_string() + ";";
  if (piece == 0) {
    x.D.write(out);
    for (const Poly& v : x.Vh) v.write(out);
    for (const std::vector<Poly>* v : {&x.Lh, &x.inertia, &x.dissipation})
      for (const Poly& p : *v) p.write(out);
  }
  std::size_t q = 0;  // a flag per numerator: '1' coprime, '0' not proved, '-' another part's
  for (const Poly* p : reduced_numerators(s, closed, x, minus_L, conditions.pending))
    out += q++ % static_cast<std::size_t>(pieces) != static_cast<std::size_t>(piece) ? '-' : !p->is_zero() && denominator.coprime_with(*p) ? '1' : '0';
  return out;
}

std::string Deriver::join_prepared(const std::vector<std::string>& pieces) {
  if (pieces.empty()) throw std::invalid_argument("join_prepared(): no part");
  const std::size_t n = pieces.size(), tag = sizeof kPreparedTag - 1;
  // The header (tag, case, ';') is the whole of each part but the first, up to its flags.
  auto header_of = [&](const std::string& p) {
    const std::size_t end = p.compare(0, tag, kPreparedTag) == 0 ? p.find(';', tag) : std::string::npos;
    if (end == std::string::npos) throw std::invalid_argument("join_prepared(): a part is not prepared work");
    return p.substr(0, end + 1);
  };
  const std::string header = header_of(pieces[0]);
  const std::size_t flags = n > 1 ? pieces[1].size() - header_of(pieces[1]).size() : 0;
  std::string out = pieces[0];
  if (out.size() < header.size() + flags) throw std::invalid_argument("join_prepared(): the first part is truncated");
  const std::size_t base = out.size() - flags;  // where the first part's flags start
  for (std::size_t k = 0; k < n; ++k) {
    const std::string& p = pieces[k];
    if (header_of(p) != header) throw std::invalid_argument("join_prepared(): the parts are of different cases");
    if (k > 0 && p.size() != header.size() + flags) throw std::invalid_argument("join_prepared(): the parts have different numbers of flags");
    const std::size_t at = k == 0 ? base : header.size();
    for (std::size_t q = 0; q < flags; ++q) {
      const char f = p[at + q];
      const bool own = q % n == k;
      if (own != (f != '-') || (own && f != '0' && f != '1'))
        throw std::invalid_argument("join_prepared(): part " + std::to_string(k) + " of " + std::to_string(n) + " is not in its place");
      if (own) out[base + q] = f;
    }
  }
  return out;
}

Derivation Deriver::derive(const ContactSet& closed) const { return derive(closed, std::string()); }

Derivation Deriver::derive(const ContactSet& closed, const std::string& prepared, Forms forms) const {
  const Symbols& sy = *symbols_;
  if (closed.bodies() != sy.bodies())
    throw std::invalid_argument("Deriver::derive(): the case " + closed.to_string() + " is for " + std::to_string(closed.bodies()) +
                                " bodies, the pattern has " + std::to_string(sy.bodies()));
  const System s = system_of(sy, closed);  // phases 1 and 2
  // Phase 3 (and the check of phase 5's equations), or its results from prepare().
  const Prepared ahead = prepared.empty() ? Prepared{solve(s, closed), {}} : read_prepared(s, closed, prepared);
  const Solution& x = ahead.x;
  if (prepared.empty()) check_equations(s, closed, x);
  const detail::Denominator denominator(x.D, sy, prepared.empty());
  std::size_t asked = 0;  // the next numerator reduced by D (reduced_numerators())
  auto coprime = [&]() -> const bool* {
    static const bool yes = true, no = false;
    const std::size_t q = asked++;
    if (prepared.empty()) return nullptr;
    if (q >= ahead.coprime.size()) throw std::invalid_argument("Deriver::derive(): the prepared work of case " + closed.to_string() + " is short");
    return ahead.coprime[q] == '1' ? &yes : &no;
  };

  Derivation out;  // phase 4: the results in lowest terms
  out.symbols = symbols_;
  out.closed = closed;
  out.case_name = Vocabulary::paper().case_name(closed);
  out.determinant = denominator.value();
  out.free_clusters = s.clusters.free;
  const GiNaC::exmap ref = reference_point(sy);
  std::vector<Stored> velocities, reactions;
  for (int i = 0; i < s.n; ++i) velocities.push_back(normalise(x.Wh[static_cast<std::size_t>(i)], denominator, ref, coprime(), forms));
  const std::vector<Poly> minus_L = negated(x.Lh);
  for (int c = 0; c + 1 < s.n; ++c)
    reactions.push_back(closed.closed(c) ? normalise(minus_L[static_cast<std::size_t>(c)], denominator, ref, coprime(), forms) : Stored{});
  for (const Stored& v : velocities) out.velocities.push_back(v.fraction);
  for (const Stored& r : reactions) out.reactions.push_back(r.fraction);

  const Conditions conditions = conditions_of(s, closed, x);  // phase 6
  const std::vector<Pending>& pending = conditions.pending;
  std::vector<char> limit(pending.size(), 0);
  const Rules rules(*this, orders_, couplings_);
  out.elimination = eliminate(s, closed, x, pending, orders_, order_, [&rules](const Poly& p) { return rules.epsilon_order(p); }, limit);  // phase 7
  if (out.elimination)
    for (const Linear& f : conditions.reaction_forms) out.reactions_eliminated.push_back(eliminated_form(f, sy));

  // Phase 8: the conditions' forms, the named parts, the case's verdict.
  Naming naming;  // the case's named parts, and the diagonal of ZᵀAZ as candidates
  const std::size_t Kc = s.k();
  for (std::size_t c = 0; c < Kc; ++c)
    if (!s.B[c * Kc + c].is_constant()) naming.candidates.push_back(s.B[c * Kc + c]);
  for (std::size_t q = 0; q < pending.size(); ++q) {
    const Pending& p = pending[q];
    const EliminatedForm form = out.elimination ? eliminated_form(p.form, sy) : EliminatedForm{};
    out.conditions.push_back(rules.make_condition(p.kind, p.about, p.relation, p.raw, denominator, p.parts, naming,
                                            out.elimination ? &form : nullptr, limit[q] != 0, coprime(), forms));
  }
  if (out.elimination && !elimination_used(out)) {  // the elimination is kept only when something is written through it
    out.elimination.reset();
    out.reactions_eliminated.clear();
  }
  // A long result left unbuilt is written through the elimination; without one (a case of too few clusters) it is built now.
  for (int i = 0; i < s.n && !out.elimination; ++i)
    if (!velocities[static_cast<std::size_t>(i)].built) {
      build(velocities[static_cast<std::size_t>(i)], x.Wh[static_cast<std::size_t>(i)], sy);
      out.velocities[static_cast<std::size_t>(i)] = velocities[static_cast<std::size_t>(i)].fraction;
    }
  for (int c = 0; c + 1 < s.n && !out.elimination; ++c)
    if (!reactions[static_cast<std::size_t>(c)].built) {
      build(reactions[static_cast<std::size_t>(c)], minus_L[static_cast<std::size_t>(c)], sy);
      out.reactions[static_cast<std::size_t>(c)] = reactions[static_cast<std::size_t>(c)].fraction;
    }
  out.check = check_solution(s, closed, x, denominator, velocities, reactions);  // phase 5: the stored results are the solution

  for (std::size_t k = 0; k < naming.named.size(); ++k)
    out.named.push_back(NamedPart{static_cast<int>(k) + 1, naming.named[k].to_ex(sy), rules.positive_terms(naming.named[k])});
  set_actual(out);
  out.conditions.insert(out.conditions.end(), psd_.begin(), psd_.end());
  return out;
}

std::vector<Derivation> Deriver::derive_all() const {
  const int n = symbols_->bodies();
  if (n > 21) throw std::invalid_argument("Deriver::derive_all(): 2^(n-1) cases for n = " + std::to_string(n) + " is too many");
  std::vector<Derivation> out;
  for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << (n - 1)); ++mask) out.push_back(derive(ContactSet::from_mask(mask, n)));
  return out;
}

}  // namespace superball::symbolic
