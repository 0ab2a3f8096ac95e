#pragma once
/// \file derivation.hpp
/// A derivation as people and programs read it: the report in text and
/// LaTeX (`superball derive`, `--format latex`), a standalone LaTeX document,
/// and the JSON of `--format json`.  Shared by the command and the Python
/// module.  The formulas themselves are symbolic/format.hpp's.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "superball/symbolic/derivation.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// The forms derivation_json() (and, compact, report()) print of a case:
/// every one when \p expanded, else symbolic::Forms::Printed (a long form
/// written through the case's elimination is printed through it only).
symbolic::Forms printed_forms(bool expanded);

/// Whether the text report writes \p p (the determinant of \p d) through
/// the case's elimination, and the compact JSON likewise: the case has one
/// and \p p has more than symbolic::max_inline_exact_terms terms.
bool through_elimination(const symbolic::Derivation& d, const GiNaC::ex& p);
/// The same for \p f, a velocity or a reaction of \p d, by its
/// symbolic::Fraction::terms (its numerator is not built in GiNaC when so
/// written under symbolic::Forms::Printed).
bool through_elimination(const symbolic::Derivation& d, const symbolic::Fraction& f);

/// One condition: kind, about, the exact and asymptotic forms in ASCII
/// (GiNaC's syntax), text and LaTeX, the readable and eliminated forms when
/// there are, the order in ε, the verdicts and the proof.  Compact (not
/// \p expanded): a form written through the case's elimination (an
/// `eliminated` form) leaves out its expanded forms (exact, text, latex;
/// asymptotic, asymptotic_text, asymptotic_latex; finite).
nlohmann::ordered_json condition_json(const symbolic::Condition& c, const symbolic::Symbols& s, bool expanded);

/// The case \p d of \p deriver: symbols, velocities, reactions, the
/// determinant, named parts, the elimination when set, and the conditions.
/// \p psd holds the JSON of the conditions on M (Deriver::psd(), the same in
/// every case), made on the first call and reused: with many cases they
/// were most of the conditions written.  Compact (not \p expanded, the
/// command's default): the conditions as condition_json() says, and a
/// velocity, reaction or determinant that the text report writes through the
/// elimination is that form over the names of `elimination.definitions`
/// ("V1", "p1*p2*p3"); \p expanded writes every expanded form (1.7 GB at 8
/// bodies against 12 MB).  \p with_psd false leaves out the conditions on
/// M: a compact list of several cases has them in its first case only, as
/// the text report writes them once (at 8 bodies they were 104 MB of the
/// 144 MB when repeated in every case).
nlohmann::ordered_json derivation_json(const symbolic::Derivation& d, const symbolic::Deriver& deriver,
                                       std::vector<nlohmann::ordered_json>& psd, bool expanded, bool with_psd = true);

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

SUPERBALL_PRESENT_API_END
