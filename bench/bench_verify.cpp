// Time of `superball verify` (superball::verify::verify_case) on the paper's
// case 1 with alpha_2, the default five values of eps, on 1 and 2 threads:
// the run is the same (a function of the seed only), so the ratio is the
// speed-up of the private block loop.  docs/PERFORMANCE.md has the figures.
#include <benchmark/benchmark.h>

#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/verify/verification.hpp"

namespace {

using namespace superball;

/// verify_case with range(0) drawn points per eps on range(1) threads (derivation included).
void BM_VerifyCase1(benchmark::State& state) {
  const symbolic::Deriver deriver(symbolic::Pattern::paper({2}), symbolic::Obstacle::Infinite);
  const ContactSet closed = Vocabulary::paper().named_case("1").closed;
  verify::VerifyOptions options;
  options.samples = static_cast<int>(state.range(0));
  options.threads = static_cast<int>(state.range(1));
  long long points = 0;
  for (auto _ : state) {
    const verify::Verification v = verify::verify_case(deriver, closed, options);
    points = 0;
    for (const verify::EpsilonResult& e : v.epsilons) points += e.all().points;
    benchmark::DoNotOptimize(points);
  }
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_VerifyCase1)->ArgNames({"samples", "threads"})->Args({4000, 1})->Args({4000, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
