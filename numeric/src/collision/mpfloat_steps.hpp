#pragma once
// Internal: the in-place steps of the solver's hot loops on MpFloat
// (defined in numeric/src/mpfloat.cpp, inside the library only), which
// dense_steps.hpp's add_product() and subtract_product() reach by
// argument-dependent lookup.

#include "superball/numeric/mpfloat.hpp"

namespace superball::numeric {

/// x += a·b in place: the product rounded, then the sum rounded, each to the
/// larger precision of its operands (two roundings, as x += a * b, bit for
/// bit), without a temporary MpFloat.
void add_product(MpFloat& x, const MpFloat& a, const MpFloat& b);
/// x −= a·b in place, rounded as x -= a * b (two roundings).
void subtract_product(MpFloat& x, const MpFloat& a, const MpFloat& b);
/// x += a·b/2 in place, rounded as x += a * b / 2 (the halving exact in
/// MPFR's range: two roundings).
void add_half_product(MpFloat& x, const MpFloat& a, const MpFloat& b);

}  // namespace superball::numeric
