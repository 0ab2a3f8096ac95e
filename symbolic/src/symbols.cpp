#include "superball/symbolic/symbols.hpp"

#include <sstream>
#include <stdexcept>

#include "polynomial.hpp"
#include "superball/cases/error.hpp"
#include "superball/cases/vocabulary.hpp"

namespace superball::symbolic {
namespace {

std::string subscript(int value) {
  static const char* const digits[] = {"₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"};
  std::string out;
  for (char c : std::to_string(value)) out += digits[c - '0'];
  return out;
}

bool short_pair(const Pair& p) { return p.i < 10 && p.j < 10; }

std::string pair_text(const Pair& p) { return subscript(p.i) + (short_pair(p) ? "" : ",") + subscript(p.j); }
std::string pair_latex(const Pair& p) { return std::to_string(p.i) + (short_pair(p) ? "" : ",") + std::to_string(p.j); }

}  // namespace

std::string pair_code(const Pair& p) { return std::to_string(p.i) + (short_pair(p) ? "" : "_") + std::to_string(p.j); }

Symbols::Symbols(const Pattern& pattern, Obstacle obstacle) : pattern_(pattern), obstacle_(obstacle) {
  pattern_.check();
  const int n = pattern_.bodies;
  for (int i = 1; i <= n; ++i) {
    if (i == n && obstacle_ == Obstacle::Infinite) break;
    SymbolInfo s;
    s.kind = SymbolKind::Mass;
    s.body = i;
    s.ascii = "m" + std::to_string(i);
    s.text = "m" + subscript(i);
    s.latex = "m_{" + std::to_string(i) + "}";
    s.symbol = GiNaC::possymbol(s.ascii, s.latex);
    add(std::move(s));
  }
  for (const Pair& p : pattern_.diagonal) {
    SymbolInfo s;
    s.kind = SymbolKind::Diagonal;
    s.first = s.second = p;
    s.ascii = "K" + pair_code(p);
    s.text = "K" + pair_text(p);
    s.latex = "K_{" + pair_latex(p) + "}";
    s.symbol = GiNaC::possymbol(s.ascii, s.latex);
    add(std::move(s));
  }
  const Vocabulary& v = Vocabulary::paper();
  for (const auto& [p, q] : pattern_.couplings) {
    SymbolInfo s;
    s.kind = SymbolKind::Coupling;
    s.first = p;
    s.second = q;
    if (n == v.bodies())
      if (const auto k = v.alpha_index(p, q)) s.alpha = *k;
    if (s.alpha) {
      s.ascii = "alpha" + std::to_string(s.alpha);
      s.text = "α" + subscript(s.alpha);
      s.latex = "\\alpha_{" + std::to_string(s.alpha) + "}";
    } else {
      s.ascii = "c_" + pair_code(p) + "_" + pair_code(q);
      s.text = "c" + pair_text(p) + "," + pair_text(q);
      s.latex = "c_{" + pair_latex(p) + "," + pair_latex(q) + "}";
    }
    s.symbol = GiNaC::symbol(s.ascii, s.latex);
    add(std::move(s));
  }
  SymbolInfo s;
  s.kind = SymbolKind::FallSpeed;
  s.ascii = s.text = s.latex = "a";
  s.symbol = GiNaC::possymbol("a");
  a_ = s.symbol;
  add(std::move(s));
}

void Symbols::add(SymbolInfo info) {
  info.rank = static_cast<int>(all_.size());
  index_.emplace(info.symbol, all_.size());
  all_.push_back(std::move(info));
}

const GiNaC::ex& Symbols::mass(int body) const {
  if (body < 1 || body > bodies())
    throw std::invalid_argument("Symbols::mass(): body " + std::to_string(body) + " is outside 1.." + std::to_string(bodies()));
  if (body == bodies() && obstacle_ == Obstacle::Infinite)
    throw std::invalid_argument("Symbols::mass(): body " + std::to_string(body) + " is the fixed obstacle (infinite mass)");
  return all_[static_cast<std::size_t>(body - 1)].symbol;
}

const GiNaC::ex& Symbols::diagonal(const Pair& p) const {
  for (const SymbolInfo& s : all_)
    if (s.kind == SymbolKind::Diagonal && s.first == p) return s.symbol;
  throw std::invalid_argument("Symbols::diagonal(): K_" + p.name() + " is not declared in the pattern");
}

const GiNaC::ex& Symbols::coupling(const Pair& p, const Pair& q) const {
  for (const SymbolInfo& s : all_)
    if (s.kind == SymbolKind::Coupling && ((s.first == p && s.second == q) || (s.first == q && s.second == p))) return s.symbol;
  throw std::invalid_argument("Symbols::coupling(): the coupling " + p.name() + "/" + q.name() + " is not declared in the pattern");
}

GiNaC::ex Symbols::entry(const Pair& p, const Pair& q) const {
  for (const SymbolInfo& s : all_) {
    if (p == q && s.kind == SymbolKind::Diagonal && s.first == p) return s.symbol;
    if (p != q && s.kind == SymbolKind::Coupling && ((s.first == p && s.second == q) || (s.first == q && s.second == p)))
      return s.symbol;
  }
  return 0;
}

const SymbolInfo& Symbols::info(const GiNaC::ex& s) const {
  const auto it = index_.find(s);
  if (it == index_.end()) {
    std::ostringstream os;
    os << s;
    throw std::invalid_argument("Symbols::info(): '" + os.str() + "' is not a symbol of this pattern");
  }
  return all_[it->second];
}

const SymbolInfo* Symbols::find(const GiNaC::ex& s) const {
  const auto it = index_.find(s);
  return it == index_.end() ? nullptr : &all_[it->second];
}

bool Symbols::is_coupling(const GiNaC::ex& s) const {
  const auto it = index_.find(s);
  return it != index_.end() && all_[it->second].kind == SymbolKind::Coupling;
}

const GiNaC::ex& Symbols::by_name(const std::string& name) const {
  for (const SymbolInfo& s : all_)
    if (s.ascii == name) return s.symbol;
  std::string list;
  for (const SymbolInfo& s : all_) list += (list.empty() ? "" : ", ") + s.ascii;
  throw std::invalid_argument("Symbols::by_name(): no parameter '" + name + "' in this pattern (it has " + list + ")");
}

GiNaC::symtab Symbols::table() const {
  GiNaC::symtab t;
  for (const SymbolInfo& s : all_) t[s.ascii] = s.symbol;
  return t;
}

std::vector<Monomial> Symbols::monomials(const GiNaC::ex& p) const {
  std::vector<Monomial> out;
  try {
    for (const detail::Term& t : detail::terms(GiNaC::expand(p))) {
      Monomial m;
      m.coefficient = t.coefficient;
      for (const auto& [symbol, exponent] : t.powers) m.powers.emplace_back(info(symbol).rank, exponent);
      out.push_back(std::move(m));
    }
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("Symbols::monomials(): " + without_function_prefix(e.what()));
  }
  return out;
}

}  // namespace superball::symbolic
