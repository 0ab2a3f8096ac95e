#include "superball/symbolic/format.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

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

std::vector<detail::Term> sorted_terms(const GiNaC::ex& p, const Symbols& symbols) {
  std::vector<detail::Term> ts;
  try {
    ts = detail::terms(GiNaC::expand(p));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("format_polynomial(): ") + e.what());
  }
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
  GiNaC::ex rest = 0;
};

Split split_common(const GiNaC::ex& p, const Symbols& symbols) {
  Split s;
  const auto ts = detail::terms(GiNaC::expand(p));
  if (ts.size() <= 1) {
    s.rest = GiNaC::expand(p);
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
  for (const auto& [sym, e0] : ts.front().powers) {
    int low = e0;
    for (const detail::Term& t : ts) {
      int here = 0;
      for (const auto& [s2, e2] : t.powers)
        if (s2.is_equal(sym)) here = e2;
      low = std::min(low, here);
    }
    if (low > 0) s.monomial *= GiNaC::pow(sym, low);
  }
  (void)symbols;
  GiNaC::ex q;
  if (!GiNaC::divide(GiNaC::expand(p), s.content * s.monomial, q)) throw std::logic_error("format_fraction(): content does not divide");
  s.rest = GiNaC::expand(q);
  return s;
}

/// "a(K₁₄ + α₂ − m₁)", "−2(…)", "m₁ + K₁₂" (no common factor), "3a".
std::string factored(const GiNaC::ex& p, const Symbols& symbols, Style style, bool* single) {
  const Split s = split_common(p, symbols);
  const auto rest = sorted_terms(s.rest, symbols);
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
  return (single_num ? num : "(" + num + ")") + "/" + (single_den ? den : "(" + den + ")");
}

std::string format_condition(const GiNaC::ex& p, Relation relation, const Symbols& symbols, Style style) {
  if (style == Style::Ascii) return format_polynomial(p, symbols, style) + " " + relation_text(relation, false, style) + " 0";
  const auto ts = sorted_terms(p, symbols);
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

std::string format_condition(const ConditionForm& form, Relation relation, const Symbols& symbols, Style style) {
  if (form.sign_proved()) return format_condition(form.numerator, relation, symbols, style);
  const Fraction f{form.numerator, form.denominator};
  const std::string note = style == Style::Latex ? "\\quad\\text{(sign of the denominator not proved)}"
                                                 : "  (sign of the denominator not proved)";
  return format_fraction(f, symbols, style) + " " + relation_text(relation, false, style) + " 0" + (style == Style::Ascii ? "" : note);
}

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
      if (style == Style::Latex)
        fraction = "\\frac{" + top + "}{" + name + "}";
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
  return form.readable ? format_readable(*form.readable, relation, symbols, style) : format_condition(form, relation, symbols, style);
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

std::string report(const Derivation& d, const Deriver& deriver, Style style) {
  if (style == Style::Ascii) throw std::invalid_argument("report(): ASCII output is JSON (see `superball derive --format json`)");
  const Symbols& sy = *d.symbols;
  const bool tex = style == Style::Latex;
  const int n = sy.bodies();
  std::ostringstream os;
  auto line = [&](const std::string& label, const std::string& value) {
    if (tex)
      os << "\\noindent " << label << (label.empty() ? "" : " ") << value << "\\par\n";
    else
      os << "  " << label << (label.empty() ? "" : " ") << value << '\n';
  };
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
  line("reduced system:", std::to_string(d.free_clusters) + " unknown velocit" + (d.free_clusters == 1 ? "y" : "ies") +
                              ", " + prose("det(Z^T A Z)", style) + " = " + math(format_polynomial(d.determinant, sy, style), style));
  if (tex) os << "\\noindent velocities after the collision:\\par\n";
  else os << "  velocities after the collision:\n";
  for (int i = 1; i <= n; ++i)
    line(tex ? "\\quad" : "  ", math(velocity_name(i, style) + " = " + format_fraction(d.velocities[static_cast<std::size_t>(i - 1)], sy, style), style));
  bool any_closed = false;
  for (int c = 0; c + 1 < n; ++c) any_closed = any_closed || d.closed.closed(c);
  if (any_closed) {
    if (tex) os << "\\noindent reactions on the closed contacts:\\par\n";
    else os << "  reactions on the closed contacts:\n";
    for (int c = 0; c + 1 < n; ++c)
      if (d.closed.closed(c))
        line(tex ? "\\quad" : "  ", math(reaction_name(Pair{c + 1, c + 2}, style) + " = " + format_fraction(d.reactions[static_cast<std::size_t>(c)], sy, style), style));
  }
  line("check:", prose(d.check, style));
  for (const NamedPart& p : d.named)
    line(p.index == 1 ? "where" : "     ", math(named_part_name(p.index, style) + " = " + format_polynomial(p.value, sy, style) + (p.positive ? " > 0" : ""), style) +
                                            (p.positive ? " (every term positive)" : prose(" (a diagonal entry of Z^T A Z)", style)));
  if (d.actual == Verdict::Never)
    line("never actual:", "the condition on " + d.actual_reason + " below fails for every admissible parameter, so this case is never the evolution");
  const std::string infinity = tex ? "m_{" + std::to_string(n) + "} = \\infty" : "m" + subscript_digits(std::to_string(n)) + " = ∞";
  const bool finite = sy.obstacle() == Obstacle::Finite;
  line("conditions:", std::string(finite ? "finite obstacle with " + math(sy.info(sy.mass(n)).name(style), style) + ", " : "") +
                          "exact with " + math(infinity, style) + (finite ? " (the limit)" : "") + "; asymptotic" +
                          (finite ? " of the finite-obstacle form" : "") + " for " + math(deriver.scaling().describe(sy, style), style) +
                          ", " + std::to_string(deriver.order() + 1) + " order(s) of " + math(tex ? "\\varepsilon" : "ε", style) + " kept");
  for (const Condition& c : d.conditions) {
    if (tex)
      os << "\\medskip\\noindent " << condition_title(c, style) << "\\par\n";
    else
      os << "  " << condition_title(c, style) << '\n';
    if (c.finite) line(tex ? "\\quad finite obstacle:" : "    finite obstacle:", math(format_form(*c.finite, c.relation, sy, style), style));
    line(tex ? "\\quad exact:" : "    exact:     ", math(format_form(c.exact, c.relation, sy, style), style) +
                                                       (c.exact.verdict == Verdict::Depends ? "" : std::string("  [") + to_string(c.exact.verdict) + "]"));
    line(tex ? "\\quad asymptotic:" : "    asymptotic:", math(format_form(c.asymptotic, c.relation, sy, style), style) + "  [" +
                                                           (c.asymptotic.verdict == Verdict::Depends ? "" : std::string(to_string(c.asymptotic.verdict)) + ", ") +
                                                           order_note(c, style) + "]");
    const std::string proof = short_proof(c);
    if (!proof.empty()) line(tex ? "\\quad" : "    ", "(" + prose(proof, style) + ")");
  }
  return os.str();
}

std::string latex_document(const std::vector<Derivation>& derivations, const Deriver& deriver) {
  std::ostringstream os;
  os << "\\documentclass[a4paper]{article}\n\\usepackage{amsmath}\n\\usepackage[margin=2cm]{geometry}\n"
        "\\sloppy\n\\begin{document}\n\\section*{Evolution cases and their conditions}\n";
  if (!derivations.empty()) {
    os << "Denominators are cleared only with a proved sign: every velocity and reaction of a case has the denominator "
          "$\\det(Z^{T}AZ)$, $A = \\mathrm{diag}(m) + D^{T}MD$, $Z$ the cluster incidence, which is positive definite for "
          "positive masses and $M$ positive semi-definite; a factor of it never vanishes on the connected set of admissible "
          "parameters, so its sign is its sign at $m = K = a = 1$, couplings $0$.\n";
  }
  for (const Derivation& d : derivations) os << report(d, deriver, Style::Latex) << '\n';
  os << "\\end{document}\n";
  return os.str();
}

}  // namespace superball::symbolic
