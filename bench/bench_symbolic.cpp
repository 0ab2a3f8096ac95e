// Time of the symbolic derivation (superball::symbolic): all evolution cases
// of a pattern with their conditions and asymptotic forms, as `superball
// derive --all` computes them, and one case against the straightforward
// GiNaC lsolve of the full unreduced system.  bench/sympy_reference.py does
// the same derivations in SymPy; docs/SYMBOLIC.md has the figures.
#include <benchmark/benchmark.h>

#include <ginac/ginac.h>

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/derivation.hpp"

namespace {

using namespace superball;
using namespace superball::symbolic;

/// 0: the paper's four bodies with the seven α's; k ≥ 1: nearest and next-nearest neighbours on 4 + k bodies.
Pattern pattern_of(int which) {
  return which == 0 ? Pattern::paper({1, 2, 3, 4, 5, 6, 7}) : Pattern::nearest_and_next_nearest(4 + which);
}

/// Every case of the pattern, conditions and asymptotics included (Deriver built inside the loop).
void BM_DeriveAll(benchmark::State& state) {
  const Pattern p = pattern_of(static_cast<int>(state.range(0)));
  const Obstacle o = state.range(1) ? Obstacle::Finite : Obstacle::Infinite;
  std::size_t conditions = 0;
  for (auto _ : state) {
    const Deriver d(p, o);
    const auto all = d.derive_all();
    conditions = 0;
    for (const Derivation& r : all) conditions += r.conditions.size();
    benchmark::DoNotOptimize(conditions);
  }
  state.counters["cases"] = static_cast<double>(std::size_t{1} << (p.bodies - 1));
  state.counters["conditions"] = static_cast<double>(conditions);
}
BENCHMARK(BM_DeriveAll)->Args({0, 0})->Name("derive_all/n4_all_alphas/fixed")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeriveAll)->Args({0, 1})->Name("derive_all/n4_all_alphas/finite")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeriveAll)->Args({1, 0})->Name("derive_all/n5_nnn/fixed")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeriveAll)->Args({1, 1})->Name("derive_all/n5_nnn/finite")->Unit(benchmark::kMillisecond);
// Seconds an iteration: three repetitions, the median reported.
BENCHMARK(BM_DeriveAll)->Args({2, 0})->Name("derive_all/n6_nnn/fixed")->Unit(benchmark::kSecond)->Iterations(1)->Repetitions(3)->ReportAggregatesOnly(true);

/// One case, the paper's §4.1 (case 1 with α₂), everything included.
void BM_DeriveCase1Alpha2(benchmark::State& state) {
  const ContactSet closed = Vocabulary::paper().named_case("1").closed;
  for (auto _ : state) {
    const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
    benchmark::DoNotOptimize(d.derive(closed).conditions.size());
  }
}
BENCHMARK(BM_DeriveCase1Alpha2)->Name("derive/case1_alpha2/fixed")->Unit(benchmark::kMillisecond);

/// Case 3.3 (no contact closed) with the seven α's and a fixed obstacle: the structured derivation…
void BM_DeriveCase33(benchmark::State& state) {
  const ContactSet closed = Vocabulary::paper().named_case("3.3").closed;
  for (auto _ : state) {
    const Deriver d(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Infinite);
    benchmark::DoNotOptimize(d.derive(closed).conditions.size());
  }
}
BENCHMARK(BM_DeriveCase33)->Name("derive/case3.3_all_alphas/fixed")->Unit(benchmark::kMillisecond);

/// …and GiNaC's lsolve on the full unreduced system of the same case (velocities and
/// reactions only, no condition): unknowns W₁..W₄ and λ on the three contacts
/// (W₄ = 0 for the fixed obstacle, m₄ a symbol for the finite one).
void BM_LsolveCase33(benchmark::State& state) {
  const bool finite = state.range(0) != 0;
  const Symbols s(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), finite ? Obstacle::Finite : Obstacle::Infinite);
  const ContactSet closed = Vocabulary::paper().named_case("3.3").closed;
  const int n = s.bodies();
  const std::vector<Pair> pairs = s.pattern().pairs();
  GiNaC::matrix M(static_cast<unsigned>(pairs.size()), static_cast<unsigned>(pairs.size()));
  GiNaC::matrix D(static_cast<unsigned>(pairs.size()), static_cast<unsigned>(n));
  for (unsigned r = 0; r < pairs.size(); ++r) {
    D(r, static_cast<unsigned>(pairs[r].i - 1)) = 1;
    D(r, static_cast<unsigned>(pairs[r].j - 1)) = -1;
    for (unsigned c = 0; c < pairs.size(); ++c) M(r, c) = s.entry(pairs[r], pairs[c]);
  }
  const GiNaC::matrix K = D.transpose().mul(M).mul(D);
  std::vector<GiNaC::symbol> W, L;
  for (int i = 0; i < n; ++i) W.emplace_back("W" + std::to_string(i + 1));
  for (int c = 0; c + 1 < n; ++c) L.emplace_back("L" + std::to_string(c + 1));
  GiNaC::lst eqs, vars;
  auto u = [&](int i) { return i + 1 < n ? GiNaC::ex(-s.fall_speed()) : GiNaC::ex(0); };
  for (int i = 0; i < (finite ? n : n - 1); ++i) {
    GiNaC::ex r = s.mass(i + 1) * (W[static_cast<std::size_t>(i)] - u(i));
    for (int j = 0; j < n; ++j) r += K(static_cast<unsigned>(i), static_cast<unsigned>(j)) * (W[static_cast<std::size_t>(j)] + u(j));
    if (i + 1 < n) r -= L[static_cast<std::size_t>(i)];
    if (i > 0) r += L[static_cast<std::size_t>(i - 1)];
    eqs.append(r == 0);
  }
  if (!finite) eqs.append(W[static_cast<std::size_t>(n - 1)] == 0);
  for (int c = 0; c + 1 < n; ++c)
    eqs.append(closed.closed(c) ? GiNaC::ex(W[static_cast<std::size_t>(c)] == W[static_cast<std::size_t>(c + 1)]) : GiNaC::ex(L[static_cast<std::size_t>(c)] == 0));
  for (const auto& w : W) vars.append(w);
  for (const auto& l : L) vars.append(l);
  for (auto _ : state) {
    const GiNaC::ex sol = GiNaC::lsolve(eqs, vars);
    if (sol.nops() == 0) state.SkipWithError("lsolve returned an empty list: the system is singular");
    benchmark::DoNotOptimize(sol.nops());
  }
}
BENCHMARK(BM_LsolveCase33)->Arg(0)->Name("lsolve_unreduced/case3.3_all_alphas/fixed")->Unit(benchmark::kMillisecond);

/// The finite-obstacle lsolve runs for many minutes: registered only when
/// SUPERBALL_BENCH_SLOW is set in the environment (see docs/SYMBOLIC.md).
const bool slow_registered = [] {
  if (std::getenv("SUPERBALL_BENCH_SLOW"))
    benchmark::RegisterBenchmark("lsolve_unreduced/case3.3_all_alphas/finite", BM_LsolveCase33)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
