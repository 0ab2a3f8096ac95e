// The LaTeX layout of a derivation's report: latex_layout.hpp.
#include "latex_layout.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "superball/symbolic/format.hpp"

namespace superball::present::latex {

using namespace superball::symbolic;

namespace {

/// Widest a "label: formula" line is kept inline, by the same estimate.
constexpr double kInlineLinePt = 0.9 * kTextWidthPt;
/// A first side (left of the first relation) at most this wide stays in the
/// left column of the display, the rest aligned on its relation; a wider one
/// is broken like the right side.
constexpr double kLeadColumnPt = 0.3 * kTextWidthPt;
/// Widths at 10 pt of Computer Modern (cmr10, cmmi10, cmsy10), in pt.
constexpr double kDigitPt = 5.0, kLowerPt = 5.5, kUpperPt = 8.5, kWideLetterPt = 8.8, kCommandPt = 6.5;
constexpr double kBinaryPt = kSignPt + 2 * 2.22;    ///< + or − with \medmuskip on both sides
constexpr double kParenPt = 3.89, kBigParenPt = 4.6, kPunctPt = 2.78 + 1.67, kQuadPt = 10.0;
constexpr double kDetPt = 15.6, kInfinityPt = 10.0, kBracePt = 5.0, kNullDelimiterPt = 1.2;  ///< \det, \infty, \{, each side of \frac
constexpr double kTextCharPt = 5.0, kTextUpperPt = 7.3, kTextSpacePt = 3.33;  ///< prose: a lower-case letter, a capital, a space
/// Subscripts and superscripts: cmr7/cmmi7 glyphs are about 0.8 of the 10 pt ones, cmr5 about 0.68.
constexpr double kScriptScale = 0.8, kScriptScriptScale = 0.68;

std::size_t group_end(const std::string& s, std::size_t open);  // index of the '}' closing s[open] == '{'

}  // namespace

/// Estimated width in pt of the math-mode LaTeX \p s at size \p scale (1 =
/// text size), as report() writes it: symbols with sub- and superscripts,
/// \frac, \text, operators written " + ", relations " > ".
double latex_width(const std::string& s, double scale) {
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

namespace {

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

}  // namespace

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
  const CommonFactor num = format_common_factor(f.numerator, sy, Style::Latex);
  const std::string& prefix = num.factor;
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
  const std::string sign = num.negative ? "-" : "";
  if (num.rest_is_one) return sign + (den.empty() ? prefix : "\\frac{" + prefix + "}{" + den + "}");
  const std::string head = den.empty() ? (prefix == "1" ? "" : prefix) : "\\frac{" + prefix + "}{" + den + "}";
  const std::string& body = num.rest;
  if (head.empty()) return sign.empty() ? body : sign + "\\bigl(" + body + "\\bigr)";
  return sign + head + "\\bigl(" + body + "\\bigr)";
}

}  // namespace superball::present::latex
