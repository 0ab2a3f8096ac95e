// The elimination of a case's reduced system (derivation.hpp, Elimination),
// the eliminated forms, and the names and titles of format.hpp.
#include "superball/symbolic/format.hpp"

#include <algorithm>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "format_terms.hpp"

namespace superball::symbolic {

using detail::minus;
using detail::relation_text;
using detail::sorted_terms;
using detail::subscript_digits;
using detail::term_text;

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

std::string format_pivot_product(const Elimination& e, Style style) {
  std::vector<std::string> pivots;
  for (int c = 1; c <= e.size; ++c) pivots.push_back(elimination_name("p", static_cast<std::size_t>(c - 1), std::nullopt, style));
  return product(pivots, style);
}

std::string epsilon_power(const GiNaC::numeric& k, Style style) {
  std::ostringstream os;
  os << k;
  if (style == Style::Latex) return "\\varepsilon^{" + os.str() + "}";
  if (style == Style::Text) return "ε^" + os.str();
  return "eps^" + os.str();
}

std::string mass_name(int body, Style style) {
  const std::string i = std::to_string(body);
  if (style == Style::Latex) return "m_{" + i + "}";
  if (style == Style::Text) return "m" + subscript_digits(i);
  return "m" + i;
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
  auto m = [&](const std::string& s) { return style == Style::Latex ? "$" + s + "$" : s; };
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

}  // namespace superball::symbolic
