#pragma once
/// \file document.hpp
/// A small document model for reports, written once and rendered as
/// Markdown and as LaTeX (so report.md and report.tex always agree).

#include <string>
#include <vector>

namespace superball::cli {

/// A report: headings, paragraphs, tables, figures and verbatim blocks.
/// Text may use `code` spans; "§", "->" and "<=" are rendered per format.
class Document {
 public:
  explicit Document(std::string title) : title_(std::move(title)) {}
  void heading(const std::string& text) { blocks_.push_back({Kind::Heading, text, {}, {}}); }
  void paragraph(const std::string& text) { blocks_.push_back({Kind::Paragraph, text, {}, {}}); }
  void bullets(const std::vector<std::string>& items) { blocks_.push_back({Kind::Bullets, "", {}, {items}}); }
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  /// A figure \p stem.png / \p stem.svg in the report folder.
  void figure(const std::string& stem, const std::string& caption) { blocks_.push_back({Kind::Figure, caption, stem, {}}); }
  void verbatim(const std::string& text) { blocks_.push_back({Kind::Verbatim, text, {}, {}}); }

  std::string markdown() const;
  std::string latex() const;

 private:
  enum class Kind { Heading, Paragraph, Bullets, Table, Figure, Verbatim };
  struct Block {
    Kind kind;
    std::string text, stem;
    std::vector<std::vector<std::string>> rows;  // bullets: rows[0]; table: header then rows
  };
  std::string title_;
  std::vector<Block> blocks_;
};

/// \p text with LaTeX's special characters escaped and `code` spans typeset.
std::string latex_text(const std::string& text);

}  // namespace superball::cli
