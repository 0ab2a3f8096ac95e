#include "collision/magnitude.hpp"

#include <cln/integer.h>

namespace superball::numeric::detail {

namespace {

/// n = q·2^e with q the leading 62 bits of n > 0 (truncated), as a double.
double leading_bits(const cln::cl_I& n, long& e) {
  e = std::max(static_cast<long>(cln::integer_length(n)) - 62, 0L);
  return cln::double_approx(e > 0 ? cln::ash(n, -e) : n);
}

}  // namespace

Magnitude::Magnitude(const cln::cl_RA& x) {
  if (cln::zerop(x)) return;
  const cln::cl_RA a = cln::abs(x);
  long en = 0, ed = 0;
  const double q = leading_bits(cln::numerator(a), en) / leading_bits(cln::denominator(a), ed);
  int k = 0;
  const double m = std::frexp(q, &k);
  set(m, en - ed + k);
}

}  // namespace superball::numeric::detail
