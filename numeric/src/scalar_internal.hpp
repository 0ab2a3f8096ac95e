#pragma once
// Internal: the exact route of numeric::to_decimal() (scalar.cpp), which
// takes a shortcut in 128-bit integers for rationals of small numerator and
// denominator; tests/numeric/problem_test.cpp checks that both give the
// same text.

#include <cln/rational.h>

#include <string>

namespace superball::numeric::detail {

/// to_decimal() computed in CLN's exact rationals whatever \p x is.
std::string to_decimal_by_cln(const cln::cl_RA& x, int significant);

}  // namespace superball::numeric::detail
