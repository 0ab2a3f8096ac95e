#pragma once
// Phase one of the simplex method, for the linear programme of the clash
// proofs (clash.cpp).  Private to the library.

#include <cstddef>
#include <optional>
#include <vector>

namespace superball::verify::detail::explore {

/// Phase one of the simplex method (dense tableau, Bland's rule): some x >= 0
/// with eq·x = b and le·x <= 0 (rows over \p n unknowns), or nullopt.
std::optional<std::vector<double>> feasible_point(std::vector<std::vector<double>> eq, std::vector<double> b,
                                                  const std::vector<std::vector<double>>& le, std::size_t n);

}  // namespace superball::verify::detail::explore
