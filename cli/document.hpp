#pragma once
/// \file document.hpp
/// A small document model for reports, written once and rendered as
/// Markdown and as LaTeX (so report.md and report.tex always agree).

#include <string>
#include <utility>
#include <vector>

namespace superball::cli {

/// A table cell: plain text, or text with its own LaTeX form (a formula).
/// Plain text is escaped for LaTeX by latex_text().
struct Cell {
  Cell(std::string plain) : text(std::move(plain)) {}  // NOLINT: plain strings are cells
  Cell(const char* plain) : text(plain) {}             // NOLINT
  Cell(std::string text_form, std::string latex_form) : text(std::move(text_form)), latex(std::move(latex_form)) {}
  /// A formula: \p text_form in Markdown (Unicode notation), \p latex_math (math mode, without $) in LaTeX.
  static Cell math(std::string text_form, const std::string& latex_math) { return Cell(std::move(text_form), "$" + latex_math + "$"); }

  std::string text;   ///< what Markdown shows
  std::string latex;  ///< LaTeX source; empty: latex_text(text)
};

/// A report: headings, paragraphs, tables, figures and verbatim blocks.
/// Text may use `code` spans and **bold**; "§", "->", "<=", ">=" and the
/// Unicode math characters of the symbolic library's text notation (α₂,
/// K₁₄, ≤, …) are rendered per format.
class Document {
 public:
  explicit Document(std::string title) : title_(std::move(title)) {}
  void heading(const std::string& text) { blocks_.push_back({Kind::Heading, text, {}, {}, {}}); }
  /// A heading one level below heading().
  void subheading(const std::string& text) { blocks_.push_back({Kind::Subheading, text, {}, {}, {}}); }
  void paragraph(const std::string& text) { blocks_.push_back({Kind::Paragraph, text, {}, {}, {}}); }
  void bullets(const std::vector<std::string>& items);
  /// A table.  In LaTeX, long tables break across pages; \p widths, when
  /// given, are the columns' widths as fractions of the line (wrapping text,
  /// 0 for a natural-width column); without them, a table too wide for the
  /// line wraps its widest columns in the width the narrow ones leave.
  void table(const std::vector<std::string>& header, const std::vector<std::vector<Cell>>& rows, const std::vector<double>& widths = {});
  /// A figure \p stem.png / \p stem.svg in the report folder.
  void figure(const std::string& stem, const std::string& caption) { blocks_.push_back({Kind::Figure, caption, stem, {}, {}}); }
  void verbatim(const std::string& text) { blocks_.push_back({Kind::Verbatim, text, {}, {}, {}}); }

  std::string markdown() const;
  std::string latex() const;

 private:
  enum class Kind { Heading, Subheading, Paragraph, Bullets, Table, Figure, Verbatim };
  struct Block {
    Kind kind;
    std::string text, stem;
    std::vector<std::vector<Cell>> rows;  // bullets: rows[0]; table: header then rows
    std::vector<double> widths;           // table: column widths (fractions of the line), may be empty
  };
  std::string title_;
  std::vector<Block> blocks_;
};

/// \p text with LaTeX's special characters escaped and `code` spans typeset.
std::string latex_text(const std::string& text);

}  // namespace superball::cli
