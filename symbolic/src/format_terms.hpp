#pragma once
// The term-level pieces shared by the files of format.hpp (format.cpp: term
// order, polynomials, fractions, conditions and readable forms;
// format_elimination.cpp: the elimination, the names and the titles).
// Private to the library.

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "polynomial.hpp"
#include "superball/symbolic/format.hpp"

namespace superball::symbolic::detail {

/// "₁₂" of "12": each digit as a Unicode subscript, other characters as they are.
std::string subscript_digits(const std::string& digits);
/// The minus sign of \p style: "−" (text), "-" (LaTeX, ASCII).
const char* minus(Style style);
/// A term with its coefficient's absolute value: "2m₁K₁₂" (text), "2*m1*K12" (ASCII).
std::string term_text(const Term& t, const Symbols& symbols, Style style);
/// The terms of the expanded \p p in the canonical order (format.hpp); throws
/// std::invalid_argument("format_polynomial(): ...") when p is not a polynomial in \p symbols.
std::vector<Term> sorted_terms(const GiNaC::ex& p, const Symbols& symbols);
/// ">" / "≥" (or turned "<" / "≤") in \p style.
std::string relation_text(Relation r, bool turned, Style style);

}  // namespace superball::symbolic::detail
