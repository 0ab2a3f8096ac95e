#include "superball/numeric/psd_along.hpp"

#include <algorithm>
#include <numeric>
#include <optional>

#include "superball/cases/error.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/scalar.hpp"

namespace superball::numeric {

std::vector<bool> psd_along(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values) {
  const std::size_t n = values.size();
  std::vector<bool> out(n, true);
  if (n == 0) return out;
  // The values in increasing order: the PSD ones are consecutive there.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  auto psd = [&](std::size_t rank) {
    Scene s = scene;
    parameter.assign(s, Number::parse(to_string(values[order[rank]])));
    try {
      return positive_semidefinite(ExactScene::from(s, ExactScene::MCheck::Caller));
    } catch (const InputError&) {
      return true;  // another check fails here: check_range()'s to refuse, with its message
    }
  };
  if (psd(0) && psd(n - 1)) return out;  // both ends PSD: every value between is
  // Sample evenly in increasing order.
  const std::size_t stride = std::max<std::size_t>(1, (n + psd_along_samples - 1) / psd_along_samples);
  std::vector<std::size_t> sampled;
  for (std::size_t r = 0; r < n; r += stride) sampled.push_back(r);
  if (sampled.back() != n - 1) sampled.push_back(n - 1);
  std::vector<char> verdict(sampled.size());
  std::optional<std::size_t> inside;
  for (std::size_t k = 0; k < sampled.size(); ++k)
    if ((verdict[k] = psd(sampled[k])) && !inside) inside = k;
  if (!inside) {  // no sample PSD: a PSD run, if any, lies between two samples; check every value
    for (std::size_t r = 0; r < n; ++r) out[order[r]] = psd(r);
    return out;
  }
  std::size_t first = sampled[*inside], last = first;  // ranks of the PSD run's ends
  std::size_t k = *inside;
  while (k + 1 < sampled.size() && verdict[k + 1]) ++k;
  last = sampled[k];
  // Bisect each edge between a PSD rank and a non-PSD one (the predicate is monotone on each side).
  if (*inside > 0) {
    std::size_t bad = sampled[*inside - 1], good = first;
    while (good - bad > 1) {
      const std::size_t mid = bad + (good - bad) / 2;
      (psd(mid) ? good : bad) = mid;
    }
    first = good;
  }
  if (k + 1 < sampled.size()) {
    std::size_t good = last, bad = sampled[k + 1];
    while (bad - good > 1) {
      const std::size_t mid = good + (bad - good) / 2;
      (psd(mid) ? good : bad) = mid;
    }
    last = good;
  }
  for (std::size_t r = 0; r < n; ++r) out[order[r]] = r >= first && r <= last;
  return out;
}

}  // namespace superball::numeric
