// The reports of a derivation for people (`superball derive`, text and
// LaTeX; the Python module's Derivation.report): present/derivation.hpp.
// Formulas come from symbolic/format.hpp, the LaTeX layout from latex_layout.hpp.
#include <ginac/ginac.h>

#include <sstream>
#include <stdexcept>
#include <tuple>

#include "latex_layout.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/present/derivation.hpp"
#include "superball/symbolic/format.hpp"

namespace superball::present {

using namespace superball::symbolic;
using latex::kDisplayRowPt;
using latex::kRelationPt;
using latex::display_rows;
using latex::latex_formula_line;
using latex::latex_fraction;
using latex::latex_prose;
using latex::latex_width;

namespace {

/// \p s in math mode when \p style is LaTeX ($…$), else as it is.
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

/// "order ε^-1; the leading terms of order ε^-2 cancel": the order of a condition's asymptotic form.
std::string order_note(const Condition& c, Style style) {
  std::string s = "order " + math(epsilon_power(c.leading_order, style), style);
  if (c.descended > 0) {
    s += "; the leading terms of order " + math(epsilon_power(c.leading_order - c.descended, style), style) + " cancel";
  }
  return s;
}

/// How a condition's denominator was cleared, in a few words ("" for a condition on M).
std::string short_proof(const Condition& c) {
  if (c.kind == ConditionKind::Psd) return "";
  if (c.proof.rfind("sign not proved", 0) == 0) return "sign of the denominator not proved";
  if (c.proof.rfind("the denominator divides", 0) == 0)
    return std::string("denominator cleared: a factor of det(Z^T A Z) > 0, sign ") + (c.proof.find(": +,") != std::string::npos ? "+" : "-");
  return "denominator cleared: " + c.proof;
}

/// How many orders of ε the asymptotic forms keep, in words.
std::string orders_kept_text(int order) {
  if (order == 0) return "the dominant balance only";
  return "the dominant balance and the next " + (order == 1 ? std::string("order") : std::to_string(order) + " orders");
}

/// A labelled line: "  LABEL VALUE" (text), "\noindent LABEL VALUE\par" (LaTeX).
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
    const std::string minus = style == Style::Text ? "−" : "-";
    std::string quantity;
    if (c.kind == ConditionKind::Superball) {
      quantity = velocity_name(1, style) + " " + minus + " a";
    } else {
      const Pair p = Pair::parse(c.about);
      quantity = c.kind == ConditionKind::Evolution ? velocity_name(p.i, style) + " " + minus + " " + velocity_name(p.j, style)
                                                    : minus + reaction_name(p, style);
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
                        ? "fixed (" + math(mass_name(n, style) + (tex ? " = \\infty" : " = ∞"), style) + ", it stays at rest)"
                        : "finite mass " + math(sy.info(sy.mass(n)).name(style), style));
  // LaTeX: det(ZᵀAZ) is named \Delta once, and long velocities and reactions are written over it.
  const bool named_determinant = tex && !GiNaC::is_a<GiNaC::numeric>(d.determinant);
  const std::string unknowns = std::to_string(d.free_clusters) + " unknown velocit" + (d.free_clusters == 1 ? "y" : "ies") + ",";
  // A long case is written through its elimination (Elimination): det(ZᵀAZ) as the product of the pivots,
  // long velocities as cluster velocities V, long reactions as sums over them.
  const Elimination* e = d.elimination ? &*d.elimination : nullptr;
  auto is_long = [&](const auto& p) { return through_elimination(d, p); };
  std::string determinant = format_polynomial(d.determinant, sy, style);
  if (is_long(d.determinant)) determinant = format_pivot_product(*e, style);
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
    velocities.emplace_back(velocity_name(i, style), &f, is_long(f) ? cluster_velocity_name(c, style) : "");
    if (i < n && !d.closed.closed(i - 1)) ++c;  // the next body starts a cluster
  }
  fractions("velocities after the collision:", velocities);
  for (int c = 0; c + 1 < n; ++c) {
    if (!d.closed.closed(c)) continue;
    const Fraction& f = d.reactions[static_cast<std::size_t>(c)];
    reactions.emplace_back(reaction_name(Pair{c + 1, c + 2}, style), &f,
                           is_long(f) ? format_linear(d.reactions_eliminated[static_cast<std::size_t>(c)], sy, style, true) : "");
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
  const std::string infinity = mass_name(n, style) + (tex ? " = \\infty" : " = ∞");
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

}  // namespace superball::present
