#pragma once
/// \file derivation.hpp
/// A derivation as people and programs read it: the report in text and
/// LaTeX (`superball derive`, `--format latex`), a standalone LaTeX document,
/// and the JSON of `--format json`.  Shared by the command and the Python
/// module; not installed.  The formulas themselves are symbolic/format.hpp's.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "superball/symbolic/derivation.hpp"

namespace superball::present {

/// One condition: kind, about, the exact and asymptotic forms in ASCII
/// (GiNaC's syntax), text and LaTeX, the readable and eliminated forms when
/// there are, the order in ε, the verdicts and the proof.
nlohmann::ordered_json condition_json(const symbolic::Condition& c, const symbolic::Symbols& s);

/// The case \p d of \p deriver: symbols, velocities, reactions, the
/// determinant, named parts, the elimination when set, and the conditions.
/// \p psd holds the JSON of the conditions on M (Deriver::psd(), the same in
/// every case), made on the first call and reused: with many cases they
/// were most of the conditions written.
nlohmann::ordered_json derivation_json(const symbolic::Derivation& d, const symbolic::Deriver& deriver,
                                       std::vector<nlohmann::ordered_json>& psd);

/// A full report of \p d in Text or Latex style (a LaTeX fragment: use
/// latex_document() for a compilable file); \p with_psd false leaves out the
/// conditions on M, which are the same in every case (report_psd()).
/// Throws std::invalid_argument ("report(): ...") for Style::Ascii (use JSON for programs).
std::string report(const symbolic::Derivation& d, const symbolic::Deriver& deriver, symbolic::Style style, bool with_psd = true);

/// The conditions on M of the deriver's pattern (paper §3: M positive
/// semi-definite, one principal minor per connected set of coupled pairs),
/// once, in Text or Latex style.  Throws std::invalid_argument("report_psd(): ...") for Style::Ascii.
std::string report_psd(const symbolic::Deriver& deriver, symbolic::Style style);

/// A standalone LaTeX document (article class, amsmath, geometry) with the
/// reports of \p derivations; compiles with texlive-latex-base's pdflatex
/// without an overfull line or a missing glyph (tests/present/latex_test.cpp).
std::string latex_document(const std::vector<symbolic::Derivation>& derivations, const symbolic::Deriver& deriver);

}  // namespace superball::present
