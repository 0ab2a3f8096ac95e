#pragma once
// The falling chain of the long-chain benchmark (bench/bench_chain.cpp) and
// tests (tests/numeric/chain_test.cpp): one generator for both.
#include "superball/numeric/problem.hpp"

namespace superball::test {

/// A falling stack of light bodies: masses 0.001 … 0.007 repeating, K = 1
/// on (i, i+1), 1/2 on (i, i+2), a coupling 1/4 between (i, i+1) and
/// (i+1, i+2) (M diagonally dominant, so positive definite); the bodies fall
/// onto a fixed obstacle, the top fastest: speeds step down from 1.9 to 1.0
/// m/s in tenths (−1.9 + ⌊10 i/(n−1)⌋/10), so every contact closes, as the
/// collision law requires.  For n ≥ 2000 every contact stays closed and the
/// chain stops on the obstacle (the active set is found without an
/// iteration); for n = 32 24 of the 31 contacts stay closed.
inline numeric::Problem<double> falling_chain(int n) {
  numeric::Problem<double> p;
  p.n = n;
  p.fixed_bottom = true;
  for (int i = 0; i < n; ++i) {
    p.mass.push_back(i + 1 == n ? 0.0 : 0.001 * (1 + i % 7));
    p.u.push_back(i + 1 == n ? 0.0 : -1.9 + (10 * i / (n - 1)) / 10.0);  // the top falls fastest
  }
  for (int i = 0; i + 1 < n; ++i) {
    p.entries.push_back({i, i + 1, i, i + 1, 1.0});
    if (i + 2 < n) {
      p.entries.push_back({i, i + 2, i, i + 2, 0.5});
      p.entries.push_back({i, i + 1, i + 1, i + 2, 0.25});
    }
  }
  return p;
}

}  // namespace superball::test
