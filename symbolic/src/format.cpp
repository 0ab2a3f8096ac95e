// Term order and the readable forms of format.hpp: polynomials, fractions,
// conditions, isolated and grouped forms.  The elimination, the names and
// the titles are in format_elimination.cpp; the reports of a derivation in
// present/ (present/derivation.hpp).
#include "superball/symbolic/format.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "polynomial.hpp"
#include "superball/cases/vocabulary.hpp"

#include "format_terms.hpp"

namespace superball::symbolic {
namespace {

std::string superscript_digits(int value) {
  static const char* const sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string out;
  for (char c : std::to_string(value)) out += sup[c - '0'];
  return out;
}

std::string number_text(const GiNaC::numeric& c, Style style) {
  std::ostringstream os;
  if (c.is_integer()) {
    os << c;
    return os.str();
  }
  if (style == Style::Latex) {
    os << "\\frac{" << c.numer() << "}{" << c.denom() << "}";
    return os.str();
  }
  os << "(" << c.numer() << "/" << c.denom() << ")";
  return os.str();
}

/// Sort key of a term: the ranks of its symbols with multiplicity, ascending.
std::vector<int> term_key(const detail::Term& t, const Symbols& symbols) {
  std::vector<int> key;
  for (const auto& [s, e] : t.powers)
    for (int k = 0; k < e; ++k) key.push_back(symbols.info(s).rank);
  std::sort(key.begin(), key.end());
  return key;
}

bool has_coupling(const detail::Term& t, const Symbols& symbols) {
  return std::any_of(t.powers.begin(), t.powers.end(), [&](const auto& pe) { return symbols.is_coupling(pe.first); });
}

/// \p ts in the canonical order (format.hpp).
std::vector<detail::Term> sort_terms(std::vector<detail::Term> ts, const Symbols& symbols) {
  // Each key once (a long polynomial has thousands of terms), then one stable sort.
  std::vector<std::pair<bool, std::vector<int>>> keys;
  keys.reserve(ts.size());
  for (const detail::Term& t : ts) keys.emplace_back(!t.coefficient.is_positive(), term_key(t, symbols));
  std::vector<std::size_t> order(ts.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return keys[x] < keys[y]; });
  std::vector<detail::Term> out;
  out.reserve(ts.size());
  for (std::size_t k : order) out.push_back(std::move(ts[k]));
  return out;
}

}  // namespace

namespace detail {

std::string subscript_digits(const std::string& digits) {
  static const char* const sub[] = {"₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"};
  std::string out;
  for (char c : digits) out += (c >= '0' && c <= '9') ? sub[c - '0'] : std::string(1, c);
  return out;
}

const char* minus(Style style) { return style == Style::Text ? "−" : "-"; }

/// A term with a positive coefficient |c|: "2m₁K₁₂", "α₂²", "a" (text),
/// "2*m1*K12", "alpha2^2" (ASCII, readable by GiNaC::parser).
std::string term_text(const detail::Term& t, const Symbols& symbols, Style style) {
  std::vector<std::pair<int, std::string>> factors;  // (print order, text)
  for (const auto& [s, e] : t.powers) {
    const SymbolInfo& info = symbols.info(s);
    std::string f = info.name(style);
    if (e != 1)
      f += style == Style::Latex ? "^{" + std::to_string(e) + "}" : style == Style::Ascii ? "^" + std::to_string(e) : superscript_digits(e);
    // a first in a product (a(K₁₄ + …)), then masses, K's, couplings.
    factors.emplace_back(info.kind == SymbolKind::FallSpeed ? -1 : info.rank, f);
  }
  std::sort(factors.begin(), factors.end());
  const GiNaC::numeric c = GiNaC::abs(t.coefficient);
  std::string out = c.is_equal(1) && !factors.empty() ? "" : number_text(c, style);
  // LaTeX: "2m_{1}", "K_{12} K_{14}" (a space between two symbols only); ASCII: "2*m1*K12".
  for (const auto& f : factors) {
    if (style == Style::Ascii)
      out += out.empty() ? "" : "*";
    else if (style == Style::Latex && !out.empty() && !(out.back() >= '0' && out.back() <= '9'))
      out += " ";
    out += f.second;
  }
  return out;
}

std::vector<detail::Term> sorted_terms(const GiNaC::ex& p, const Symbols& symbols) {
  try {
    return sort_terms(detail::terms(GiNaC::expand(p)), symbols);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("format_polynomial(): ") + e.what());
  }
}

std::string relation_text(Relation r, bool turned, Style style) {
  if (style == Style::Latex) return r == Relation::Greater ? (turned ? "<" : ">") : (turned ? "\\le" : "\\ge");
  if (style == Style::Ascii) return r == Relation::Greater ? (turned ? "<" : ">") : (turned ? "<=" : ">=");
  return r == Relation::Greater ? (turned ? "<" : ">") : (turned ? "≤" : "≥");
}

}  // namespace detail

using detail::minus;
using detail::relation_text;
using detail::sorted_terms;
using detail::subscript_digits;
using detail::term_text;

namespace {

/// Terms joined with signs; the first term carries its own sign.
std::string join(const std::vector<detail::Term>& ts, const Symbols& symbols, Style style, bool negate = false) {
  if (ts.empty()) return "0";
  std::string out;
  bool first = true;
  for (const detail::Term& t : ts) {
    const bool negative = t.coefficient.is_negative() != negate;
    if (first)
      out += negative ? minus(style) : "";
    else
      out += negative ? std::string(" ") + minus(style) + " " : " + ";
    out += term_text(t, symbols, style);
    first = false;
  }
  return out;
}

/// Split p into rational content c > 0 (sign moved in when all terms are
/// negative), the common monomial, and the primitive rest.
struct Split {
  GiNaC::numeric content = 1;
  GiNaC::ex monomial = 1;
  std::vector<detail::Term> rest;  ///< the primitive rest, term by term (unsorted)
};

Split split_common(const GiNaC::ex& p, const Symbols& symbols) {
  Split s;
  auto ts = detail::terms(GiNaC::expand(p));
  if (ts.size() <= 1) {
    s.rest = std::move(ts);
    return s;
  }
  GiNaC::numeric num = 0, den = 1;
  bool all_negative = true;
  for (const detail::Term& t : ts) {
    num = GiNaC::gcd(num, t.coefficient.numer());
    den = GiNaC::lcm(den, t.coefficient.denom());
    all_negative = all_negative && t.coefficient.is_negative();
  }
  s.content = (all_negative ? -num : num) / den;
  std::vector<std::pair<GiNaC::ex, int>> common;  // (symbol, lowest exponent > 0)
  for (const auto& [sym, e0] : ts.front().powers) {
    int low = e0;
    for (const detail::Term& t : ts) {
      int here = 0;
      for (const auto& [s2, e2] : t.powers)
        if (s2.is_equal(sym)) here = e2;
      low = std::min(low, here);
    }
    if (low > 0) {
      s.monomial *= GiNaC::pow(sym, low);
      common.emplace_back(sym, low);
    }
  }
  (void)symbols;
  // The rest, term by term (the content and the monomial divide every term exactly).
  s.rest.reserve(ts.size());
  for (detail::Term& t : ts) {
    detail::Term r;
    r.coefficient = t.coefficient / s.content;
    for (auto& [sym, e] : t.powers) {
      int left = e;
      for (const auto& [c, low] : common)
        if (c.is_equal(sym)) left -= low;
      if (left) r.powers.emplace_back(sym, left);
    }
    s.rest.push_back(std::move(r));
  }
  return s;
}

/// "a(K₁₄ + α₂ − m₁)", "−2(…)", "m₁ + K₁₂" (no common factor), "3a".
std::string factored(const GiNaC::ex& p, const Symbols& symbols, Style style, bool* single) {
  Split s = split_common(p, symbols);
  const auto rest = sort_terms(std::move(s.rest), symbols);
  std::string prefix;
  GiNaC::ex front = s.content * s.monomial;
  if (!front.is_equal(1)) {
    const auto ft = detail::terms(GiNaC::expand(front));
    prefix = join(ft, symbols, style);
  }
  if (prefix.empty()) {
    if (single) *single = rest.size() <= 1;
    return join(rest, symbols, style);
  }
  if (single) *single = true;
  if (rest.size() == 1 && rest.front().powers.empty() && rest.front().coefficient.is_equal(1)) return prefix;
  if (prefix == minus(style)) return prefix + "(" + join(rest, symbols, style) + ")";
  return prefix + (style == Style::Latex ? "\\left(" : "(") + join(rest, symbols, style) + (style == Style::Latex ? "\\right)" : ")");
}

/// \p latex with \left( and \right) written ( and ).
std::string without_sized_parentheses(std::string latex) {
  for (const char* sized : {"\\left", "\\right"})
    for (std::size_t at = latex.find(sized); at != std::string::npos; at = latex.find(sized, at)) latex.erase(at, std::string(sized).size());
  return latex;
}

}  // namespace

std::string format_polynomial(const GiNaC::ex& p, const Symbols& symbols, Style style) {
  return join(sorted_terms(p, symbols), symbols, style);
}

std::string format_fraction(const Fraction& f, const Symbols& symbols, Style style) {
  if (style == Style::Ascii) {
    if (f.denominator.is_equal(1)) return format_polynomial(f.numerator, symbols, style);
    return "(" + format_polynomial(f.numerator, symbols, style) + ")/(" + format_polynomial(f.denominator, symbols, style) + ")";
  }
  bool single_num = true, single_den = true;
  const std::string num = factored(f.numerator, symbols, style, &single_num);
  if (f.denominator.is_equal(1)) return num;
  const std::string den = factored(f.denominator, symbols, style, &single_den);
  if (style == Style::Latex && num.size() + den.size() < 160) return "\\frac{" + num + "}{" + den + "}";
  if (style == Style::Latex) {
    // Plain parentheses: TeX can break an inline formula after the + and - inside them, never inside \left( … \right).
    const std::string n = without_sized_parentheses(num), d = without_sized_parentheses(den);
    return (single_num ? n : "(" + n + ")") + "/" + (single_den ? d : "(" + d + ")");
  }
  return (single_num ? num : "(" + num + ")") + "/" + (single_den ? den : "(" + den + ")");
}

namespace {

/// format_condition() of the polynomial whose sorted terms are \p ts.
std::string condition_from_terms(const std::vector<detail::Term>& ts, Relation relation, const Symbols& symbols, Style style) {
  if (style == Style::Ascii) return join(ts, symbols, style) + " " + relation_text(relation, false, style) + " 0";
  std::vector<detail::Term> pos, neg;
  for (const detail::Term& t : ts) (t.coefficient.is_positive() ? pos : neg).push_back(t);
  const std::string rel = relation_text(relation, false, style), turned = relation_text(relation, true, style);
  if (ts.empty()) return "0 " + rel + " 0";
  if (pos.empty()) {
    std::vector<detail::Term> left, right;
    for (const detail::Term& t : neg) (has_coupling(t, symbols) ? left : right).push_back(t);
    if (left.empty()) return "0 " + rel + " " + join(right, symbols, style, true);
    if (right.empty()) return join(left, symbols, style) + " " + rel + " 0";
    return join(left, symbols, style) + " " + rel + " " + join(right, symbols, style, true);
  }
  if (neg.empty()) return join(pos, symbols, style) + " " + rel + " 0";
  auto couples = [&](const std::vector<detail::Term>& side) {
    return std::any_of(side.begin(), side.end(), [&](const detail::Term& t) { return has_coupling(t, symbols); });
  };
  const bool swap = neg.size() < pos.size() || (neg.size() == pos.size() && couples(neg) && !couples(pos));
  if (swap) return join(neg, symbols, style, true) + " " + turned + " " + join(pos, symbols, style);
  return join(pos, symbols, style) + " " + rel + " " + join(neg, symbols, style, true);
}

}  // namespace

std::string format_condition(const GiNaC::ex& p, Relation relation, const Symbols& symbols, Style style) {
  return condition_from_terms(sorted_terms(p, symbols), relation, symbols, style);
}

StyledText format_condition_styles(const ConditionForm& form, Relation relation, const Symbols& symbols) {
  if (!form.sign_proved())
    return {format_condition(form, relation, symbols, Style::Ascii), format_condition(form, relation, symbols, Style::Text),
            format_condition(form, relation, symbols, Style::Latex)};
  const auto ts = sorted_terms(form.numerator, symbols);  // once for the three
  return {condition_from_terms(ts, relation, symbols, Style::Ascii), condition_from_terms(ts, relation, symbols, Style::Text),
          condition_from_terms(ts, relation, symbols, Style::Latex)};
}

std::string format_condition(const ConditionForm& form, Relation relation, const Symbols& symbols, Style style) {
  if (form.sign_proved()) return format_condition(form.numerator, relation, symbols, style);
  const Fraction f{form.numerator, form.denominator};
  const std::string note = style == Style::Latex ? "\\quad\\text{(sign of the denominator not proved)}"
                                                 : "  (sign of the denominator not proved)";
  return format_fraction(f, symbols, style) + " " + relation_text(relation, false, style) + " 0" + (style == Style::Ascii ? "" : note);
}

/// Up to this many characters a numerator over a named part stays in one \frac.
constexpr std::size_t kShortFractionChars = 120;

std::string named_part_name(int k, Style style) {
  const std::string i = std::to_string(k);
  if (style == Style::Latex) return "S_{" + i + "}";
  if (style == Style::Text) return "S" + subscript_digits(i);
  return "S" + i;
}

std::string format_readable(const Readable& r, Relation relation, const Symbols& symbols, Style style) {
  const std::string rel = relation_text(relation, false, style);
  if (r.subject.is_zero()) {  // grouped: Q S REL −R
    const std::string name = named_part_name(r.named, style);
    std::string left;
    if (style == Style::Ascii) {
      left = "(" + format_polynomial(r.quotient, symbols, style) + ")*" + name;
    } else {
      bool single = true;
      const std::string q = factored(r.quotient, symbols, style, &single);
      left = (single && q.find(' ') == std::string::npos ? q : "(" + q + ")") + (style == Style::Latex ? " " : "") + name;
    }
    const GiNaC::ex right = -r.remainder;
    std::string rtext = right.is_zero() ? "0" : style == Style::Ascii ? format_polynomial(right, symbols, style) : factored(right, symbols, style, nullptr);
    return left + " " + rel + " " + rtext;
  }
  std::string right = r.quotient.is_zero() ? "" : format_polynomial(r.quotient, symbols, style);
  if (!r.remainder.is_zero()) {
    const std::string name = named_part_name(r.named, style);
    std::string fraction;
    bool negative = false;
    if (style == Style::Ascii) {
      fraction = "(" + format_polynomial(r.remainder, symbols, style) + ")/" + name;
    } else {
      // The remainder's sign in front when all its terms are negative: "− K₁₂(…)/S₁".
      const auto ts = detail::terms(GiNaC::expand(r.remainder));
      negative = std::all_of(ts.begin(), ts.end(), [](const detail::Term& t) { return t.coefficient.is_negative(); });
      bool single = true;
      const std::string top = factored(negative ? GiNaC::ex(-r.remainder) : r.remainder, symbols, style, &single);
      if (style == Style::Latex)  // a long numerator as a factor 1/S times a sum that a display can break
        fraction = top.size() < kShortFractionChars ? "\\frac{" + top + "}{" + name + "}"
                                                    : "\\frac{1}{" + name + "}\\left(" + format_polynomial(negative ? GiNaC::ex(-r.remainder) : r.remainder, symbols, style) + "\\right)";
      else
        fraction = (single ? top : "(" + top + ")") + "/" + name;
    }
    if (right.empty())
      right = (negative ? minus(style) : "") + fraction;
    else
      right += std::string(negative ? std::string(" ") + minus(style) + " " : " + ") + fraction;
  }
  if (right.empty()) right = "0";
  return format_polynomial(r.subject, symbols, style) + " " + rel + " " + right;
}

CommonFactor format_common_factor(const GiNaC::ex& p, const Symbols& symbols, Style style) {
  Split s = split_common(p, symbols);
  const auto rest = sort_terms(std::move(s.rest), symbols);
  const GiNaC::ex front = s.content * s.monomial;
  CommonFactor out;
  out.negative = s.content.is_negative();
  out.factor = front.is_equal(1) || front.is_equal(-1) ? "1" : join(detail::terms(GiNaC::expand(out.negative ? -front : front)), symbols, style);
  out.rest = join(rest, symbols, style);
  out.rest_is_one = rest.size() == 1 && rest.front().powers.empty() && rest.front().coefficient.is_equal(1);
  return out;
}

std::string format_form(const ConditionForm& form, Relation relation, const Symbols& symbols, Style style) {
  if (form.eliminated) return format_eliminated(*form.eliminated, relation, symbols, style);
  return form.readable ? format_readable(*form.readable, relation, symbols, style) : format_condition(form, relation, symbols, style);
}

}  // namespace superball::symbolic
