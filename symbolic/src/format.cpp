#include "superball/symbolic/format.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "polynomial.hpp"
#include "superball/cases/vocabulary.hpp"

namespace superball::symbolic {
namespace {

std::string subscript_digits(const std::string& digits) {
  static const char* const sub[] = {"₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"};
  std::string out;
  for (char c : digits) out += (c >= '0' && c <= '9') ? sub[c - '0'] : std::string(1, c);
  return out;
}

std::string superscript_digits(int value) {
  static const char* const sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string out;
  for (char c : std::to_string(value)) out += sup[c - '0'];
  return out;
}

const char* minus(Style style) { return style == Style::Text ? "−" : "-"; }

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

std::vector<detail::Term> sorted_terms(const GiNaC::ex& p, const Symbols& symbols) {
  try {
    return sort_terms(detail::terms(GiNaC::expand(p)), symbols);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("format_polynomial(): ") + e.what());
  }
}

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

std::string relation_text(Relation r, bool turned, Style style) {
  if (style == Style::Latex) return r == Relation::Greater ? (turned ? "<" : ">") : (turned ? "\\le" : "\\ge");
  if (style == Style::Ascii) return r == Relation::Greater ? (turned ? "<" : ">") : (turned ? "<=" : ">=");
  return r == Relation::Greater ? (turned ? "<" : ">") : (turned ? "≤" : "≥");
}

std::string order_text(const GiNaC::numeric& k, Style style) {
  std::ostringstream os;
  os << k;
  if (style == Style::Latex) return "\\varepsilon^{" + os.str() + "}";
  return "ε^" + os.str();
}

std::string math(const std::string& s, Style style) { return style == Style::Latex ? "$" + s + "$" : s; }

/// Prose of the library (proofs, checks, case names) in \p style: "Z^T A Z"
/// becomes ZᵀAZ or $Z^{T}AZ$; LaTeX specials are escaped.
std::string prose(const std::string& s, Style style) {
  static const std::string zaz = "Z^T A Z";
  std::string out;
  for (std::size_t k = 0; k < s.size();) {
    if (s.compare(k, zaz.size(), zaz) == 0) {
      out += style == Style::Latex ? "$Z^{T}AZ$" : style == Style::Text ? "ZᵀAZ" : zaz;
      k += zaz.size();
      continue;
    }
    const char c = s[k++];
    if (style == Style::Latex && std::string("{}_%#&$").find(c) != std::string::npos)
      out += std::string("\\") + c;
    else if (style == Style::Latex && (c == '^' || c == '~'))
      out += std::string("\\") + c + "{}";
    else
      out += c;
  }
  return out;
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

std::string format_form(const ConditionForm& form, Relation relation, const Symbols& symbols, Style style) {
  if (form.eliminated) return format_eliminated(*form.eliminated, relation, symbols, style);
  return form.readable ? format_readable(*form.readable, relation, symbols, style) : format_condition(form, relation, symbols, style);
}

// ---------------------------------------------------------------------------
// The elimination of a case's reduced system (derivation.hpp, Elimination).
namespace {

/// "p₅", "l₄₅", "y₅", "V₁" (text); "p_{5}", "l_{45}" (LaTeX); "p5", "l4_5" (ASCII); clusters 0-based.
std::string elimination_name(const char* letter, std::size_t i, std::optional<std::size_t> j, Style style) {
  std::string digits = std::to_string(i + 1);
  if (j) digits += (style == Style::Ascii || i + 1 >= 10 || *j + 1 >= 10 ? (style == Style::Ascii ? "_" : ",") : "") + std::to_string(*j + 1);
  if (style == Style::Latex) return std::string(letter) + "_{" + digits + "}";
  if (style == Style::Text) return letter + subscript_digits(digits);
  return letter + digits;
}

/// Factors of a product in \p style: "l₄₅²p₅", "l_{45}^{2} p_{5}", "l4_5^2*p5".
std::string product(const std::vector<std::string>& factors, Style style) {
  std::string out;
  for (const std::string& f : factors) out += (out.empty() ? "" : style == Style::Ascii ? "*" : style == Style::Latex ? " " : "") + f;
  return out;
}

std::string squared(const std::string& name, Style style) {
  return name + (style == Style::Latex ? "^{2}" : style == Style::Ascii ? "^2" : "²");
}

/// "first − piece − piece": \p first a polynomial (0: left out), the pieces subtracted.
std::string difference(const GiNaC::ex& first, const std::vector<std::string>& pieces, const Symbols& symbols, Style style, bool* several) {
  std::string out = first.is_zero() ? "" : format_polynomial(first, symbols, style);
  std::size_t count = first.is_zero() ? 0 : detail::terms(GiNaC::expand(first)).size();
  for (const std::string& piece : pieces) {
    out += out.empty() ? std::string(minus(style)) : std::string(" ") + minus(style) + " ";
    out += piece;
    ++count;
  }
  if (several) *several = count > 1;
  return out.empty() ? "0" : out;
}

std::string quotient(const std::string& top, bool several, const std::string& bottom, Style style) {
  if (style == Style::Latex) return "\\frac{" + top + "}{" + bottom + "}";
  return (several ? "(" + top + ")" : top) + "/" + bottom;
}

/// A coefficient times a name: "V₁", "−V₂", "2m₁V₁", "(m₂ + K₁₂)V₁"; \p negative receives
/// whether every term of the coefficient is negative (the text is then of its negation).
std::string scaled_name(const GiNaC::ex& coefficient, const std::string& name, const Symbols& symbols, Style style, bool* negative) {
  const auto ts = detail::terms(GiNaC::expand(coefficient));
  *negative = std::all_of(ts.begin(), ts.end(), [](const detail::Term& t) { return t.coefficient.is_negative(); });
  const GiNaC::ex c = *negative ? GiNaC::ex(-coefficient) : coefficient;
  if (c.is_equal(1)) return name;
  const std::string text = format_polynomial(c, symbols, style);
  const std::string factor = ts.size() == 1 ? text : "(" + text + ")";
  return factor + (style == Style::Ascii ? "*" : style == Style::Latex && ts.size() == 1 ? " " : "") + name;
}

/// The pieces of Σ_c ℓ_c V_c + β, each a product (never a sum) with its
/// sign: the positive ones and the negated negative ones; β term by term.
void linear_pieces(const EliminatedForm& f, const Symbols& symbols, Style style, std::vector<std::string>& positive, std::vector<std::string>& negative) {
  for (std::size_t c = 0; c < f.coefficients.size(); ++c) {
    if (f.coefficients[c].is_zero()) continue;
    bool neg = false;
    const std::string piece = scaled_name(f.coefficients[c], cluster_velocity_name(static_cast<int>(c) + 1, style), symbols, style, &neg);
    (neg ? negative : positive).push_back(piece);
  }
  for (const detail::Term& t : sorted_terms(f.constant, symbols)) (t.coefficient.is_negative() ? negative : positive).push_back(term_text(t, symbols, style));
}

std::string joined(const std::vector<std::string>& pieces) {
  std::string out;
  for (const std::string& p : pieces) out += (out.empty() ? "" : " + ") + p;
  return out.empty() ? "0" : out;
}

}  // namespace

std::string cluster_velocity_name(int c, Style style) { return elimination_name("V", static_cast<std::size_t>(c - 1), std::nullopt, style); }

std::vector<std::pair<std::string, std::string>> elimination_definitions(const Elimination& e, const Symbols& symbols, Style style) {
  const auto K = static_cast<std::size_t>(e.size);
  auto p = [&](std::size_t j) { return elimination_name("p", j, std::nullopt, style); };
  auto y = [&](std::size_t j) { return elimination_name("y", j, std::nullopt, style); };
  auto l = [&](std::size_t i, std::size_t j) { return elimination_name("l", i, j, style); };
  auto present = [&](std::size_t i, std::size_t j) { return e.multiplier[i * K + j] != 0; };
  std::vector<std::pair<std::string, std::string>> out;
  for (std::size_t a = 0; a < K; ++a) {
    const auto j = static_cast<std::size_t>(e.order[a]);
    std::vector<std::string> pivot, rhs;
    for (std::size_t c = 0; c < a; ++c) {
      const auto t = static_cast<std::size_t>(e.order[c]);
      if (!present(j, t)) continue;
      pivot.push_back(product({squared(l(j, t), style), p(t)}, style));
      rhs.push_back(product({l(j, t), y(t)}, style));
    }
    out.emplace_back(p(j), difference(e.matrix[j * K + j], pivot, symbols, style, nullptr));
    for (std::size_t b = a + 1; b < K; ++b) {
      const auto i = static_cast<std::size_t>(e.order[b]);
      if (!present(i, j)) continue;
      std::vector<std::string> fill;
      for (std::size_t c = 0; c < a; ++c) {
        const auto t = static_cast<std::size_t>(e.order[c]);
        if (present(i, t) && present(j, t)) fill.push_back(product({l(i, t), l(j, t), p(t)}, style));
      }
      bool several = false;
      const std::string top = difference(e.matrix[i * K + j], fill, symbols, style, &several);
      out.emplace_back(l(i, j), quotient(top, several, p(j), style));
    }
    out.emplace_back(y(j), difference(e.rhs[j], rhs, symbols, style, nullptr));
  }
  for (std::size_t a = K; a-- > 0;) {
    const auto j = static_cast<std::size_t>(e.order[a]);
    std::string value = quotient(y(j), false, p(j), style);
    for (std::size_t b = a + 1; b < K; ++b) {
      const auto i = static_cast<std::size_t>(e.order[b]);
      if (present(i, j)) value += std::string(" ") + minus(style) + " " + product({l(i, j), cluster_velocity_name(static_cast<int>(i) + 1, style)}, style);
    }
    out.emplace_back(cluster_velocity_name(static_cast<int>(j) + 1, style), value);
  }
  return out;
}

std::string format_eliminated(const EliminatedForm& f, Relation relation, const Symbols& symbols, Style style) {
  std::vector<std::string> positive, negative;
  linear_pieces(f, symbols, style, positive, negative);
  return joined(positive) + " " + relation_text(relation, false, style) + " " + joined(negative);
}

std::string format_linear(const EliminatedForm& f, const Symbols& symbols, Style style, bool negate) {
  std::vector<std::string> positive, negative;
  linear_pieces(f, symbols, style, positive, negative);
  if (negate) std::swap(positive, negative);
  std::string out;
  for (const std::string& p : positive) out += (out.empty() ? "" : " + ") + p;
  for (const std::string& p : negative) out += (out.empty() ? std::string(minus(style)) : std::string(" ") + minus(style) + " ") + p;
  return out.empty() ? "0" : out;
}

std::string velocity_name(int body, Style style) {
  const std::string i = std::to_string(body);
  if (style == Style::Latex) return "U_{" + i + "}^{+}";
  if (style == Style::Text) return "U" + subscript_digits(i) + "⁺";
  return "U" + i;
}

std::string reaction_name(const Pair& contact, Style style) {
  if (style == Style::Latex) return "R_{" + std::to_string(contact.i) + std::to_string(contact.j) + "}";
  if (style == Style::Text) return "R" + subscript_digits(std::to_string(contact.i) + (contact.j >= 10 ? "," : "") + std::to_string(contact.j));
  return "R" + std::to_string(contact.i) + "_" + std::to_string(contact.j);
}

std::string condition_title(const Condition& c, Style style) {
  auto m = [&](const std::string& s) { return math(s, style); };
  const std::string gt = style == Style::Latex ? ">" : ">";
  const std::string le = style == Style::Latex ? "\\le" : style == Style::Text ? "≤" : "<=";
  switch (c.kind) {
    case ConditionKind::Superball: return "superball (" + m(velocity_name(1, style) + " > a") + ")";
    case ConditionKind::Evolution: {
      const Pair p = Pair::parse(c.about);
      return "contact " + c.about + " opens (" + m(velocity_name(p.i, style) + " " + gt + " " + velocity_name(p.j, style)) + ")";
    }
    case ConditionKind::Contact: {
      const Pair p = Pair::parse(c.about);
      return "contact " + c.about + " stays closed without interpenetration (" + m(reaction_name(p, style) + " " + le + " 0") + ")";
    }
    case ConditionKind::Psd: break;
  }
  return "M positive semi-definite, minor on " + c.about;
}

namespace {

std::string order_note(const Condition& c, Style style) {
  std::string s = "order " + math(order_text(c.leading_order, style), style);
  if (c.descended > 0) {
    std::ostringstream os;
    os << c.descended;
    s += "; the leading terms of order " + math(order_text(c.leading_order - c.descended, style), style) + " cancel";
  }
  return s;
}

std::string short_proof(const Condition& c) {
  if (c.kind == ConditionKind::Psd) return "";
  if (c.proof.rfind("sign not proved", 0) == 0) return "sign of the denominator not proved";
  if (c.proof.rfind("the denominator divides", 0) == 0)
    return std::string("denominator cleared: a factor of det(Z^T A Z) > 0, sign ") + (c.proof.find(": +,") != std::string::npos ? "+" : "-");
  return "denominator cleared: " + c.proof;
}

}  // namespace

// ---------------------------------------------------------------------------
// LaTeX layout of report(): formulas that do not fit on a line are set as
// align* displays broken by hand between terms (amsmath only; breqn is not in
// texlive-latex-base), and long velocities and reactions are written as
// \frac{prefix}{\Delta} (…) with \Delta = det(ZᵀAZ) given once per case.
namespace {

/// \textwidth of latex_document(): a4paper (597.51 pt) less two margins of 2 cm (56.91 pt each).
constexpr double kTextWidthPt = 483.69;
/// Widest a displayed row is made, by the estimate of latex_width().  With
/// rows and lines made a full \textwidth wide by the estimate, TeX found them
/// at most 12 pt (2.5 %) wider in the documents of tests/symbolic/latex_test.cpp;
/// the 10 % kept free is four times that.
constexpr double kDisplayRowPt = 0.9 * kTextWidthPt;
/// Widest a "label: formula" line is kept inline, by the same estimate.
constexpr double kInlineLinePt = 0.9 * kTextWidthPt;
/// A first side (left of the first relation) at most this wide stays in the
/// left column of the display, the rest aligned on its relation; a wider one
/// is broken like the right side.
constexpr double kLeadColumnPt = 0.3 * kTextWidthPt;
/// Widths at 10 pt of Computer Modern (cmr10, cmmi10, cmsy10), in pt.
constexpr double kDigitPt = 5.0, kLowerPt = 5.5, kUpperPt = 8.5, kWideLetterPt = 8.8, kCommandPt = 6.5;
constexpr double kSignPt = 7.78;                    ///< + or − (cmr10, cmsy10), a unary sign
constexpr double kBinaryPt = kSignPt + 2 * 2.22;    ///< + or − with \medmuskip on both sides
constexpr double kRelationPt = kSignPt + 2 * 2.78;  ///< >, <, =, \le, \ge, \sim with \thickmuskip on both sides
constexpr double kParenPt = 3.89, kBigParenPt = 4.6, kPunctPt = 2.78 + 1.67, kQuadPt = 10.0;
constexpr double kDetPt = 15.6, kInfinityPt = 10.0, kBracePt = 5.0, kNullDelimiterPt = 1.2;  ///< \det, \infty, \{, each side of \frac
constexpr double kTextCharPt = 5.0, kTextUpperPt = 7.3, kTextSpacePt = 3.33;  ///< prose: a lower-case letter, a capital, a space
/// Subscripts and superscripts: cmr7/cmmi7 glyphs are about 0.8 of the 10 pt ones, cmr5 about 0.68.
constexpr double kScriptScale = 0.8, kScriptScriptScale = 0.68;

std::size_t group_end(const std::string& s, std::size_t open);  // index of the '}' closing s[open] == '{'

/// Estimated width in pt of the math-mode LaTeX \p s at size \p scale (1 =
/// text size), as report() writes it: symbols with sub- and superscripts,
/// \frac, \text, operators written " + ", relations " > ".
double latex_width(const std::string& s, double scale = 1.0) {
  double w = 0;
  for (std::size_t k = 0; k < s.size();) {
    const char c = s[k];
    if (c == '\\') {
      std::size_t e = k + 1;
      while (e < s.size() && std::isalpha(static_cast<unsigned char>(s[e]))) ++e;
      if (e == k + 1) e = std::min(k + 2, s.size());  // \{, \,, \\ …
      const std::string cmd = s.substr(k + 1, e - k - 1);
      k = e;
      auto argument = [&](double arg_scale) {
        while (k < s.size() && s[k] == ' ') ++k;
        if (k >= s.size() || s[k] != '{') return 0.0;
        const std::size_t close = group_end(s, k);
        const std::string inner = s.substr(k + 1, close - k - 1);
        k = close + 1;
        return arg_scale < 0 ? static_cast<double>(inner.size()) : latex_width(inner, arg_scale);
      };
      if (cmd == "frac") {
        const double num = argument(scale), den = argument(scale);
        w += std::max(num, den) + 2 * kNullDelimiterPt * scale;
      } else if (cmd == "text" || cmd == "mathrm") {
        w += argument(-1) * kTextCharPt * scale;
      } else if (cmd == "quad") {
        w += kQuadPt * scale;
      } else if (cmd == "qquad") {
        w += 2 * kQuadPt * scale;
      } else if (cmd == "," || cmd == ";" || cmd == " " || cmd == "!") {
        w += (cmd == "!" ? 0 : kTextSpacePt) * scale;
      } else if (cmd == "left" || cmd == "right" || cmd == "bigl" || cmd == "bigr") {
        if (k < s.size()) ++k;  // the delimiter
        w += kBigParenPt * scale;
      } else if (cmd == "le" || cmd == "ge" || cmd == "sim") {
        w += kRelationPt * scale;
      } else if (cmd == "det") {
        w += kDetPt * scale;
      } else if (cmd == "infty") {
        w += kInfinityPt * scale;
      } else if (cmd == "{" || cmd == "}") {
        w += kBracePt * scale;
      } else {
        w += kCommandPt * scale;  // \alpha, \Delta, \varepsilon, …
      }
      continue;
    }
    if (c == '_' || c == '^') {
      ++k;
      const double sub = scale >= 1.0 ? kScriptScale : kScriptScriptScale;
      if (k < s.size() && s[k] == '{') {
        const std::size_t close = group_end(s, k);
        w += latex_width(s.substr(k + 1, close - k - 1), sub);
        k = close + 1;
      } else if (k < s.size()) {
        w += latex_width(s.substr(k, 1), sub);
        ++k;
      }
      continue;
    }
    if (c == '{' || c == '}' || c == ' ' || c == '&') {
      ++k;
      continue;
    }
    if ((c == '+' || c == '-') && k + 1 < s.size() && s[k + 1] == ' ' && k > 0 && s[k - 1] == ' ')
      w += kBinaryPt * scale;  // binary: " + "
    else if (c == '+' || c == '-')
      w += kSignPt * scale;  // unary: "-m_{1}"
    else if (c == '>' || c == '<' || c == '=')
      w += kRelationPt * scale;
    else if (c == '(' || c == ')' || c == '[' || c == ']')
      w += kParenPt * scale;
    else if (c == ',' || c == ';')
      w += kPunctPt * scale;
    else if (std::isdigit(static_cast<unsigned char>(c)))
      w += kDigitPt * scale;
    else if (c == 'm' || c == 'w' || c == 'M' || c == 'W')
      w += kWideLetterPt * scale;
    else if (std::isupper(static_cast<unsigned char>(c)))
      w += kUpperPt * scale;
    else
      w += kLowerPt * scale;
    ++k;
  }
  return w;
}

std::size_t group_end(const std::string& s, std::size_t open) {
  int depth = 0;
  for (std::size_t k = open; k < s.size(); ++k) {
    if (s[k] == '\\') {
      ++k;
      continue;
    }
    if (s[k] == '{') ++depth;
    if (s[k] == '}' && --depth == 0) return k;
  }
  throw std::logic_error("report(): unbalanced braces in LaTeX: " + s);
}

/// Estimated width in pt of LaTeX text \p s: prose, \quad, $math$.
double text_width(const std::string& s) {
  double w = 0;
  for (std::size_t k = 0; k < s.size();) {
    if (s[k] == '$') {
      const std::size_t close = s.find('$', k + 1);
      if (close == std::string::npos) throw std::logic_error("report(): unbalanced $ in: " + s);
      w += latex_width(s.substr(k + 1, close - k - 1));
      k = close + 1;
    } else if (s.compare(k, 5, "\\quad") == 0) {
      w += kQuadPt;
      k += 5;
    } else if (s[k] == '\\') {  // \noindent, \par, \{ …: no width
      ++k;
      while (k < s.size() && std::isalpha(static_cast<unsigned char>(s[k]))) ++k;
    } else {
      // One byte of a UTF-8 sequence counts for its character once.
      if ((static_cast<unsigned char>(s[k]) & 0xC0) != 0x80) w += s[k] == ' ' ? kTextSpacePt : std::isupper(static_cast<unsigned char>(s[k])) ? kTextUpperPt : kTextCharPt;
      ++k;
    }
  }
  return w;
}

/// One term of a formula and the operator before it ("", "+", "-").
struct Piece {
  std::string op, body;
};
/// A side of a formula: the relation before it ("" for the first side) and its terms.
struct Side {
  std::string relation;
  std::vector<Piece> pieces;
};

/// \p math cut at its top level (outside braces and \left…\right) before
/// every " + ", " - " and relation (" > ", " < ", " = ", " \le ", " \ge ").
std::vector<Side> split_formula(const std::string& math) {
  static const std::vector<std::string> relations = {" > ", " < ", " = ", " \\le ", " \\ge "};
  std::vector<Side> sides(1);
  Piece piece;
  int braces = 0, sized = 0;
  auto close_piece = [&] {
    if (!piece.body.empty() || !piece.op.empty()) sides.back().pieces.push_back(piece);
    piece = Piece{};
  };
  for (std::size_t k = 0; k < math.size();) {
    if (braces == 0 && sized == 0) {
      if (math.compare(k, 3, " + ") == 0 || math.compare(k, 3, " - ") == 0) {
        close_piece();
        piece.op = math.substr(k + 1, 1);
        k += 3;
        continue;
      }
      bool relation = false;
      for (const std::string& r : relations)
        if (math.compare(k, r.size(), r) == 0) {
          close_piece();
          sides.push_back(Side{r.substr(1, r.size() - 2), {}});
          k += r.size();
          relation = true;
          break;
        }
      if (relation) continue;
    }
    const char c = math[k];
    if (c == '\\' && k + 1 < math.size()) {
      if (math.compare(k, 5, "\\left") == 0 && !std::isalpha(static_cast<unsigned char>(math[std::min(k + 5, math.size() - 1)]))) ++sized;
      if (math.compare(k, 6, "\\right") == 0 && !std::isalpha(static_cast<unsigned char>(math[std::min(k + 6, math.size() - 1)]))) --sized;
      piece.body += math.substr(k, 2);
      k += 2;
      continue;
    }
    if (c == '{') ++braces;
    if (c == '}') --braces;
    piece.body += c;
    ++k;
  }
  close_piece();
  return sides;
}

/// \p math with every \left( … \right) written \bigl( … \bigr), so that the
/// terms inside can go on several rows.
std::string open_sized(std::string math) {
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{{"\\left(", "\\bigl("}, {"\\right)", "\\bigr)"}})
    for (std::size_t at = math.find(from); at != std::string::npos; at = math.find(from, at + to.size())) math.replace(at, from.size(), to);
  return math;
}

double piece_width(const Piece& p) { return latex_width(p.body) + (p.op.empty() ? 0 : kBinaryPt); }

/// The rows of an align* for \p math, each at most \p width wide by
/// latex_width() (a single term wider than that gets a row of its own).  A
/// short first side stays in the left column and the rest aligns on its
/// relation; a long one is broken like the others.  A row that continues a
/// side starts with \quad and its operator ({}+ keeps + binary); a row that
/// starts a side starts with its relation.
std::string display_rows(const std::string& math, double width) {
  std::vector<Side> sides = split_formula(math);
  const auto too_wide = [&](const std::vector<Side>& ss) {
    for (const Side& s : ss)
      for (const Piece& p : s.pieces)
        if (piece_width(p) > width - kQuadPt && p.body.find("\\left") != std::string::npos) return true;
    return false;
  };
  if (too_wide(sides)) sides = split_formula(open_sized(math));
  std::string lead;
  double lead_width = 0;
  std::size_t first = 0;
  if (sides.size() > 1) {
    for (const Piece& p : sides[0].pieces) lead += (p.op.empty() ? "" : " " + p.op + " ") + p.body;
    lead_width = latex_width(lead);
    if (lead_width <= kLeadColumnPt)
      first = 1;
    else
      lead.clear(), lead_width = 0;
  }
  const double available = width - lead_width;
  std::vector<std::string> rows;
  std::string row;
  double used = 0;
  bool empty_row = true;
  auto start_row = [&](const std::string& prefix, double prefix_width) {
    if (!row.empty()) rows.push_back(row);
    row = "&" + prefix;
    used = prefix_width;
    empty_row = true;
  };
  for (std::size_t s = first; s < sides.size(); ++s) {
    const Side& side = sides[s];
    start_row(side.relation.empty() ? "" : side.relation + " ", side.relation.empty() ? 0 : kRelationPt);
    for (const Piece& p : side.pieces) {
      const double w = piece_width(p);
      if (!empty_row && used + w > available) start_row("\\quad {}", kQuadPt);
      if (!p.op.empty()) row += (empty_row && row.back() == '}' ? "" : " ") + p.op + " ";
      // A sign opening a row: {-} keeps it a sign (after &, amsmath makes a bare - binary).
      if (empty_row && row == "&" && p.op.empty() && p.body.rfind("-", 0) == 0)
        row += "{-}" + p.body.substr(1);
      else
        row += p.body;
      used += w;
      empty_row = false;
    }
  }
  if (!row.empty()) rows.push_back(row);
  std::string out = lead.empty() ? "" : lead + " ";
  for (std::size_t r = 0; r < rows.size(); ++r) out += (r ? " \\\\\n" : "") + rows[r];
  return out;
}

/// LaTeX text of the library's prose: relations in math mode (a text-mode
/// > prints as ¿ in OT1), det(Z^T A Z) as $\det(Z^{T}AZ)$, signs as $+$ and
/// $-$, LaTeX specials escaped.
std::string latex_prose(const std::string& s) {
  static const std::vector<std::pair<std::string, std::string>> words = {
      {"det(Z^T A Z) > 0", "$\\det(Z^{T}AZ) > 0$"}, {"det(Z^T A Z)", "$\\det(Z^{T}AZ)$"}, {"Z^T A Z", "$Z^{T}AZ$"}, {"D^T M D", "$D^{T}MD$"}, {"sign +", "sign $+$"}, {"sign -", "sign $-$"}};
  std::string out;
  for (std::size_t k = 0; k < s.size();) {
    bool replaced = false;
    for (const auto& [from, to] : words)
      if (s.compare(k, from.size(), from) == 0) {
        out += to;
        k += from.size();
        replaced = true;
        break;
      }
    if (replaced) continue;
    const char c = s[k++];
    if (std::string("<>=|").find(c) != std::string::npos)
      out += std::string("$") + c + "$";
    else if (std::string("{}_%#&$").find(c) != std::string::npos)
      out += std::string("\\") + c;
    else if (c == '^' || c == '~')
      out += std::string("\\") + c + "{}";
    else if (c == '\\')
      out += "\\textbackslash{}";
    else
      out += c;
  }
  return out;
}

/// "\noindent LABEL $MATH$ NOTE\par" when it fits on a line (by
/// text_width()), else "\noindent LABEL NOTE" followed by an align* of
/// display_rows().
std::string latex_formula_line(const std::string& label, const std::string& math, const std::string& note) {
  const std::string head = "\\noindent " + label;
  if (text_width(head + " $" + math + "$" + note) <= kInlineLinePt) return head + " $" + math + "$" + note + "\\par\n";
  return head + note + "\n\\begin{align*}\n" + display_rows(math, kDisplayRowPt) + "\n\\end{align*}\n";
}

/// The right side of "NAME = f" in LaTeX: format_fraction() when it fits in
/// \p width; else PREFIX/DEN (REST) with the denominator written \Delta when
/// it is det(ZᵀAZ), so that the terms of REST can be broken over rows.
/// \p den_name names a long denominator that is not \Delta; its value is
/// appended to \p where ("D_{…} = …").
std::string latex_fraction(const Fraction& f, const Symbols& sy, const GiNaC::ex& determinant, double width, const std::string& den_name,
                           std::vector<std::pair<std::string, std::string>>& where) {
  const std::string whole = format_fraction(f, sy, Style::Latex);
  if (latex_width(whole) <= width) return whole;
  Split num = split_common(f.numerator, sy);
  const auto rest = sort_terms(std::move(num.rest), sy);
  const GiNaC::ex front = num.content * num.monomial;
  const bool negative = num.content.is_negative();
  const std::string prefix = front.is_equal(1) || front.is_equal(-1) ? "1" : join(detail::terms(GiNaC::expand(negative ? -front : front)), sy, Style::Latex);
  std::string den;
  if (f.denominator.is_equal(1))
    den.clear();
  else if (!GiNaC::is_a<GiNaC::numeric>(determinant) && GiNaC::expand(f.denominator - determinant).is_zero())
    den = "\\Delta";
  else if (const std::string d = format_polynomial(f.denominator, sy, Style::Latex); latex_width(d) <= kLeadColumnPt)
    den = d;
  else {
    den = den_name;
    where.emplace_back(den_name, d);
  }
  const std::string sign = negative ? "-" : "";
  const bool unit_rest = rest.size() == 1 && rest.front().powers.empty() && rest.front().coefficient.is_equal(1);
  if (unit_rest) return sign + (den.empty() ? prefix : "\\frac{" + prefix + "}{" + den + "}");
  const std::string head = den.empty() ? (prefix == "1" ? "" : prefix) : "\\frac{" + prefix + "}{" + den + "}";
  const std::string body = join(rest, sy, Style::Latex);
  if (head.empty()) return sign.empty() ? body : sign + "\\bigl(" + body + "\\bigr)";
  return sign + head + "\\bigl(" + body + "\\bigr)";
}

/// How many orders of ε the asymptotic forms keep, in words.
std::string orders_kept_text(int order) {
  if (order == 0) return "the dominant balance only";
  return "the dominant balance and the next " + (order == 1 ? std::string("order") : std::to_string(order) + " orders");
}


void write_line(std::ostream& os, Style style, const std::string& label, const std::string& value) {
  if (style == Style::Latex)
    os << "\\noindent " << label << (label.empty() ? "" : " ") << value << "\\par\n";
  else
    os << "  " << label << (label.empty() ? "" : " ") << value << '\n';
}

/// A labelled formula: one line of text, or in LaTeX a display broken over rows when it does not fit.
void write_formula(std::ostream& os, Style style, const std::string& label, const std::string& value, const std::string& note) {
  if (style == Style::Latex)
    os << latex_formula_line(label, value, note);
  else
    os << "  " << label << (label.empty() ? "" : " ") << value << note << '\n';
}

/// One condition of a report: its title, forms and proof note.
void write_condition(std::ostream& os, const Condition& c, const Symbols& sy, Style style, const std::string& limit) {
  const bool tex = style == Style::Latex;
  if (tex)
    os << "\\medskip\\noindent " << condition_title(c, style) << "\\par\n";
  else
    os << "  " << condition_title(c, style) << '\n';
  if (c.finite) write_formula(os, style, tex ? "\\quad finite obstacle:" : "    finite obstacle:", format_form(*c.finite, c.relation, sy, style), "");
  write_formula(os, style, tex ? "\\quad exact:" : "    exact:     ", format_form(c.exact, c.relation, sy, style),
                c.exact.verdict == Verdict::Depends ? "" : std::string("  [") + to_string(c.exact.verdict) + "]");
  write_formula(os, style, tex ? "\\quad asymptotic:" : "    asymptotic:", format_form(c.asymptotic, c.relation, sy, style),
                "  [" + (c.asymptotic.verdict == Verdict::Depends ? "" : std::string(to_string(c.asymptotic.verdict)) + ", ") +
                    (c.asymptotic.eliminated && c.asymptotic.eliminated->limit && !limit.empty() ? math(limit, style) + " in the elimination, " : "") +
                    order_note(c, style) + "]");
  // "always"/"never" with nothing left but a constant: the positive factor divided out says why.
  if (c.kind != ConditionKind::Psd && !c.finite && c.exact.verdict != Verdict::Depends && c.exact.sign_proved() &&
      GiNaC::is_a<GiNaC::numeric>(c.exact.numerator) && !c.removed.is_equal(1)) {
    std::string quantity;
    if (c.kind == ConditionKind::Superball) {
      quantity = velocity_name(1, style) + " " + minus(style) + " a";
    } else {
      const Pair p = Pair::parse(c.about);
      quantity = c.kind == ConditionKind::Evolution ? velocity_name(p.i, style) + " " + minus(style) + " " + velocity_name(p.j, style)
                                                    : minus(style) + reaction_name(p, style);
    }
    const std::string value = format_polynomial(GiNaC::expand(c.exact.numerator * c.removed), sy, style);
    const std::string delta = tex ? "\\Delta" : "Δ";
    write_formula(os, style, tex ? "\\quad why:" : "    why:       ",
                  quantity + " = " + (tex ? "\\frac{" + value + "}{" + delta + "}" : "(" + value + ")/" + delta) + " " +
                      (GiNaC::ex_to<GiNaC::numeric>(c.exact.numerator).is_negative() ? "<" : c.exact.numerator.is_zero() ? "=" : ">") + " 0",
                  tex ? ", $\\Delta$ a factor of $\\det(Z^{T}AZ) > 0$" : ", Δ a factor of det(ZᵀAZ) > 0");
  }
  const std::string proof = short_proof(c);
  if (!proof.empty()) write_line(os, style, tex ? "\\quad" : "    ", "(" + (tex ? latex_prose(proof) : prose(proof, style)) + ")");
}

}  // namespace

std::string report(const Derivation& d, const Deriver& deriver, Style style, bool with_psd) {
  if (style == Style::Ascii) throw std::invalid_argument("report(): ASCII output is JSON (see `superball derive --format json`)");
  const Symbols& sy = *d.symbols;
  const bool tex = style == Style::Latex;
  const int n = sy.bodies();
  std::ostringstream os;
  auto line = [&](const std::string& label, const std::string& value) { write_line(os, style, label, value); };
  auto formula = [&](const std::string& label, const std::string& value, const std::string& note) { write_formula(os, style, label, value, note); };
  auto words = [&](const std::string& s) { return tex ? latex_prose(s) : prose(s, style); };
  std::string description;
  for (const NamedCase& c : Vocabulary::paper().cases())
    if (n == Vocabulary::paper().bodies() && c.closed == d.closed) description = c.description;
  const std::string title = prose("case " + d.case_name + (d.case_name == d.closed.to_string() ? "" : " " + d.closed.to_string()) +
                                      (description.empty() ? "" : ": " + description), style);
  if (tex)
    os << "\\subsection*{" << title << "}\n";
  else
    os << title << '\n';
  std::string couplings;
  for (const SymbolInfo& s : sy.all())
    if (s.kind == SymbolKind::Coupling) couplings += (couplings.empty() ? "" : ", ") + math(s.name(style), style);
  line("pattern:", std::to_string(n) + " bodies, K on " + std::to_string(sy.pattern().diagonal.size()) + " pairs, couplings " +
                       (couplings.empty() ? "none" : couplings));
  line("obstacle:", sy.obstacle() == Obstacle::Infinite
                        ? "fixed (" + math(tex ? "m_{" + std::to_string(n) + "} = \\infty" : "m" + subscript_digits(std::to_string(n)) + " = ∞", style) + ", it stays at rest)"
                        : "finite mass " + math(sy.info(sy.mass(n)).name(style), style));
  // LaTeX: det(ZᵀAZ) is named \Delta once, and long velocities and reactions are written over it.
  const bool named_determinant = tex && !GiNaC::is_a<GiNaC::numeric>(d.determinant);
  const std::string unknowns = std::to_string(d.free_clusters) + " unknown velocit" + (d.free_clusters == 1 ? "y" : "ies") + ",";
  // A long case is written through its elimination (Elimination): det(ZᵀAZ) as the product of the pivots,
  // long velocities as cluster velocities V, long reactions as sums over them.
  const Elimination* e = d.elimination ? &*d.elimination : nullptr;
  auto is_long = [&](const GiNaC::ex& p) { return e && (GiNaC::is_a<GiNaC::add>(p) ? p.nops() : 1) > max_inline_exact_terms; };
  std::string determinant = format_polynomial(d.determinant, sy, style);
  if (is_long(d.determinant)) {
    std::vector<std::string> pivots;
    for (int c = 1; c <= e->size; ++c) pivots.push_back(elimination_name("p", static_cast<std::size_t>(c - 1), std::nullopt, style));
    determinant = product(pivots, style);
  }
  if (tex)
    formula("reduced system: " + unknowns, (named_determinant ? "\\Delta = " : "") + std::string("\\det(Z^{T}AZ) = ") + determinant, "");
  else
    line("reduced system:", unknowns + " " + prose("det(Z^T A Z)", style) + " = " + determinant);
  // Velocities and reactions: in LaTeX one align* per group, aligned on "=", a long fraction over \Delta
  // (or over a named denominator, given after the group) with its terms broken over rows.
  // Entries: (name, fraction, its value through the elimination when the fraction is long).
  using Entry = std::tuple<std::string, const Fraction*, std::string>;
  auto fractions = [&](const std::string& heading, const std::vector<Entry>& entries) {
    if (!tex) {
      os << "  " << heading << '\n';
      for (const auto& [name, f, through] : entries) line("  ", name + " = " + (through.empty() ? format_fraction(*f, sy, style) : through));
      return;
    }
    std::vector<std::pair<std::string, std::string>> where;
    std::string rows;
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const auto& [name, f, through] = entries[k];
      const double room = kDisplayRowPt - latex_width(name) - kRelationPt;
      const std::string den_name = "D_{" + std::to_string(where.size() + 1) + "}";
      rows += (k ? " \\\\\n" : "") +
              display_rows(name + " = " + (through.empty() ? latex_fraction(*f, sy, d.determinant, room, den_name, where) : through), kDisplayRowPt);
    }
    if (!where.empty()) rows += " \\\\\n\\intertext{where}\n";
    for (std::size_t k = 0; k < where.size(); ++k) rows += (k ? " \\\\\n" : "") + display_rows(where[k].first + " = " + where[k].second, kDisplayRowPt);
    os << "\\noindent " << heading << "\n\\begin{align*}\n" << rows << "\n\\end{align*}\n";
  };
  std::vector<Entry> velocities, reactions;
  for (int i = 1, c = 1; i <= n; ++i) {
    const Fraction& f = d.velocities[static_cast<std::size_t>(i - 1)];
    velocities.emplace_back(velocity_name(i, style), &f, is_long(f.numerator) ? cluster_velocity_name(c, style) : "");
    if (i < n && !d.closed.closed(i - 1)) ++c;  // the next body starts a cluster
  }
  fractions("velocities after the collision:", velocities);
  for (int c = 0; c + 1 < n; ++c) {
    if (!d.closed.closed(c)) continue;
    const Fraction& f = d.reactions[static_cast<std::size_t>(c)];
    reactions.emplace_back(reaction_name(Pair{c + 1, c + 2}, style), &f,
                           is_long(f.numerator) ? format_linear(d.reactions_eliminated[static_cast<std::size_t>(c)], sy, style, true) : "");
  }
  if (!reactions.empty()) fractions("reactions on the closed contacts:", reactions);
  line("check:", words(d.check));
  std::string small;  // "m₁ = 0": the limit the marked asymptotic forms take in the elimination
  if (e) {
    for (const GiNaC::ex& x : e->small) small += (small.empty() ? "" : ", ") + sy.info(x).name(style) + " = 0";
    line("elimination:", "of " + math(tex ? "(Z^{T}AZ)V = Z^{T}b" : "(ZᵀAZ)V = Zᵀb", style) + " cluster by cluster from the obstacle up, " + math(cluster_velocity_name(1, style), style) +
                             " the velocity of the top cluster; pivots " + math("p > 0", style) + ", multipliers " + math("l", style) +
                             ", eliminated right-hand sides " + math("y", style) +
                             (small.empty() ? "" : "; the asymptotic forms marked so take " + math(small, style) + " in these"));
    for (const auto& [name, value] : elimination_definitions(*e, sy, style)) formula(tex ? "\\quad" : "     ", name + " = " + value, "");
  }
  for (const NamedPart& p : d.named)
    formula(p.index == 1 ? "where" : (tex ? "\\quad" : "     "), named_part_name(p.index, style) + " = " + format_polynomial(p.value, sy, style) + (p.positive ? " > 0" : ""),
            p.positive ? " (every term positive)" : words(" (a diagonal entry of Z^T A Z)"));
  if (d.actual == Verdict::Never)
    line("never actual:", "the condition on " + d.actual_reason + " below fails for every admissible parameter, so this case is never the evolution");
  const std::string infinity = tex ? "m_{" + std::to_string(n) + "} = \\infty" : "m" + subscript_digits(std::to_string(n)) + " = ∞";
  const bool finite = sy.obstacle() == Obstacle::Finite;
  line("conditions:", std::string(finite ? "finite obstacle with " + math(sy.info(sy.mass(n)).name(style), style) + ", " : "") +
                          "exact with " + math(infinity, style) + (finite ? " (the limit)" : "") + "; asymptotic" +
                          (finite ? " of the finite-obstacle form" : "") + " for " + math(deriver.scaling().describe(sy, style), style) +
                          ", keeping " + orders_kept_text(deriver.order()));
  for (const Condition& c : d.conditions)
    if (with_psd || c.kind != ConditionKind::Psd) write_condition(os, c, sy, style, small);
  return os.str();
}

std::string report_psd(const Deriver& deriver, Style style) {
  if (style == Style::Ascii) throw std::invalid_argument("report_psd(): ASCII output is JSON (see `superball derive --format json`)");
  std::ostringstream os;
  const std::string title = "M positive semi-definite (paper §3): the same conditions in every case";
  if (style == Style::Latex)
    os << "\\subsection*{" << title << "}\n";
  else
    os << title << '\n';
  for (const Condition& c : deriver.psd()) write_condition(os, c, deriver.symbols(), style, "");
  return os.str();
}

std::string latex_document(const std::vector<Derivation>& derivations, const Deriver& deriver) {
  std::ostringstream os;
  // \allowdisplaybreaks: the rows of a long align* may go on the next page.
  os << "\\documentclass[a4paper]{article}\n\\usepackage{amsmath}\n\\usepackage[margin=2cm]{geometry}\n"
        "\\allowdisplaybreaks\n\\sloppy\n\\begin{document}\n\\section*{Evolution cases and their conditions}\n";
  if (!derivations.empty()) {
    os << "Denominators are cleared only with a proved sign: every velocity and reaction of a case has the denominator "
          "$\\Delta = \\det(Z^{T}AZ)$, $A = \\mathrm{diag}(m) + D^{T}MD$, $Z$ the cluster incidence, which is positive definite for "
          "positive masses and $M$ positive semi-definite; a factor of it never vanishes on the connected set of admissible "
          "parameters, so its sign is its sign at $m = K = a = 1$, couplings $0$.  A formula too long for a line is broken "
          "between its terms over several rows, and a long velocity or reaction is written as a factor over $\\Delta$ times "
          "the sum of the remaining terms.\n";
  }
  // Several cases: the conditions on M, the same in every case, once before them.
  const bool shared = derivations.size() > 1;
  if (shared) os << report_psd(deriver, Style::Latex) << '\n';
  for (const Derivation& d : derivations) os << report(d, deriver, Style::Latex, !shared) << '\n';
  os << "\\end{document}\n";
  return os.str();
}

}  // namespace superball::symbolic
