#include "document.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>

namespace superball::cli {
namespace {

/// Width of the LaTeX line in average characters of the tables' \small font, and what a column adds.
constexpr double line_chars = 100, column_gap_chars = 2.5;

/// The UTF-8 sequence starting at \p i (one code point).
std::string code_point(const std::string& s, std::size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  const std::size_t n = c < 0x80 ? 1 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : 4;
  return s.substr(i, n);
}

/// Number of code points of \p s (the width of plain text, roughly).
std::size_t length(const std::string& s) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.size(); i += code_point(s, i).size()) ++n;
  return n;
}

/// The math-mode LaTeX of a text-notation character or sequence, or nullptr.
const char* math_symbol(const std::string& s) {
  static const std::pair<const char*, const char*> table[] = {
      {"->", "\\to"}, {"<=", "\\le"}, {">=", "\\ge"}, {"<", "<"}, {">", ">"}, {"≤", "\\le"}, {"≥", "\\ge"}, {"−", "-"},
      {"·", "\\cdot"}, {"→", "\\to"}, {"∞", "\\infty"}, {"⪰", "\\succeq"}, {"∈", "\\in"}, {"≠", "\\ne"}, {"α", "\\alpha"},
      {"ε", "\\varepsilon"}, {"λ", "\\lambda"}, {"√", "\\surd"}};
  for (const auto& [from, to] : table)
    if (s == from) return to;
  return nullptr;
}

/// The digit (or sign) a Unicode subscript (\p sub) or superscript stands for, or 0.
char script_char(const std::string& s, bool sub) {
  static const char* const subs[] = {"₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"};
  static const char* const sups[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  for (int d = 0; d < 10; ++d)
    if (s == (sub ? subs : sups)[d]) return static_cast<char>('0' + d);
  if (!sub && s == "⁺") return '+';
  if (!sub && s == "⁻") return '-';
  if (!sub && s == "ᵀ") return 'T';
  return 0;
}

/// The run of Unicode subscripts (\p sub) or superscripts starting at \p i, as
/// the characters they stand for ("₁₂,₁₄" -> "12,14"); \p i moves past it.
std::string script_run(const std::string& text, std::size_t& i, bool sub) {
  std::string script;
  while (i < text.size()) {
    const std::string c = code_point(text, i);
    if (const char d = script_char(c, sub))
      script += d;
    else if (sub && c == "," && i + 1 < text.size() && script_char(code_point(text, i + 1), true))
      script += ',';
    else
      break;
    i += c.size();
  }
  return script;
}

/// Plain text (no code spans) as LaTeX: special characters escaped, **bold**
/// typeset, the text notation's math characters in math mode (adjacent pieces
/// merged into one formula, a run of sub- or superscripts into one script, a
/// letter carrying one in math italic).  In \p code (typewriter, never
/// hyphenated), a line may break after '-' too.
std::string latex_plain(const std::string& text, bool code = false) {
  std::string out;
  bool math_open = false, bold = false;
  auto add = [&](const std::string& s, bool math) {
    if (math != math_open) out += '$';
    math_open = math;
    out += s;
  };
  for (std::size_t i = 0; i < text.size();) {
    const std::string cp = code_point(text, i), two = text.substr(i, 2);
    if (two == "->" || two == "<=" || two == ">=") {
      add(std::string(math_symbol(two)) + ' ', true);
      i += 2;
    } else if (two == "**") {
      add(bold ? "}" : "\\textbf{", false);
      bold = !bold;
      i += 2;
    } else if (script_char(cp, true) || script_char(cp, false)) {
      const bool sub = script_char(cp, true) != 0;
      add(std::string(sub ? "_{" : "^{") + script_run(text, i, sub) + "}", true);
    } else {
      i += cp.size();
      const std::string after = i < text.size() ? code_point(text, i) : "";
      if (const char* m = math_symbol(cp))
        add(std::string(m) + ' ', true);
      else if (std::isalpha(static_cast<unsigned char>(cp[0])) && (script_char(after, true) || script_char(after, false)))
        add(cp, true);  // the symbol of K₁₂, m₁, U₁⁺ in math italic
      else if (cp == "\\")
        add("\\textbackslash{}", false);
      else if (cp.size() == 1 && std::string("_%&#${}").find(cp[0]) != std::string::npos)
        add("\\" + cp, false);
      else if (cp == "~")
        add("\\sim ", true);
      else if (cp == "^")
        add("\\^{}", false);
      else if (cp == "|")
        add("|", true);
      else if (cp == "§")
        add("\\S", true);
      else if (cp == "/" || (code && cp == "-"))
        add(cp + "\\allowbreak{}", false);  // a line may break after it (paths, long fractions)
      else if (cp == "—")
        add("---", false);
      else if (cp == "–")
        add("--", false);
      else if (cp == "…")
        add("\\ldots{}", false);
      else
        add(cp, false);  // anything else unknown to LaTeX is reported by LaTeX
    }
  }
  add(bold ? "}" : "", false);
  return out;
}

std::string latex_cell(const Cell& c) { return c.latex.empty() ? latex_text(c.text) : c.latex; }

/// LaTeX column types for \p rows (header first): \p widths when given
/// (fractions of the line, wrapping columns); else natural widths while the
/// table fits the line, and otherwise the narrow columns keep their width and
/// the wide ones share what is left equally, wrapping (water filling).
std::string column_spec(const std::vector<std::vector<Cell>>& rows, std::vector<double> widths) {
  const std::size_t n = rows[0].size();
  if (widths.empty()) {
    std::vector<double> natural(n, 0);
    for (const auto& row : rows)
      for (std::size_t c = 0; c < n && c < row.size(); ++c) natural[c] = std::max(natural[c], static_cast<double>(length(row[c].text)));
    double left = line_chars - column_gap_chars * static_cast<double>(n), total = 0;
    for (double w : natural) total += w;
    if (total <= left) return std::string(n, 'l');
    std::vector<bool> wide(n, true);
    std::size_t count = n;
    for (bool changed = true; changed && count > 0;) {
      changed = false;
      const double share = left / static_cast<double>(count);
      for (std::size_t c = 0; c < n; ++c)
        if (wide[c] && natural[c] <= share) {
          wide[c] = false;
          left -= natural[c];
          --count;
          changed = true;
        }
    }
    widths.assign(n, 0);
    for (std::size_t c = 0; c < n; ++c)
      if (wide[c]) widths[c] = (left / static_cast<double>(count) + column_gap_chars) / line_chars;
  }
  std::string spec;
  for (std::size_t c = 0; c < n; ++c) {
    if (c >= widths.size() || widths[c] <= 0) {
      spec += 'l';
      continue;
    }
    char width[32];
    std::snprintf(width, sizeof width, "%.3f", widths[c]);
    spec += std::string(">{\\raggedright\\arraybackslash}p{\\dimexpr ") + width + "\\linewidth-2\\tabcolsep}";
  }
  return spec;
}

}  // namespace

std::string latex_text(const std::string& text) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const auto open = text.find('`', i);
    const auto close = open == std::string::npos ? open : text.find('`', open + 1);
    if (close == std::string::npos) {
      out += latex_plain(text.substr(i));
      break;
    }
    out += latex_plain(text.substr(i, open - i)) + "\\texttt{" + latex_plain(text.substr(open + 1, close - open - 1), true) + "}";
    i = close + 1;
  }
  return out;
}

void Document::bullets(const std::vector<std::string>& items) {
  blocks_.push_back({Kind::Bullets, "", {}, {std::vector<Cell>(items.begin(), items.end())}, {}});
}

void Document::table(const std::vector<std::string>& header, const std::vector<std::vector<Cell>>& rows, const std::vector<double>& widths) {
  Block b{Kind::Table, "", "", {std::vector<Cell>(header.begin(), header.end())}, widths};
  b.rows.insert(b.rows.end(), rows.begin(), rows.end());
  blocks_.push_back(std::move(b));
}

std::string Document::markdown() const {
  std::ostringstream os;
  os << "# " << title_ << "\n\n";
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Kind::Heading: os << "## " << b.text << "\n\n"; break;
      case Kind::Subheading: os << "### " << b.text << "\n\n"; break;
      case Kind::Paragraph: os << b.text << "\n\n"; break;
      case Kind::Bullets:
        for (const auto& item : b.rows[0]) os << "- " << item.text << '\n';
        os << '\n';
        break;
      case Kind::Table:
        for (std::size_t r = 0; r < b.rows.size(); ++r) {
          os << '|';
          for (const auto& cell : b.rows[r]) {
            std::string s = cell.text;
            for (std::size_t at = s.find('|'); at != std::string::npos; at = s.find('|', at + 2)) s.insert(at, "\\");
            os << ' ' << s << " |";
          }
          os << '\n';
          if (r == 0) {
            os << '|';
            for (std::size_t c = 0; c < b.rows[0].size(); ++c) os << "---|";
            os << '\n';
          }
        }
        os << '\n';
        break;
      case Kind::Figure: os << "![" << b.text << "](" << b.stem << ".svg)\n\n*" << b.text << "*\n\n"; break;
      case Kind::Verbatim: os << "```\n" << b.text << (b.text.empty() || b.text.back() == '\n' ? "" : "\n") << "```\n\n"; break;
    }
  }
  return os.str();
}

std::string Document::latex() const {
  std::ostringstream os;
  os << "\\documentclass[10pt,a4paper]{article}\n\\usepackage[utf8]{inputenc}\n\\usepackage{amsmath}\n"
        "\\usepackage{graphicx}\n\\usepackage{array}\n\\usepackage{longtable}\n\\usepackage[margin=2cm]{geometry}\n\\sloppy  % generated text: loose lines rather than lines past the margin\n\\renewcommand{\\labelitemi}{$\\bullet$}  % Computer Modern math, not a bitmap text-companion font\n"
     << "\\title{" << latex_text(title_) << "}\n\\date{}\n\\begin{document}\n\\maketitle\n\n";
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Kind::Heading: os << "\\section*{" << latex_text(b.text) << "}\n\n"; break;
      case Kind::Subheading: os << "\\subsection*{" << latex_text(b.text) << "}\n\n"; break;
      case Kind::Paragraph: os << latex_text(b.text) << "\n\n"; break;
      case Kind::Bullets:
        os << "\\begin{itemize}\n";
        for (const auto& item : b.rows[0]) os << "\\item " << latex_cell(item) << '\n';
        os << "\\end{itemize}\n\n";
        break;
      case Kind::Table: {
        // Wrapping columns make tall tables: those break across pages (longtable); the others stay whole.
        const std::string spec = column_spec(b.rows, b.widths);
        const bool wraps = spec.find("p{") != std::string::npos;
        os << (wraps ? "{\\small\n\\begin{longtable}{" : "\\begin{center}\\small\n\\begin{tabular}{") << spec << "}\n\\hline\n";
        for (std::size_t r = 0; r < b.rows.size(); ++r) {
          for (std::size_t c = 0; c < b.rows[r].size(); ++c) os << (c ? " & " : "") << latex_cell(b.rows[r][c]);
          os << " \\\\\n" << (r > 0 ? "" : wraps ? "\\hline\n\\endhead\n" : "\\hline\n");
        }
        os << (wraps ? "\\hline\n\\end{longtable}}\n\n" : "\\hline\n\\end{tabular}\n\\end{center}\n\n");
        break;
      }
      case Kind::Figure:  // in place, as in Markdown (a float could drift past a longtable, which breaks it)
        os << "\\par\\noindent\\begin{minipage}{\\linewidth}\n\\centering\n\\includegraphics[width=0.8\\linewidth]{" << b.stem
           << ".png}\\par\\smallskip\n{\\small\\itshape " << latex_text(b.text) << "\\par}\n\\end{minipage}\n\\medskip\n\n";
        break;
      case Kind::Verbatim: os << "\\begin{verbatim}\n" << b.text << (b.text.empty() || b.text.back() == '\n' ? "" : "\n") << "\\end{verbatim}\n\n"; break;
    }
  }
  os << "\\end{document}\n";
  return os.str();
}

}  // namespace superball::cli
