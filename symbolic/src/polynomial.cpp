#include "polynomial.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "superball/symbolic/derivation.hpp"

namespace superball::symbolic {
namespace detail {
namespace {

std::string show(const GiNaC::ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

/// Multiply \p term by the factor \p f (a number, a symbol or a power of a symbol).
void absorb(Term& term, const GiNaC::ex& f, const GiNaC::ex& whole) {
  if (GiNaC::is_a<GiNaC::numeric>(f)) {
    const auto& c = GiNaC::ex_to<GiNaC::numeric>(f);
    if (!c.is_rational()) throw std::invalid_argument("terms(): coefficient " + show(f) + " of " + show(whole) + " is not rational");
    term.coefficient *= c;
  } else if (GiNaC::is_a<GiNaC::symbol>(f)) {
    term.powers.emplace_back(f, 1);
  } else if (GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<GiNaC::symbol>(f.op(0)) && f.op(1).info(GiNaC::info_flags::posint)) {
    term.powers.emplace_back(f.op(0), GiNaC::ex_to<GiNaC::numeric>(f.op(1)).to_int());
  } else {
    throw std::invalid_argument("terms(): '" + show(whole) + "' is not an expanded polynomial (factor " + show(f) + ")");
  }
}

}  // namespace

GiNaC::ex Term::monomial() const {
  GiNaC::ex m = 1;
  for (const auto& [s, e] : powers) m *= GiNaC::pow(s, e);
  return m;
}

std::vector<Term> terms(const GiNaC::ex& p) {
  std::vector<Term> out;
  if (p.is_zero()) return out;
  auto one = [&](const GiNaC::ex& t) {
    Term term;
    if (GiNaC::is_a<GiNaC::mul>(t))
      for (std::size_t k = 0; k < t.nops(); ++k) absorb(term, t.op(k), p);
    else
      absorb(term, t, p);
    out.push_back(std::move(term));
  };
  if (GiNaC::is_a<GiNaC::add>(p))
    for (std::size_t k = 0; k < p.nops(); ++k) one(p.op(k));
  else
    one(p);
  return out;
}

GiNaC::ex determinant(const GiNaC::matrix& m) {
  if (m.rows() == 0) return 1;
  return GiNaC::expand(m.determinant(GiNaC::determinant_algo::automatic));
}

GiNaC::numeric evaluate(const GiNaC::ex& p, const GiNaC::exmap& point) {
  const GiNaC::ex v = p.subs(point, GiNaC::subs_options::no_pattern);
  if (!GiNaC::is_a<GiNaC::numeric>(v)) throw std::logic_error("evaluate(): '" + show(p) + "' is not a number at the point (got " + show(v) + ")");
  return GiNaC::ex_to<GiNaC::numeric>(v);
}

bool certainly_nonnegative(const GiNaC::ex& p, const Symbols& symbols) {
  for (const Term& t : terms(GiNaC::expand(p))) {
    if (!t.coefficient.is_positive()) return false;
    for (const auto& [s, e] : t.powers)
      if (symbols.is_coupling(s) && e % 2) return false;
  }
  return true;
}

Denominator::Denominator(const GiNaC::ex& q, const Symbols& symbols) : q_(GiNaC::expand(q)) {
  static const int values[] = {3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89, 97};
  constexpr int count = sizeof(values) / sizeof(values[0]);
  if (GiNaC::is_a<GiNaC::numeric>(q_)) return;
  for (const SymbolInfo& s : symbols.all()) {
    if (!q_.has(s.symbol)) continue;
    const GiNaC::ex lc = q_.lcoeff(s.symbol);
    bool found = false;
    for (int attempt = 0; attempt < 3 && !found; ++attempt) {
      Probe probe{s.symbol, {}, 0};
      int k = 0;
      for (const SymbolInfo& other : symbols.all())
        if (!other.symbol.is_equal(s.symbol)) probe.point[other.symbol] = values[(k++ * 7 + attempt * 5 + 1) % count] + attempt;
      if (lc.subs(probe.point, GiNaC::subs_options::no_pattern).is_zero()) continue;
      probe.q_at = GiNaC::expand(q_.subs(probe.point, GiNaC::subs_options::no_pattern));
      probes_.push_back(std::move(probe));
      found = true;
    }
    if (!found) unprobed_.push_back(s.symbol);
  }
}

bool Denominator::coprime_with(const GiNaC::ex& p) const {
  const GiNaC::ex pe = GiNaC::expand(p);
  if (pe.is_zero()) return false;
  if (GiNaC::is_a<GiNaC::numeric>(pe) || GiNaC::is_a<GiNaC::numeric>(q_)) return true;
  for (const GiNaC::ex& x : unprobed_)
    if (pe.has(x)) return false;
  for (const Probe& probe : probes_) {
    if (!pe.has(probe.x)) continue;
    const GiNaC::ex g = GiNaC::gcd(GiNaC::expand(pe.subs(probe.point, GiNaC::subs_options::no_pattern)), probe.q_at);
    if (g.degree(probe.x) > 0) return false;
  }
  return true;
}

std::pair<GiNaC::ex, GiNaC::ex> Denominator::lowest_terms(const GiNaC::ex& num) const {
  GiNaC::ex n = GiNaC::expand(num), d = q_;
  if (n.is_zero()) return {0, 1};
  if (!coprime_with(n)) {
    const GiNaC::ex nd = GiNaC::numer_denom(n / d);
    n = GiNaC::expand(nd.op(0));
    d = GiNaC::expand(nd.op(1));
  }
  // Common rational content.
  GiNaC::numeric top = 0, bottom = 1;
  for (const GiNaC::ex* e : {&n, &d})
    for (const Term& t : terms(*e)) {
      top = GiNaC::gcd(top, t.coefficient.numer());
      bottom = GiNaC::lcm(bottom, t.coefficient.denom());
    }
  const GiNaC::numeric c = top / bottom;
  if (!c.is_zero() && !c.is_equal(1)) {
    n = GiNaC::expand(n / c);
    d = GiNaC::expand(d / c);
  }
  return {n, d};
}

}  // namespace detail

bool certainly_nonnegative(const GiNaC::ex& p, const Symbols& symbols) { return detail::certainly_nonnegative(p, symbols); }

bool certainly_positive(const GiNaC::ex& p, const Symbols& symbols) {
  const GiNaC::ex e = GiNaC::expand(p);
  // GiNaC decides sums and products of possymbols with positive coefficients
  // itself; the term rule below also admits even powers of (real) couplings.
  if (e.info(GiNaC::info_flags::positive)) return true;
  if (!detail::certainly_nonnegative(e, symbols)) return false;
  for (const detail::Term& t : detail::terms(e)) {
    bool free_of_couplings = true;
    for (const auto& pe : t.powers) free_of_couplings = free_of_couplings && !symbols.is_coupling(pe.first);
    if (free_of_couplings) return true;
  }
  return false;
}

GiNaC::numeric epsilon_order(const GiNaC::ex& p, const Symbols& symbols, const Scaling& scaling) {
  const auto ts = detail::terms(GiNaC::expand(p));
  if (ts.empty()) throw std::invalid_argument("epsilon_order(): the zero polynomial has no order");
  GiNaC::numeric lowest = 0;
  bool first = true;
  for (const detail::Term& t : ts) {
    GiNaC::numeric w = 0;
    for (const auto& [s, e] : t.powers) w += scaling.order(symbols, s) * e;
    if (first || w < lowest) lowest = w;
    first = false;
  }
  return lowest;
}

namespace {

/// Whether the expanded polynomial \p e (without rational content) is
/// certainly irreducible over Q, decided cheaply (\p ts: the terms of e, or
/// of e times a monomial: only the symbols they name are tried): e = a·x + b is of degree 1
/// in some symbol x, with b ≠ 0 and gcd(a, b) a number.  Any factorisation
/// e = f·g puts x in one factor only, so the other, free of x, divides both
/// a and b.  A gcd is far cheaper than GiNaC::factor, which then is skipped.
bool certainly_irreducible(const GiNaC::ex& e, const std::vector<detail::Term>& ts) {
  std::vector<GiNaC::ex> seen;
  for (const detail::Term& t : ts)
    for (const auto& [x, power] : t.powers) {
      if (std::any_of(seen.begin(), seen.end(), [&](const GiNaC::ex& y) { return y.is_equal(x); })) continue;
      seen.push_back(x);
      if (e.degree(x) != 1) continue;
      const GiNaC::ex b = e.coeff(x, 0);
      if (b.is_zero()) continue;
      if (GiNaC::is_a<GiNaC::numeric>(GiNaC::gcd(e.coeff(x, 1), b))) return true;
    }
  return false;
}

}  // namespace

GiNaC::ex strip_positive_factors(const GiNaC::ex& p, const Symbols& symbols, GiNaC::ex* removed) {
  GiNaC::ex e = GiNaC::expand(p);
  GiNaC::ex gone = 1;
  const auto ts = detail::terms(e);
  if (ts.empty()) {
    if (removed) *removed = 1;
    return 0;
  }
  // Rational content (positive) and the common monomial of positive symbols.
  GiNaC::numeric num = 0, den = 1;
  for (const detail::Term& t : ts) {
    num = GiNaC::gcd(num, t.coefficient.numer());
    den = GiNaC::lcm(den, t.coefficient.denom());
  }
  GiNaC::ex monomial = 1;
  for (const auto& [s, e0] : ts.front().powers) {
    if (symbols.is_coupling(s)) continue;
    int low = e0;
    for (const detail::Term& t : ts) {
      int here = 0;
      for (const auto& [s2, e2] : t.powers)
        if (s2.is_equal(s)) here = e2;
      low = std::min(low, here);
    }
    if (low > 0) monomial *= GiNaC::pow(s, low);
  }
  gone = (num / den) * monomial;
  e = GiNaC::expand(e / gone);  // term by term: a number times a monomial divides every term exactly
  // Irreducible factors that are positive for every admissible point
  // (factorisation only for small polynomials: it dominates the cost otherwise).
  if (GiNaC::is_a<GiNaC::add>(e) && e.nops() <= max_factor_terms && !certainly_irreducible(e, ts)) {
    const GiNaC::ex f = GiNaC::factor(e);
    if (GiNaC::is_a<GiNaC::mul>(f)) {
      GiNaC::ex kept = 1;
      for (std::size_t k = 0; k < f.nops(); ++k) {
        const GiNaC::ex& fk = f.op(k);
        const GiNaC::ex base = GiNaC::is_a<GiNaC::power>(fk) ? fk.op(0) : fk;
        if (!GiNaC::is_a<GiNaC::numeric>(base) && certainly_positive(base, symbols))
          gone *= fk;
        else
          kept *= fk;
      }
      e = GiNaC::expand(kept);
    }
  }
  if (removed) *removed = gone;
  return e;
}

bool same_condition(const GiNaC::ex& p, const GiNaC::ex& q, const Symbols& symbols) {
  if (p.is_zero() || q.is_zero()) return p.is_zero() && q.is_zero();
  const GiNaC::ex nd = GiNaC::numer_denom(p / q);
  const GiNaC::ex n = nd.op(0), d = nd.op(1);
  return (certainly_positive(n, symbols) && certainly_positive(d, symbols)) ||
         (certainly_positive(-n, symbols) && certainly_positive(-d, symbols));
}

GiNaC::exmap reference_point(const Symbols& symbols) {
  GiNaC::exmap point;
  for (const SymbolInfo& s : symbols.all()) point[s.symbol] = s.kind == SymbolKind::Coupling ? 0 : 1;
  return point;
}

}  // namespace superball::symbolic
