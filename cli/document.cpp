#include "document.hpp"

#include <sstream>

namespace superball::cli {
namespace {

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

std::string latex_plain(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    switch (c) {
      case '\\': out += "\\textbackslash{}"; break;
      case '_': case '%': case '&': case '#': case '$': case '{': case '}': out += std::string("\\") + c; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '*': out += (i + 1 < text.size() && text[i + 1] == '*') ? (++i, "") : "*"; break;  // drop **bold** marks
      case '|': out += "\\textbar{}"; break;
      default: out += c;
    }
  }
  out = replace_all(out, "§", "\\S{}");
  out = replace_all(out, "->", "$\\to$");
  out = replace_all(out, "<=", "$\\le$");
  out = replace_all(out, ">=", "$\\ge$");
  return out;
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
    out += latex_plain(text.substr(i, open - i)) + "\\texttt{" + latex_plain(text.substr(open + 1, close - open - 1)) + "}";
    i = close + 1;
  }
  return out;
}

void Document::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  Block b{Kind::Table, "", "", {header}};
  b.rows.insert(b.rows.end(), rows.begin(), rows.end());
  blocks_.push_back(std::move(b));
}

std::string Document::markdown() const {
  std::ostringstream os;
  os << "# " << title_ << "\n\n";
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Kind::Heading: os << "## " << b.text << "\n\n"; break;
      case Kind::Paragraph: os << b.text << "\n\n"; break;
      case Kind::Bullets:
        for (const auto& item : b.rows[0]) os << "- " << item << '\n';
        os << '\n';
        break;
      case Kind::Table:
        for (std::size_t r = 0; r < b.rows.size(); ++r) {
          os << '|';
          for (const auto& cell : b.rows[r]) os << ' ' << cell << " |";
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
  os << "\\documentclass[10pt]{article}\n\\usepackage[utf8]{inputenc}\n\\usepackage[T1]{fontenc}\n"
        "\\usepackage{graphicx}\n\\usepackage[margin=2cm]{geometry}\n"
     << "\\title{" << latex_text(title_) << "}\n\\date{}\n\\begin{document}\n\\maketitle\n\n";
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Kind::Heading: os << "\\section*{" << latex_text(b.text) << "}\n\n"; break;
      case Kind::Paragraph: os << latex_text(b.text) << "\n\n"; break;
      case Kind::Bullets:
        os << "\\begin{itemize}\n";
        for (const auto& item : b.rows[0]) os << "\\item " << latex_text(item) << '\n';
        os << "\\end{itemize}\n\n";
        break;
      case Kind::Table: {
        os << "\\begin{center}\\small\n\\begin{tabular}{" << std::string(b.rows[0].size(), 'l') << "}\n\\hline\n";
        for (std::size_t r = 0; r < b.rows.size(); ++r) {
          for (std::size_t c = 0; c < b.rows[r].size(); ++c) os << (c ? " & " : "") << latex_text(b.rows[r][c]);
          os << " \\\\\n" << (r == 0 ? "\\hline\n" : "");
        }
        os << "\\hline\n\\end{tabular}\n\\end{center}\n\n";
        break;
      }
      case Kind::Figure:
        os << "\\begin{figure}[h]\n\\centering\n\\includegraphics[width=0.8\\textwidth]{" << b.stem << ".png}\n\\caption*{"
           << latex_text(b.text) << "}\n\\end{figure}\n\n";
        break;
      case Kind::Verbatim: os << "\\begin{verbatim}\n" << b.text << (b.text.empty() || b.text.back() == '\n' ? "" : "\n") << "\\end{verbatim}\n\n"; break;
    }
  }
  os << "\\end{document}\n";
  return os.str();
}

}  // namespace superball::cli
