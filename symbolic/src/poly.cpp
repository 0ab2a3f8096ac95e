#include "poly.hpp"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <cln/integer_io.h>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "superball/symbolic/derivation.hpp"

namespace superball::symbolic::detail {
namespace {

constexpr std::uint64_t high_bits = 0x8080808080808080ULL;

int words_for(int vars) { return std::max(1, (vars + 7) / 8); }
/// Symbol k sits in word k/8, byte 7 − k%8: comparing words as integers compares exponent vectors lexicographically.
int shift_of(int k) { return 8 * (7 - k % 8); }

/// a > b in the term order.
bool greater(const std::uint64_t* a, const std::uint64_t* b, int words) {
  for (int w = 0; w < words; ++w)
    if (a[w] != b[w]) return a[w] > b[w];
  return false;
}

bool same(const std::uint64_t* a, const std::uint64_t* b, int words) {
  for (int w = 0; w < words; ++w)
    if (a[w] != b[w]) return false;
  return true;
}

std::uint64_t hash(const std::uint64_t* m, int words) {
  std::uint64_t h = 0x9E3779B97F4A7C15ULL;
  for (int w = 0; w < words; ++w) {
    h ^= m[w] + 0x9E3779B97F4A7C15ULL + (h << 6) + (h >> 2);
    h *= 0xBF58476D1CE4E5B9ULL;
  }
  return h ^ (h >> 31);
}

}  // namespace

Poly from_terms(int vars, std::vector<std::uint64_t>&& mono, std::vector<cln::cl_I>&& coef) {
  // Sort the terms (they are distinct and non-zero).
  Poly out(vars);
  const int w = out.words_;
  std::vector<std::size_t> order(coef.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return greater(&mono[x * w], &mono[y * w], w); });
  out.mono_.reserve(mono.size());
  out.coef_.reserve(coef.size());
  for (std::size_t t : order) out.push(&mono[t * w], coef[t]);
  return out;
}

Poly::Poly(int vars) : vars_(vars), words_(words_for(vars)) {}

void Poly::push(const std::uint64_t* m, const cln::cl_I& c) {
  mono_.insert(mono_.end(), m, m + words_);
  coef_.push_back(c);
}

Poly Poly::constant(int vars, const cln::cl_I& c) {
  Poly p(vars);
  if (!cln::zerop(c)) {
    const std::vector<std::uint64_t> zero(static_cast<std::size_t>(p.words_), 0);
    p.push(zero.data(), c);
  }
  return p;
}

Poly Poly::variable(int vars, int k) {
  if (k < 0 || k >= vars) throw std::invalid_argument("Poly::variable(): symbol " + std::to_string(k) + " out of range");
  Poly p(vars);
  std::vector<std::uint64_t> m(static_cast<std::size_t>(p.words_), 0);
  m[static_cast<std::size_t>(k / 8)] = std::uint64_t{1} << shift_of(k);
  p.push(m.data(), 1);
  return p;
}

namespace {

/// The pairs of a GiNaC sum or product read in place: a sum's op(k) builds
/// a new product for every term with a coefficient other than 1, which
/// reading a polynomial of thousands of terms paid for term by term.  A sum
/// is Σ rest_k·coeff_k + overall, a product Π rest_k^coeff_k · overall;
/// the pointers to these protected members are formed through this class.
struct Pairs : GiNaC::expairseq {
  static const GiNaC::epvector& of(const GiNaC::expairseq& e) { return e.*(&Pairs::seq); }
  static const GiNaC::ex& overall(const GiNaC::expairseq& e) { return e.*(&Pairs::overall_coeff); }
};

/// Reads \p e term by term when it is already an expanded polynomial with
/// integer coefficients (a sum of integer multiples of products of powers of
/// symbols): no expand(), which rebuilds every term.  False for anything
/// else (Poly::from_ex() then drops what was read and expands it).
bool read_expanded(const GiNaC::ex& e, const Symbols& symbols, int words, std::vector<std::uint64_t>& mono, std::vector<cln::cl_I>& coef) {
  std::vector<std::uint64_t> m(static_cast<std::size_t>(words));
  auto times = [](const GiNaC::ex& f, cln::cl_I& c) {  // c · f for an integer f
    if (!GiNaC::is_a<GiNaC::numeric>(f) || !GiNaC::ex_to<GiNaC::numeric>(f).is_integer()) return false;
    c = c * cln::the<cln::cl_I>(GiNaC::ex_to<GiNaC::numeric>(f).to_cl_N());
    return true;
  };
  auto power_of = [&](const GiNaC::ex& base, const GiNaC::ex& exponent) {  // base^exponent into m
    if (!exponent.info(GiNaC::info_flags::posint) || GiNaC::ex_to<GiNaC::numeric>(exponent) > Poly::max_exponent) return false;
    const SymbolInfo* info = GiNaC::is_a<GiNaC::symbol>(base) ? symbols.find(base) : nullptr;
    if (!info) return false;
    const int k = info->rank;
    if (m[static_cast<std::size_t>(k / 8)] & (std::uint64_t{0xFF} << shift_of(k))) return false;  // a symbol twice: not canonical
    m[static_cast<std::size_t>(k / 8)] |= static_cast<std::uint64_t>(GiNaC::ex_to<GiNaC::numeric>(exponent).to_int()) << shift_of(k);
    return true;
  };
  auto factor = [&](const GiNaC::ex& f, cln::cl_I& c) {  // a number, a symbol or a power of one
    if (GiNaC::is_a<GiNaC::numeric>(f)) return times(f, c);
    if (GiNaC::is_a<GiNaC::power>(f)) return power_of(f.op(0), f.op(1));
    return power_of(f, 1);
  };
  auto term = [&](const GiNaC::ex& t, const GiNaC::ex& coefficient) {  // coefficient · t
    std::fill(m.begin(), m.end(), 0);
    cln::cl_I c = 1;
    if (!times(coefficient, c)) return false;
    if (GiNaC::is_a<GiNaC::mul>(t)) {
      const auto& product = GiNaC::ex_to<GiNaC::mul>(t);
      if (!times(Pairs::overall(product), c)) return false;
      for (const GiNaC::expair& f : Pairs::of(product))
        if (!power_of(f.rest, f.coeff)) return false;
    } else if (!factor(t, c)) {
      return false;
    }
    if (cln::zerop(c)) return false;
    mono.insert(mono.end(), m.begin(), m.end());
    coef.push_back(c);
    return true;
  };
  if (e.is_zero()) return true;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    const auto& sum = GiNaC::ex_to<GiNaC::add>(e);
    for (const GiNaC::expair& t : Pairs::of(sum))
      if (!term(t.rest, t.coeff)) return false;
    return Pairs::overall(sum).is_zero() || term(1, Pairs::overall(sum));
  }
  return term(e, 1);
}

}  // namespace

Poly Poly::from_ex(const GiNaC::ex& e, const Symbols& symbols) {
  const int vars = static_cast<int>(symbols.all().size());
  std::vector<std::uint64_t> mono;
  std::vector<cln::cl_I> coef;
  const int w = words_for(vars);
  if (read_expanded(e, symbols, w, mono, coef)) {
    Poly p = from_terms(vars, std::move(mono), std::move(coef));
    bool distinct = true;  // GiNaC's sums hold each monomial once; else expand below
    for (std::size_t t = 1; t < p.size() && distinct; ++t) distinct = !same(p.mono(t - 1), p.mono(t), w);
    if (distinct) return p;
  }
  mono.clear();  // what was read before a term that is not a monomial
  coef.clear();
  for (const Monomial& t : symbols.monomials(e)) {
    if (!t.coefficient.is_integer()) throw std::invalid_argument("Poly::from_ex(): a coefficient is not an integer");
    std::vector<std::uint64_t> m(static_cast<std::size_t>(w), 0);
    for (const auto& [k, power] : t.powers) {
      if (power > max_exponent) throw std::invalid_argument("Poly::from_ex(): an exponent is above " + std::to_string(max_exponent));
      m[static_cast<std::size_t>(k / 8)] |= static_cast<std::uint64_t>(power) << shift_of(k);
    }
    mono.insert(mono.end(), m.begin(), m.end());
    coef.push_back(cln::the<cln::cl_I>(t.coefficient.to_cl_N()));
  }
  return from_terms(vars, std::move(mono), std::move(coef));
}

bool Poly::is_constant() const {
  if (coef_.size() > 1) return false;
  for (std::uint64_t x : mono_)
    if (x) return false;
  return true;
}

int Poly::exponent(std::size_t t, int k) const {
  return static_cast<int>((mono(t)[k / 8] >> shift_of(k)) & 0xFF);
}

int Poly::degree(int k) const {
  int d = 0;
  for (std::size_t t = 0; t < size(); ++t) d = std::max(d, exponent(t, k));
  return d;
}

Poly Poly::operator-() const {
  Poly p = *this;
  for (cln::cl_I& c : p.coef_) c = -c;
  return p;
}

Poly Poly::operator+(const Poly& q) const {
  if (q.is_zero()) return *this;
  if (is_zero()) return q;
  Poly out(vars_);
  out.mono_.reserve(mono_.size() + q.mono_.size());
  out.coef_.reserve(size() + q.size());
  std::size_t i = 0, j = 0;
  while (i < size() || j < q.size()) {
    if (j == q.size() || (i < size() && greater(mono(i), q.mono(j), words_))) {
      out.push(mono(i), coef_[i]);
      ++i;
    } else if (i == size() || greater(q.mono(j), mono(i), words_)) {
      out.push(q.mono(j), q.coef_[j]);
      ++j;
    } else {
      const cln::cl_I c = coef_[i] + q.coef_[j];
      if (!cln::zerop(c)) out.push(mono(i), c);
      ++i;
      ++j;
    }
  }
  return out;
}

Poly Poly::operator-(const Poly& q) const { return *this + (-q); }

namespace {

/// Products with a factor of at most this many terms are merges of shifted copies (Poly::operator*).
constexpr std::size_t merge_factor_terms = 8;

}  // namespace

Poly Poly::times_small(const Poly& q) const {
  // Adding the same exponent vector to every term keeps the order, so P · c_j m_j is
  // P's term list shifted, and the product is a merge of q.size() sorted lists.
  const int w = words_;
  const std::size_t lists = q.size();
  std::vector<std::size_t> head(lists, 0);
  std::vector<std::uint64_t> top(lists * static_cast<std::size_t>(w));  // the monomial at each list's head
  auto load = [&](std::size_t j) {
    if (head[j] == size()) return;
    const std::uint64_t *a = mono(head[j]), *b = q.mono(j);
    for (int k = 0; k < w; ++k) {
      top[j * w + k] = a[k] + b[k];
      if (top[j * w + k] & high_bits) throw std::overflow_error("Poly::operator*(): an exponent exceeds " + std::to_string(max_exponent));
    }
  };
  for (std::size_t j = 0; j < lists; ++j) load(j);
  Poly out(vars_);
  out.mono_.reserve(mono_.size() * lists);
  out.coef_.reserve(size() * lists);
  for (;;) {
    std::size_t best = lists;
    for (std::size_t j = 0; j < lists; ++j)
      if (head[j] < size() && (best == lists || greater(&top[j * w], &top[best * w], w))) best = j;
    if (best == lists) break;
    const std::uint64_t* m = &top[best * w];
    cln::cl_I c = coef_[head[best]] * q.coef_[best];
    for (std::size_t j = best + 1; j < lists; ++j)
      if (head[j] < size() && same(&top[j * w], m, w)) {
        c = c + coef_[head[j]] * q.coef_[j];
        ++head[j];
        load(j);
      }
    if (!cln::zerop(c)) out.push(m, c);
    ++head[best];
    load(best);
  }
  return out;
}

Poly Poly::operator*(const Poly& q) const {
  if (is_zero() || q.is_zero()) return Poly(vars_);
  if (q.size() <= merge_factor_terms && q.size() <= size()) return times_small(q);
  if (size() <= merge_factor_terms) return q.times_small(*this);
  const int w = words_;
  std::vector<std::uint64_t> res_mono;
  std::vector<cln::cl_I> res_coef;
  std::size_t capacity = 16;
  const std::size_t bound = std::min<std::size_t>(size() * q.size(), std::size_t{1} << 24);
  while (capacity < 2 * bound) capacity <<= 1;
  std::vector<std::uint32_t> slot(capacity, 0);  // index + 1 into res_coef, 0 = empty
  std::vector<std::uint64_t> m(static_cast<std::size_t>(w));
  auto insert_slot = [&](std::size_t index) {
    std::size_t h = hash(&res_mono[index * w], w) & (capacity - 1);
    while (slot[h]) h = (h + 1) & (capacity - 1);
    slot[h] = static_cast<std::uint32_t>(index + 1);
  };
  for (std::size_t i = 0; i < size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j) {
      const std::uint64_t *a = mono(i), *b = q.mono(j);
      for (int k = 0; k < w; ++k) {
        m[k] = a[k] + b[k];
        if (m[k] & high_bits) throw std::overflow_error("Poly::operator*(): an exponent exceeds " + std::to_string(max_exponent));
      }
      std::size_t h = hash(m.data(), w) & (capacity - 1);
      for (;;) {
        const std::uint32_t s = slot[h];
        if (!s) {
          slot[h] = static_cast<std::uint32_t>(res_coef.size() + 1);
          res_mono.insert(res_mono.end(), m.begin(), m.end());
          res_coef.push_back(coef_[i] * q.coef_[j]);
          if (2 * res_coef.size() > capacity) {  // grow and rehash
            capacity <<= 1;
            slot.assign(capacity, 0);
            for (std::size_t t = 0; t < res_coef.size(); ++t) insert_slot(t);
          }
          break;
        }
        if (same(&res_mono[(s - 1) * w], m.data(), w)) {
          res_coef[s - 1] = res_coef[s - 1] + coef_[i] * q.coef_[j];
          break;
        }
        h = (h + 1) & (capacity - 1);
      }
    }
  // Drop cancelled terms.
  std::size_t kept = 0;
  for (std::size_t t = 0; t < res_coef.size(); ++t) {
    if (cln::zerop(res_coef[t])) continue;
    if (kept != t) {
      std::copy(&res_mono[t * w], &res_mono[t * w] + w, &res_mono[kept * w]);
      res_coef[kept] = res_coef[t];
    }
    ++kept;
  }
  res_mono.resize(kept * w);
  res_coef.resize(kept);
  return from_terms(vars_, std::move(res_mono), std::move(res_coef));
}

Poly Poly::scaled(const cln::cl_I& c) const {
  if (cln::zerop(c)) return Poly(vars_);
  Poly p = *this;
  for (cln::cl_I& x : p.coef_) x = x * c;
  return p;
}

bool Poly::operator==(const Poly& q) const { return vars_ == q.vars_ && coef_ == q.coef_ && mono_ == q.mono_; }

cln::cl_I Poly::content() const {
  cln::cl_I g = 0;
  for (const cln::cl_I& c : coef_) g = cln::gcd(g, c);
  return g;
}

Poly Poly::divided(const cln::cl_I& c) const {
  Poly p = *this;
  for (cln::cl_I& x : p.coef_) x = cln::exquo(x, c);
  return p;
}

std::vector<int> Poly::common_exponents() const {
  std::vector<int> e(static_cast<std::size_t>(vars_), 0);
  if (is_zero()) return e;
  for (int k = 0; k < vars_; ++k) {
    int low = exponent(0, k);
    for (std::size_t t = 1; t < size() && low > 0; ++t) low = std::min(low, exponent(t, k));
    e[static_cast<std::size_t>(k)] = low;
  }
  return e;
}

Poly Poly::divided_by_monomial(const std::vector<int>& e) const {
  std::vector<std::uint64_t> m(static_cast<std::size_t>(words_), 0);
  for (int k = 0; k < vars_; ++k) m[static_cast<std::size_t>(k / 8)] |= static_cast<std::uint64_t>(e[static_cast<std::size_t>(k)]) << shift_of(k);
  Poly out(vars_);
  std::vector<std::uint64_t> here(static_cast<std::size_t>(words_));
  for (std::size_t t = 0; t < size(); ++t) {
    for (int w = 0; w < words_; ++w) {
      here[static_cast<std::size_t>(w)] = mono(t)[w] - m[static_cast<std::size_t>(w)];
      if (here[static_cast<std::size_t>(w)] & high_bits) throw std::invalid_argument("Poly::divided_by_monomial(): the monomial does not divide a term");
    }
    out.push(here.data(), coef_[t]);  // subtracting the same vector keeps the order
  }
  return out;
}

Poly Poly::leading_coefficient(int k) const { return coefficient_of(k, degree(k)); }

Poly Poly::times_power(int k, int d) const {
  if (d < 0 || d > max_exponent) throw std::invalid_argument("Poly::times_power(): exponent " + std::to_string(d) + " out of range");
  Poly x(vars_);
  std::vector<std::uint64_t> m(static_cast<std::size_t>(words_), 0);
  m[static_cast<std::size_t>(k / 8)] = static_cast<std::uint64_t>(d) << shift_of(k);
  x.push(m.data(), 1);
  return *this * x;
}

Poly Poly::coefficient_of(int k, int d) const {
  std::vector<std::uint64_t> res_mono;
  std::vector<cln::cl_I> res_coef;
  for (std::size_t t = 0; t < size(); ++t) {
    if (exponent(t, k) != d) continue;
    const std::size_t at = res_mono.size();
    res_mono.insert(res_mono.end(), mono(t), mono(t) + words_);
    res_mono[at + static_cast<std::size_t>(k / 8)] &= ~(std::uint64_t{0xFF} << shift_of(k));
    res_coef.push_back(coef_[t]);
  }
  return from_terms(vars_, std::move(res_mono), std::move(res_coef));
}

Poly Poly::subset(const std::vector<std::size_t>& terms) const {
  Poly out(vars_);
  for (std::size_t t : terms) out.push(mono(t), coef_[t]);
  return out;
}

std::vector<cln::cl_I> Poly::univariate(int keep, const std::vector<cln::cl_I>& point) const {
  std::vector<cln::cl_I> out(static_cast<std::size_t>(degree(keep) + 1), 0);
  std::vector<std::vector<cln::cl_I>> powers(static_cast<std::size_t>(vars_));
  for (std::size_t t = 0; t < size(); ++t) {
    cln::cl_I v = coef_[t];
    for (int k = 0; k < vars_; ++k) {
      if (k == keep) continue;
      const int e = exponent(t, k);
      if (!e) continue;
      auto& table = powers[static_cast<std::size_t>(k)];
      if (table.empty()) table.push_back(1);
      while (static_cast<int>(table.size()) <= e) table.push_back(table.back() * point[static_cast<std::size_t>(k)]);
      v = v * table[static_cast<std::size_t>(e)];
    }
    cln::cl_I& slot = out[static_cast<std::size_t>(exponent(t, keep))];
    slot = slot + v;
  }
  while (out.size() > 1 && cln::zerop(out.back())) out.pop_back();
  return out;
}

namespace mod61 {

std::uint64_t reduce(const cln::cl_I& x) {
  if (cln::integer_length(x) < 62) {  // the usual small coefficient: no bignum division
    const long long v = cln::cl_I_to_Q(x);
    const long long r = v % static_cast<long long>(prime);
    return static_cast<std::uint64_t>(r < 0 ? r + static_cast<long long>(prime) : r);
  }
  return cln::cl_I_to_UQ(cln::mod(x, cln::cl_I(prime)));
}

__extension__ typedef unsigned __int128 wide;  // GCC and Clang's 128-bit integer

std::uint64_t multiply(std::uint64_t a, std::uint64_t b) {
  const wide r = static_cast<wide>(a) * b;  // < 2^122
  std::uint64_t x = static_cast<std::uint64_t>(r & prime) + static_cast<std::uint64_t>(r >> 61);
  x = (x & prime) + (x >> 61);
  return x >= prime ? x - prime : x;
}

std::uint64_t add(std::uint64_t a, std::uint64_t b) {
  const std::uint64_t x = a + b;
  return x >= prime ? x - prime : x;
}

std::uint64_t subtract(std::uint64_t a, std::uint64_t b) { return add(a, b == 0 ? 0 : prime - b); }

std::uint64_t inverse(std::uint64_t a) {  // a^(p−2), a ≠ 0
  std::uint64_t result = 1, base = a;
  for (std::uint64_t e = prime - 2; e; e >>= 1) {
    if (e & 1) result = multiply(result, base);
    base = multiply(base, base);
  }
  return result;
}

int gcd_degree(std::vector<std::uint64_t> a, std::vector<std::uint64_t> b) {
  if (a.size() < b.size()) std::swap(a, b);
  while (!b.empty()) {
    // a mod b
    const std::uint64_t lead = inverse(b.back());
    while (a.size() >= b.size() && !a.empty()) {
      const std::uint64_t f = multiply(a.back(), lead);
      const std::size_t shift = a.size() - b.size();
      for (std::size_t k = 0; k < b.size(); ++k) a[shift + k] = add(a[shift + k], prime - multiply(f, b[k]));
      while (!a.empty() && a.back() == 0) a.pop_back();
    }
    std::swap(a, b);
  }
  return static_cast<int>(a.size()) - 1;
}

}  // namespace mod61

template <class F>
void Poly::for_each_power(std::size_t t, F f) const {
  const std::uint64_t* m = mono(t);
  for (int w = 0; w < words_; ++w)
    for (std::uint64_t word = m[w]; word;) {
      const int k = 8 * w + __builtin_clzll(word) / 8;  // the first nonzero exponent left in the word (shift_of: byte 0 is x_{8w})
      const int e = static_cast<int>((word >> shift_of(k)) & 0xFF);
      word &= ~(std::uint64_t{0xFF} << shift_of(k));
      if (!f(k, e)) return;
    }
}

std::vector<std::uint64_t> Poly::univariate_mod(int keep, const std::vector<std::uint64_t>& point) const {
  std::vector<std::uint64_t> out(static_cast<std::size_t>(degree(keep) + 1), 0);
  std::vector<std::vector<std::uint64_t>> powers(static_cast<std::size_t>(vars_));
  for (std::size_t t = 0; t < size(); ++t) {
    std::uint64_t v = mod61::reduce(coef_[t]);
    for_each_power(t, [&](int k, int e) {
      if (k == keep) return true;
      auto& table = powers[static_cast<std::size_t>(k)];
      if (table.empty()) table.push_back(1);
      while (static_cast<int>(table.size()) <= e) table.push_back(mod61::multiply(table.back(), point[static_cast<std::size_t>(k)]));
      v = mod61::multiply(v, table[static_cast<std::size_t>(e)]);
      return v != 0;
    });
    std::uint64_t& slot = out[static_cast<std::size_t>(exponent(t, keep))];
    slot = mod61::add(slot, v);
  }
  while (!out.empty() && out.back() == 0) out.pop_back();
  return out;
}

std::vector<std::uint64_t> Poly::on_line_mod(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) const {
  std::vector<std::uint64_t> out, term, next;
  // (a_k + b_k t)^e for each symbol k, e = 0, 1, … as far as a term needs.
  std::vector<std::vector<std::vector<std::uint64_t>>> powers(static_cast<std::size_t>(vars_));
  for (std::size_t t = 0; t < size(); ++t) {
    term.assign(1, mod61::reduce(coef_[t]));
    for_each_power(t, [&](int k, int e) {
      auto& table = powers[static_cast<std::size_t>(k)];
      if (table.empty()) table.push_back({1});
      while (static_cast<int>(table.size()) <= e) {
        const std::vector<std::uint64_t>& last = table.back();
        std::vector<std::uint64_t> times(last.size() + 1, 0);  // last · (a_k + b_k t)
        for (std::size_t i = 0; i < last.size(); ++i) {
          times[i] = mod61::add(times[i], mod61::multiply(last[i], a[static_cast<std::size_t>(k)]));
          times[i + 1] = mod61::multiply(last[i], b[static_cast<std::size_t>(k)]);
        }
        table.push_back(std::move(times));
      }
      const std::vector<std::uint64_t>& f = table[static_cast<std::size_t>(e)];
      next.assign(term.size() + f.size() - 1, 0);
      for (std::size_t i = 0; i < term.size(); ++i)
        for (std::size_t j = 0; j < f.size(); ++j) next[i + j] = mod61::add(next[i + j], mod61::multiply(term[i], f[j]));
      term.swap(next);
      return true;
    });
    if (out.size() < term.size()) out.resize(term.size(), 0);
    for (std::size_t i = 0; i < term.size(); ++i) out[i] = mod61::add(out[i], term[i]);
  }
  while (!out.empty() && out.back() == 0) out.pop_back();
  return out;
}

std::uint64_t Poly::evaluate_mod(const std::vector<std::uint64_t>& point) const {
  if (vars_ == 0) return is_zero() ? 0 : mod61::reduce(coef_.front());
  const std::vector<std::uint64_t> c = univariate_mod(0, point);  // x_0 kept, then evaluated
  std::uint64_t v = 0;
  for (std::size_t d = c.size(); d-- > 0;) v = mod61::add(mod61::multiply(v, point[0]), c[d]);
  return v;
}

int Poly::total_degree() const {
  int most = 0;
  for (std::size_t t = 0; t < size(); ++t) {
    int d = 0;
    for_each_power(t, [&d](int, int e) {
      d += e;
      return true;
    });
    most = std::max(most, d);
  }
  return most;
}

cln::cl_I Poly::evaluate(const std::vector<cln::cl_I>& point) const {
  if (vars_ == 0) return is_zero() ? cln::cl_I(0) : coef_.front();
  // x_0 is kept as the univariate variable, then evaluated.
  const std::vector<cln::cl_I> c = univariate(0, point);
  cln::cl_I v = 0;
  for (std::size_t d = c.size(); d-- > 0;) v = v * point[0] + c[d];
  return v;
}

GiNaC::ex Poly::to_ex(const Symbols& symbols) const {
  if (static_cast<int>(symbols.all().size()) != vars_) throw std::invalid_argument("Poly::to_ex(): the symbols do not match");
  // The sum as (monomial, coefficient) pairs and the constant term apart, as
  // GiNaC keeps it: no term is split into that form again.
  GiNaC::epvector pairs;
  pairs.reserve(size());
  GiNaC::ex constant = 0;
  for (std::size_t t = 0; t < size(); ++t) {
    GiNaC::epvector powers;
    for (int k = 0; k < vars_; ++k)
      if (const int e = exponent(t, k)) powers.emplace_back(symbols.all()[static_cast<std::size_t>(k)].symbol, e);
    const GiNaC::numeric c{cln::cl_N(coef_[t])};
    if (powers.empty()) {
      constant = c;
    } else if (powers.size() == 1) {
      const GiNaC::expair& p = powers.front();
      pairs.emplace_back(p.coeff.is_equal(1) ? p.rest : GiNaC::pow(p.rest, p.coeff), c);
    } else {
      pairs.emplace_back(GiNaC::dynallocate<GiNaC::mul>(std::move(powers)).setflag(GiNaC::status_flags::evaluated), c);
    }
  }
  if (pairs.empty()) return constant;
  if (pairs.size() == 1 && constant.is_zero()) return GiNaC::add(std::move(pairs), constant);
  return GiNaC::dynallocate<GiNaC::add>(std::move(pairs), constant).setflag(GiNaC::status_flags::evaluated);
}

namespace {

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
T get(const std::string& in, std::size_t& at) {
  if (in.size() - at < sizeof(T) || at > in.size()) throw std::invalid_argument("Poly::read(): the record is truncated");
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return v;
}

}  // namespace

void Poly::write(std::string& out) const {
  // Terms, then per term its packed exponents and its coefficient: a machine
  // integer when it fits in 62 bits (tag 0), else its decimal digits (tag 1).
  put<std::uint64_t>(out, size());
  if (!mono_.empty()) out.append(reinterpret_cast<const char*>(mono_.data()), mono_.size() * sizeof(std::uint64_t));
  for (const cln::cl_I& c : coef_) {
    if (cln::integer_length(c) <= 62) {
      put<std::uint8_t>(out, 0);
      put<std::int64_t>(out, cln::cl_I_to_Q(c));
    } else {
      std::ostringstream digits;
      digits << c;
      put<std::uint8_t>(out, 1);
      put<std::uint64_t>(out, digits.str().size());
      out += digits.str();
    }
  }
}

Poly Poly::read(const std::string& in, std::size_t& at, int vars) {
  Poly p(vars);
  const auto terms = get<std::uint64_t>(in, at);
  const std::size_t words = static_cast<std::size_t>(p.words_);
  if (terms > (in.size() - at) / (words * sizeof(std::uint64_t) + 1)) throw std::invalid_argument("Poly::read(): the record is truncated");
  p.mono_.resize(terms * words);
  if (!p.mono_.empty()) std::memcpy(p.mono_.data(), in.data() + at, p.mono_.size() * sizeof(std::uint64_t));  // the zero polynomial has no words
  at += p.mono_.size() * sizeof(std::uint64_t);
  p.coef_.reserve(terms);
  for (std::uint64_t t = 0; t < terms; ++t) {
    if (get<std::uint8_t>(in, at) == 0) {
      p.coef_.emplace_back(static_cast<long long>(get<std::int64_t>(in, at)));
    } else {
      const auto size = get<std::uint64_t>(in, at);
      if (size > in.size() - at) throw std::invalid_argument("Poly::read(): the record is truncated");
      p.coef_.push_back(cln::cl_I(in.substr(at, size).c_str()));
      at += size;
    }
  }
  return p;
}

Poly determinant(const std::vector<Poly>& m, int n, int vars) {
  if (n < 0 || n > max_moving_clusters || m.size() != static_cast<std::size_t>(n) * static_cast<std::size_t>(n))
    throw std::invalid_argument("determinant(): expected an n x n matrix, n <= " + std::to_string(max_moving_clusters));
  if (n == 0) return Poly::constant(vars, 1);
  // minor(S): det of the last |S| rows on the columns of S.
  std::unordered_map<std::uint32_t, Poly> memo;
  std::function<Poly(std::uint32_t)> minor = [&](std::uint32_t columns) -> Poly {
    if (!columns) return Poly::constant(vars, 1);
    if (auto it = memo.find(columns); it != memo.end()) return it->second;
    const int row = n - __builtin_popcount(columns);
    Poly sum(vars);
    int position = 0;
    for (int c = 0; c < n; ++c) {
      if (!(columns >> c & 1u)) continue;
      const Poly& entry = m[static_cast<std::size_t>(row * n + c)];
      if (!entry.is_zero()) {
        const Poly rest = minor(columns & ~(1u << c));
        if (!rest.is_zero()) sum += position % 2 ? -(entry * rest) : entry * rest;
      }
      ++position;
    }
    return memo.emplace(columns, std::move(sum)).first->second;
  };
  return minor((n == 32 ? 0u : (1u << n)) - 1u);
}

}  // namespace superball::symbolic::detail
