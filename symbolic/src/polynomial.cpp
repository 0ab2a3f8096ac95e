#include "polynomial.hpp"

#include <algorithm>
#include <random>
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

namespace {

/// c_0 + c_1 x + … as a GiNaC polynomial in x.
GiNaC::ex univariate_ex(const std::vector<cln::cl_I>& c, const GiNaC::ex& x) {
  GiNaC::ex p = 0;
  for (std::size_t d = 0; d < c.size(); ++d)
    if (!cln::zerop(c[d])) p += GiNaC::numeric(cln::cl_N(c[d])) * GiNaC::pow(x, static_cast<int>(d));
  return p;
}

}  // namespace

const GiNaC::ex& Denominator::value() const {
  if (!have_ex_) {
    q_ex_ = q_.to_ex(*symbols_);
    have_ex_ = true;
  }
  return q_ex_;
}

Denominator::Denominator(const Poly& q, const Symbols& symbols, bool probe) : symbols_(&symbols), q_(q), probe_(probe) {
  const int vars = q.vars();
  std::vector<cln::cl_I> ref(static_cast<std::size_t>(vars));
  for (int k = 0; k < vars; ++k) ref[static_cast<std::size_t>(k)] = symbols.all()[static_cast<std::size_t>(k)].kind == SymbolKind::Coupling ? 0 : 1;
  sign_ = cln::signum(q.evaluate(ref)) > 0 ? 1 : cln::zerop(q.evaluate(ref)) ? 0 : -1;
  if (q_.is_constant() || !probe) return;
  // The line: fixed pseudo-random points modulo ℓ (the answers do not depend on them, only how fast they come).
  std::mt19937_64 draw(0x11e5eedu);
  for (int k = 0; k < vars; ++k) {
    line_a_.push_back(draw() % mod61::prime);
    line_b_.push_back(draw() % (mod61::prime - 1) + 1);
  }
  line_q_ = q_.on_line_mod(line_a_, line_b_);
  if (static_cast<int>(line_q_.size()) - 1 != q_.total_degree()) line_q_.clear();  // q_top(b) ≡ 0: the degree drops
}

void Denominator::make_probes() const {
  static const int values[] = {3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89, 97};
  constexpr int count = sizeof(values) / sizeof(values[0]);
  probed_ = true;
  const int vars = q_.vars();
  for (int x = 0; x < vars; ++x) {
    const int degree = q_.degree(x);
    if (!degree) continue;
    bool found = false;
    for (int attempt = 0; attempt < 3 && !found; ++attempt) {
      Probe probe{x, std::vector<cln::cl_I>(static_cast<std::size_t>(vars), 0), 0, {}, {}};
      int k = 0;
      for (int other = 0; other < vars; ++other)
        if (other != x) probe.point[static_cast<std::size_t>(other)] = values[(k++ * 7 + attempt * 5 + 1) % count] + attempt;
      const std::vector<cln::cl_I> at = q_.univariate(x, probe.point);
      if (static_cast<int>(at.size()) - 1 != degree || cln::zerop(at.back())) continue;  // the leading coefficient vanishes there
      probe.q_at = univariate_ex(at, symbols_->all()[static_cast<std::size_t>(x)].symbol);
      for (const cln::cl_I& v : probe.point) probe.point_mod.push_back(mod61::reduce(v));
      probe.q_mod = q_.univariate_mod(x, probe.point_mod);
      if (static_cast<int>(probe.q_mod.size()) - 1 != degree) probe.q_mod.clear();
      probes_.push_back(std::move(probe));
      found = true;
    }
    if (!found) unprobed_.push_back(x);
  }
}

bool Denominator::coprime_with(const Poly& p) const {
  if (p.is_zero()) return false;
  if (p.is_constant() || q_.is_constant()) return true;
  if (!probe_) throw std::logic_error("Denominator::coprime_with(): made without probes");
  if (!line_q_.empty()) {
    const std::vector<std::uint64_t> p_line = p.on_line_mod(line_a_, line_b_);
    if (!p_line.empty() && mod61::gcd_degree(p_line, line_q_) == 0) return true;  // proved on the line
  }
  if (!probed_) make_probes();
  for (int x : unprobed_)
    if (p.has(x)) return false;
  for (const Probe& probe : probes_) {
    if (!p.has(probe.x)) continue;
    if (!probe.q_mod.empty()) {
      const std::vector<std::uint64_t> p_mod = p.univariate_mod(probe.x, probe.point_mod);
      if (!p_mod.empty() && mod61::gcd_degree(p_mod, probe.q_mod) == 0) continue;  // proved for x, modulo the prime
    }
    const GiNaC::ex& x = symbols_->all()[static_cast<std::size_t>(probe.x)].symbol;
    const GiNaC::ex g = GiNaC::gcd(univariate_ex(p.univariate(probe.x, probe.point), x), probe.q_at);
    if (g.degree(x) > 0) return false;
  }
  return true;
}

Denominator::Reduced Denominator::lowest_terms(const Poly& num, bool with_numerator, const bool* coprime) const {
  Reduced r;
  if (num.is_zero()) {
    r.numerator = 0;
    r.denominator = 1;
    return r;
  }
  if (coprime ? *coprime : coprime_with(num)) {
    r.whole = true;
    r.content = cln::gcd(num.content(), q_.content());
    if (with_numerator) r.numerator = num.divided(r.content).to_ex(*symbols_);
    r.denominator = r.content == 1 ? value() : q_.divided(r.content).to_ex(*symbols_);
    return r;
  }
  const GiNaC::ex nd = GiNaC::numer_denom(num.to_ex(*symbols_) / value());
  GiNaC::ex n = GiNaC::expand(nd.op(0)), d = GiNaC::expand(nd.op(1));
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
  r.numerator = n;
  r.denominator = d;
  return r;
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
    for (const auto& x_power : t.powers) {
      const GiNaC::ex& x = x_power.first;  // C++17: a lambda cannot capture a structured binding
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
