#pragma once
// The LaTeX layout of a derivation's report (present/derivation.hpp): a
// width estimate of math-mode LaTeX in Computer Modern at 10 pt, formulas
// that do not fit on a line set as align* displays broken by hand between
// terms (amsmath only; breqn is not in texlive-latex-base), and long
// fractions written as \frac{prefix}{\Delta} (…) so that their terms can
// go on several rows.  Private to present/.

#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

#include "superball/symbolic/derivation.hpp"

namespace superball::present::latex {

/// \textwidth of latex_document(): a4paper (597.51 pt) less two margins of 2 cm (56.91 pt each).
constexpr double kTextWidthPt = 483.69;
/// Widest a displayed row is made, by the estimate of latex_width().  With
/// rows and lines made a full \textwidth wide by the estimate, TeX found them
/// at most 12 pt (2.5 %) wider in the documents of tests/present/latex_test.cpp;
/// the 10 % kept free is four times that.
constexpr double kDisplayRowPt = 0.9 * kTextWidthPt;
/// + or − (cmr10, cmsy10), a unary sign, in pt.
constexpr double kSignPt = 7.78;
/// >, <, =, \le, \ge, \sim with \thickmuskip on both sides, in pt.
constexpr double kRelationPt = kSignPt + 2 * 2.78;

/// Estimated width in pt of the math-mode LaTeX \p s at size \p scale (1 =
/// text size), as the report writes it: symbols with sub- and superscripts,
/// \frac, \text, operators written " + ", relations " > ".
double latex_width(const std::string& s, double scale = 1.0);

/// The rows of an align* for \p math, each at most \p width wide by
/// latex_width() (a single term wider than that gets a row of its own).  A
/// short first side stays in the left column and the rest aligns on its
/// relation; a long one is broken like the others.  A row that continues a
/// side starts with \quad and its operator ({}+ keeps + binary); a row that
/// starts a side starts with its relation.
std::string display_rows(const std::string& math, double width);

/// LaTeX text of the library's prose: relations in math mode (a text-mode
/// > prints as ¿ in OT1), det(Z^T A Z) as $\det(Z^{T}AZ)$, signs as $+$ and
/// $-$, LaTeX specials escaped.
std::string latex_prose(const std::string& s);

/// "\noindent LABEL $MATH$ NOTE\par" when it fits on a line (by the width
/// estimate), else "\noindent LABEL NOTE" followed by an align* of
/// display_rows().
std::string latex_formula_line(const std::string& label, const std::string& math, const std::string& note);

/// The right side of "NAME = f" in LaTeX: symbolic::format_fraction() when it
/// fits in \p width; else PREFIX/DEN (REST) with the denominator written
/// \Delta when it is \p determinant, so that the terms of REST can be broken
/// over rows.  \p den_name names a long denominator that is not \Delta; its
/// value is appended to \p where ("D_{…} = …").
std::string latex_fraction(const symbolic::Fraction& f, const symbolic::Symbols& sy, const GiNaC::ex& determinant, double width,
                           const std::string& den_name, std::vector<std::pair<std::string, std::string>>& where);

}  // namespace superball::present::latex
