#pragma once
// The proofs that a case's conditions cannot hold together (explore.hpp,
// "The proof"): weighted sums of the conditions against quadratic forms of
// M, and polynomial multipliers from a linear programme.  Private to the library.

#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <vector>

#include "superball/verify/explore.hpp"

namespace superball::verify::detail::explore {

/// "+e(1-2), -e(1-4)": the signs of \p x on \p pairs.
std::string signed_pairs(const std::vector<int>& x, const std::vector<Pair>& pairs);

/// xᵀMx for x ∈ {−1, 0, 1} on \p pairs, expanded.
GiNaC::ex quadratic_form(const std::vector<int>& x, const std::vector<Pair>& pairs, const symbolic::Symbols& sy);

/// Step \p x through {−1, 0, 1}^k (first digit fastest); false after the last.
bool next_signs(std::vector<int>& x);

/// Search weights w ∈ {0, 1, 2} on the case's conditions and a form Q >= 0
/// on M ⪰ 0 — t·xᵀMx (t ∈ {0, 1, 2}, x ∈ {−1, 0, 1} on the coupled pairs up
/// to sign) or a sum of multiples of the 2×2 minors' forms — with −Σ wᵢNᵢ − Q
/// certainly nonnegative and some strict condition weighted; then polynomial
/// multipliers from a linear programme.  Without the superball condition
/// first: a clash there proves the case never actual.  \p asymptotic: the
/// leading-order forms, else the exact ones.
std::optional<Clash> find_clash(const symbolic::Derivation& d, const symbolic::Symbols& sy, bool asymptotic);

}  // namespace superball::verify::detail::explore
