// explore_case() (explore.hpp): the multi-start search, its exact
// confirmation, and the clash proofs when no witness is found.  The search's
// box and objective are in explore_search.hpp, its optimiser in
// nelder_mead.cpp, the proofs in clash.cpp (with the simplex phase one of
// simplex.cpp); the reports of a result in present/explore.hpp.
#include "superball/verify/explore.hpp"

#include <cln/rational_io.h>
#include <ginac/ginac.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "clash.hpp"
#include "explore_search.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/verify/space.hpp"

namespace superball::verify {
namespace detail::explore {
namespace {

using namespace superball::symbolic;

/// ε of the regime points used as starts (m₁ ~ ε, K₁₄ ~ 1/ε).
constexpr int regime_inverse_epsilon = 100;
/// Feasible local results tried by the exact confirmation, best first.
constexpr int confirmations = 6;

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("explore_case(): " + what); }

/// The sum of the absolute values of the terms of \p p.
GiNaC::ex absolute_terms(const GiNaC::ex& p, const Symbols& s) {
  GiNaC::ex out = 0;
  for (const Monomial& m : s.monomials(p)) {
    GiNaC::ex t = GiNaC::abs(m.coefficient);
    for (const auto& [k, e] : m.powers) t *= GiNaC::pow(s.all()[static_cast<std::size_t>(k)].symbol, e);
    out += t;
  }
  return out;
}

/// The couplings of \p sy in \p style, ", "-separated (text) or ","-separated (ASCII).
std::string couplings_text(const Symbols& sy, Style style) {
  std::string s;
  for (const SymbolInfo& i : sy.all())
    if (i.kind == SymbolKind::Coupling) s += (s.empty() ? "" : style == Style::Ascii ? "," : ", ") + i.name(style);
  return s.empty() ? (style == Style::Ascii ? "none" : "no coupling") : s;
}

}  // namespace
}  // namespace detail::explore

std::string describe_box(const ExploreOptions& o) {
  return "every mass and K in [" + numeric::to_string(o.box_low, 6) + ", " + numeric::to_string(o.box_high, 6) +
         "] (log scale), each coupling t·√(K_p K_q) with t in [-1, 1], a = 1, bottom body fixed";
}

const char* to_string(Reach r) {
  switch (r) {
    case Reach::Yes: return "yes";
    case Reach::Impossible: return "no (proved)";
    case Reach::CaseImpossible: return "case impossible";
    case Reach::NotFound: break;
  }
  return "not found";
}

ExploreResult explore_case(const symbolic::Deriver& deriver, const ContactSet& closed, const ExploreOptions& o) {
  using namespace superball::symbolic;
  using cln::cl_RA;
  if (deriver.symbols().obstacle() != Obstacle::Infinite) detail::explore::fail("the search needs a fixed obstacle (m_n = infinity)");
  if (closed.bodies() != deriver.symbols().bodies()) detail::explore::fail("the case is for " + std::to_string(closed.bodies()) + " bodies");
  o.check();
  const Symbols& sy = deriver.symbols();
  const Derivation d = deriver.derive(closed);
  const ParameterSpace space(deriver);
  ExploreResult out;
  out.pattern = detail::explore::couplings_text(sy, Style::Text);
  out.pattern_ascii = detail::explore::couplings_text(sy, Style::Ascii);
  out.case_name = d.case_name;
  out.closed = closed;
  out.box = describe_box(o);
  out.seed = o.seed;

  // The feasible set: the case's evolution and contact conditions and M ⪰ 0.
  std::vector<detail::explore::Constraint> constraints;
  for (const Condition& c : d.conditions)
    if (c.kind != ConditionKind::Superball)
      constraints.push_back({CompiledCondition(c, c.exact, sy), Polynomial(detail::explore::absolute_terms(c.exact.numerator, sy), sy)});
  const Fraction& u1 = d.velocities.front();
  const Polynomial u1_numerator(u1.numerator, sy), u1_denominator(u1.denominator, sy);
  const detail::explore::Box box(space, o);
  detail::explore::Objective f{box, constraints, u1_numerator, u1_denominator};

  // Progress (ExploreOptions::progress): the local searches' evaluations, then one step for the rest.
  const long long planned = static_cast<long long>(o.starts) * o.evaluations + 1;
  long long searched = 0;  // the steps of the local searches ended, each at its full budget
  int search_start = 0;    // f.evaluations when the current local search started
  auto report = [&](long long done) {
    if (o.progress) o.progress(std::min(done, planned - 1), planned);
  };
  f.poll = [&] { report(searched + std::min(f.evaluations - search_start, o.evaluations)); };

  // Multi-start local search.
  RegimeSampler sampler(space, cl_RA(1) / detail::explore::regime_inverse_epsilon, o.seed);
  std::mt19937_64 rng(o.seed);
  std::vector<std::pair<std::vector<double>, double>> ends;
  for (int s = 0; s < o.starts; ++s) {
    std::vector<double> y(static_cast<std::size_t>(box.size()));
    std::optional<Point> regime;
    if (s % 2 == 0) regime = sampler.draw();
    if (regime) {
      y = box.coordinates_of(*regime);
    } else {
      for (int v = 0; v < box.size(); ++v) y[static_cast<std::size_t>(v)] = std::uniform_real_distribution<double>(box.lower(v), box.upper(v))(rng);
    }
    search_start = f.evaluations;
    ends.push_back(detail::explore::nelder_mead(f, box, y, o.evaluations));
    searched += o.evaluations;
    report(searched);
    ++out.stats.starts;
    if (ends.back().second < detail::explore::infeasible_floor) {
      ++out.stats.feasible_starts;
      const double r = f.ratio(box.point(ends.back().first));
      out.stats.best_double = std::max(out.stats.best_double, r);
      if (r > 1) ++out.stats.superball_starts;
    }
  }
  std::stable_sort(ends.begin(), ends.end(), [](const auto& a, const auto& b) { return a.second < b.second; });

  // Exact confirmation of the best feasible ends, stepping inward when the rounded point fails.
  numeric::CollisionSolver<cl_RA> solver;
  int tried = 0;
  for (const auto& [y0, value] : ends) {
    if (value >= detail::explore::infeasible_floor || tried++ >= detail::explore::confirmations || !out.witness.empty()) break;
    const bool wants_superball = f.ratio(box.point(y0)) > 1;
    std::vector<double> y = y0;
    for (double margin : detail::explore::margins) {
      if (margin > detail::explore::margins[0]) {
        ++out.stats.inward_steps;
        detail::explore::Objective inward{box, constraints, u1_numerator, u1_denominator, margin};
        inward.poll = [&] { report(searched); };
        y = detail::explore::nelder_mead(inward, box, y, o.evaluations / 2).first;
        f.evaluations += inward.evaluations;
      }
      const std::optional<Point> x = box.exact(y);
      if (!x) continue;
      const numeric::Problem<cl_RA> problem = space.problem(*x);
      numeric::Solution<cl_RA> sol;
      solver.compute(problem, sol);
      ++out.stats.exact_solves;
      const cl_RA a = -problem.u.front();
      if (sol.status != numeric::Status::Success || sol.closed != closed) continue;
      if (wants_superball && !(sol.velocities_after[0] > a)) continue;
      out.witness = space.named(*x);
      out.scene = space.scene(*x, "explore: " + out.pattern + ", case " + out.case_name);
      out.u1 = sol.velocities_after[0];
      out.ratio = out.u1 / a;
      break;
    }
  }
  out.stats.evaluations = f.evaluations;
  report(searched);
  if (!out.witness.empty() && out.ratio > 1) {
    out.reach = Reach::Yes;
  } else {
    out.clash = detail::explore::find_clash(d, sy, false);
    report(searched);
    out.asymptotic_clash = detail::explore::find_clash(d, sy, true);
    if (out.clash) out.reach = out.clash->superball ? Reach::Impossible : Reach::CaseImpossible;
  }
  if (o.progress) o.progress(planned, planned);
  return out;
}

std::vector<std::vector<int>> table_patterns() { return {{1}, {2}, {3}, {4}, {5}, {6}, {7}, {1, 6}}; }

PatternTable explore_all_patterns(const ExploreOptions& options) {
  options.check();
  PatternTable t;
  t.options = options;
  t.options.progress = nullptr;  // the caller's, not the table's
  t.patterns = table_patterns();
  for (const NamedCase& c : Vocabulary::paper().cases()) t.cases.push_back(c.name);
  // Each cell's progress as a part of the table's: every cell plans the same steps.
  const long long cells = static_cast<long long>(t.patterns.size() * t.cases.size());
  long long cell = 0;
  ExploreOptions each = options;
  if (options.progress)
    each.progress = [&](long long done, long long planned) { options.progress(cell * planned + done, cells * planned); };
  for (const std::vector<int>& alphas : t.patterns) {
    const symbolic::Deriver deriver(symbolic::Pattern::paper(alphas), symbolic::Obstacle::Infinite);
    std::vector<ExploreResult> row;
    for (const NamedCase& c : Vocabulary::paper().cases()) {
      row.push_back(explore_case(deriver, c.closed, each));
      ++cell;
    }
    t.cells.push_back(std::move(row));
  }
  return t;
}

}  // namespace superball::verify
