#pragma once
/// \file random_point.hpp
/// The random admissible points of the check_ tests of tests/symbolic.

#include <ginac/ginac.h>

#include <random>

#include "superball/symbolic/symbols.hpp"

namespace superball::symbolic::test {

/// A random admissible point: masses, K's and a in [1/7, 10] (rationals),
/// couplings small against the K's so that M stays positive semi-definite
/// (diagonally dominant).
inline GiNaC::exmap random_point(const Symbols& s, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> num(1, 70), den(1, 7), coupling(-6, 6);
  const auto couplings = static_cast<int>(s.pattern().couplings.size()) + 1;
  GiNaC::exmap at;
  for (const SymbolInfo& info : s.all())
    at[info.symbol] = info.kind == SymbolKind::Coupling ? GiNaC::numeric(coupling(rng), 7 * couplings) : GiNaC::numeric(num(rng), den(rng));
  return at;
}

}  // namespace superball::symbolic::test
