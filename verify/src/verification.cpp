#include "superball/verify/verification.hpp"

#include <cln/integer.h>
#include <cln/rational_io.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <exception>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/memory.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/symbolic/format.hpp"
#include "superball/verify/space.hpp"

namespace superball::verify {
namespace detail {
namespace {

using cln::cl_RA;

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("verify_case(): " + what); }

/// SplitMix64: the seed of a block from the run's seed, the ε index and the block index.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
std::uint64_t block_seed(std::uint64_t seed, std::size_t epsilon, std::size_t block) {
  return mix(mix(seed) ^ mix((static_cast<std::uint64_t>(epsilon) << 40) + block));
}

/// Everything a worker thread touches: its own copies, sharing no CLN object.
struct Context {
  ParameterSpace space;
  std::vector<CompiledCondition> exact, asymptotic;
  std::vector<cl_RA> epsilons;
  ContactSet closed;
  std::string title;
  numeric::CollisionSolver<cl_RA> solver{};
  numeric::Solution<cl_RA> actual{}, forced{};
};

/// What one block of work found, merged in block order.
struct BlockResult {
  std::size_t epsilon = 0;
  Tally tally;
  std::vector<Disagreement> disagreements;
  std::vector<Point> points;              ///< bulk: the points drawn
  std::vector<std::vector<bool>> sides;   ///< bulk: per point, per condition, whether the exact form holds
  std::vector<Point> disagreement_points; ///< the point of each disagreement (to send it as text)
};

const char* yes(bool b) { return b ? "holds" : "fails"; }

/// The role of a point in evaluate(): drawn, found by reach(), or (>= 0) an
/// end of a bracket of that condition.
constexpr int drawn_point = -1, found_point = -2;

/// Solve the point \p x both ways and compare; \p near: its role.
void evaluate(Context& ctx, const std::vector<VerifiedCondition>& names, const Point& x, int near, BlockResult& out) {
  Tally& t = out.tally;
  ++t.points;
  t.found += near == found_point;
  const numeric::Problem<cl_RA> problem = ctx.space.problem(x);
  ctx.solver.compute(problem, ctx.actual);
  ctx.solver.compute_case(problem, ctx.closed, ctx.forced);
  if (ctx.actual.status != numeric::Status::Success || ctx.forced.status != numeric::Status::Success) {
    ++t.unsolved;
    return;
  }
  const cl_RA a = -problem.u.front();
  const bool truth = ctx.actual.closed == ctx.closed && ctx.actual.velocities_after[0] > a;
  bool exact = true, asymptotic = true, exact_form = false;
  std::vector<std::string> details;
  std::vector<bool> sides;
  for (std::size_t c = 0; c < ctx.exact.size(); ++c) {
    std::string quantity;
    const bool truth_c = condition_truth(ctx.exact[c].kind, ctx.exact[c].about, problem, ctx.forced, &quantity);
    const bool e = ctx.exact[c].holds(x), s = ctx.asymptotic[c].holds(x);
    exact = exact && e;
    asymptotic = asymptotic && s;
    sides.push_back(e);
    ConditionTally& ct = t.conditions[c];
    (truth_c ? ct.holds : ct.fails) += 1;
    if (near == static_cast<int>(c)) {
      (truth_c ? ct.near_holds : ct.near_fails) += 1;
      ct.near_asymptotic_agree += s == truth_c;
    }
    ct.exact_agree += e == truth_c;
    exact_form = exact_form || e != truth_c;
    ct.asymptotic_agree += s == truth_c;
    for (const auto& [form, holds] : {std::pair<const char*, bool>{"exact", e}, {"asymptotic", s}})
      if (holds != truth_c)
        details.push_back(std::string(form) + " form of " + names[c].name() + " " + yes(holds) + "; the exact solution of the case: " +
                          quantity + " (" + yes(truth_c) + ")");
  }
  auto count = [truth](Confusion& m, bool holds) {
    (holds ? (truth ? m.holds_true : m.holds_false) : (truth ? m.fails_true : m.fails_false)) += 1;
  };
  count(t.exact, exact);
  count(t.asymptotic, asymptotic);
  if (near == drawn_point) {
    out.points.push_back(x);
    out.sides.push_back(std::move(sides));
  }
  if (exact == truth && asymptotic == truth && details.empty()) return;
  Disagreement d;
  d.epsilon_index = static_cast<int>(out.epsilon);
  d.near = near >= 0;
  d.point = ctx.space.named(x);
  d.scene = ctx.space.scene(x, ctx.title + " at eps = " + epsilon_name(ctx.epsilons[out.epsilon]));
  d.actual_case = Vocabulary::paper().case_name(ctx.actual.closed);
  d.quantity = "U1 - a = " + to_string(ctx.actual.velocities_after[0] - a);
  d.truth = truth;
  d.exact = exact;
  d.asymptotic = asymptotic;
  d.exact_form = exact_form || exact != truth;
  d.details = std::move(details);
  out.disagreements.push_back(std::move(d));
  out.disagreement_points.push_back(x);
}

/// Whether \p c is exactly on its boundary at \p x (numerator or denominator zero).
bool on_boundary(const CompiledCondition& c, const Point& x) {
  return c.numerator.sign(x) == 0 || (!c.denominator.is_zero() && c.denominator.sign(x) == 0);
}

/// Bisect the segment from \p hold (the exact form of condition \p c holds)
/// to \p fails (it fails) down to a bracket of 2^-boundary_bracket_bits of
/// it, and evaluate both ends.  A split point exactly on the boundary is
/// moved (1/3, 1/4, … of the bracket) so both ends are strictly on a side.
void bisect(Context& ctx, const std::vector<VerifiedCondition>& names, const Point& hold, const Point& fails, int c, BlockResult& out) {
  constexpr int max_split = 16;
  const CompiledCondition& cond = ctx.exact[static_cast<std::size_t>(c)];
  const cl_RA width = cl_RA(1) / cln::expt(cl_RA(2), boundary_bracket_bits);
  Point direction(hold.size());
  for (std::size_t k = 0; k < hold.size(); ++k) direction[k] = fails[k] - hold[k];
  auto at = [&](const cl_RA& t) {
    Point x(hold.size());
    for (std::size_t k = 0; k < hold.size(); ++k) x[k] = hold[k] + t * direction[k];
    return x;
  };
  cl_RA lo = 0, hi = 1;
  while (hi - lo > width) {
    std::optional<bool> side;
    cl_RA t;
    for (int j = 2; j <= max_split && !side; ++j) {
      t = lo + (hi - lo) / j;
      const Point x = at(t);
      if (!ctx.space.admissible(x)) return;  // cannot happen: the admissible set is convex
      if (!on_boundary(cond, x)) side = cond.holds(x);
    }
    if (!side) return;
    (*side ? lo : hi) = t;
  }
  evaluate(ctx, names, at(lo), c, out);
  evaluate(ctx, names, at(hi), c, out);
}

/// How far \p c is toward the side \p holds at \p x: its value in double,
/// with the sign of that side (-inf where the denominator vanishes).
double toward(const CompiledCondition& c, const Point& x, bool holds) {
  std::vector<double> d;
  for (const cl_RA& v : x) d.push_back(cln::double_approx(v));
  const double f = c.value(d);
  return std::isnan(f) ? -std::numeric_limits<double>::infinity() : (holds ? f : -f);
}

/// From \p start, look for an admissible point of the regime where the exact
/// form of condition \p c is on the side \p want_holds: up to reach_steps
/// random moves of one or two coordinates to values drawn in the regime at
/// the same ε, each kept when the point stays admissible and moves toward
/// that side (toward() increases).
std::optional<Point> reach(Context& ctx, const Point& start, int c, bool want_holds, std::size_t e, std::uint64_t seed) {
  const CompiledCondition& cond = ctx.exact[static_cast<std::size_t>(c)];
  RegimeSampler sampler(ctx.space, ctx.epsilons[e], seed);
  std::mt19937_64 rng(mix(seed));
  std::uniform_int_distribution<int> coordinate(0, ctx.space.size() - 1);
  Point x = start;
  double fx = toward(cond, x, want_holds);
  for (int step = 0; step < reach_steps; ++step) {
    const std::optional<Point> y = sampler.draw();
    if (!y) return std::nullopt;
    Point z = x;
    for (int m = 0; m <= step % 2; ++m) {
      const auto k = static_cast<std::size_t>(coordinate(rng));
      z[k] = (*y)[k];
    }
    if (!ctx.space.admissible(z)) continue;
    const double fz = toward(cond, z, want_holds);
    if (!(fz > fx)) continue;
    x = std::move(z);
    fx = fz;
    if (!on_boundary(cond, x) && cond.holds(x) == want_holds) return x;
  }
  return std::nullopt;
}

void merge(ConditionTally& a, const ConditionTally& b) {
  a.holds += b.holds;
  a.fails += b.fails;
  a.near_holds += b.near_holds;
  a.near_fails += b.near_fails;
  a.exact_agree += b.exact_agree;
  a.asymptotic_agree += b.asymptotic_agree;
  a.near_asymptotic_agree += b.near_asymptotic_agree;
}

void merge(Tally& into, const Tally& from) {
  into.points += from.points;
  into.found += from.found;
  into.undrawn += from.undrawn;
  into.unsolved += from.unsolved;
  for (auto [m, n] : {std::pair{&into.exact, &from.exact}, {&into.asymptotic, &from.asymptotic}}) {
    m->holds_true += n->holds_true;
    m->holds_false += n->holds_false;
    m->fails_true += n->fails_true;
    m->fails_false += n->fails_false;
  }
  for (std::size_t c = 0; c < into.conditions.size(); ++c) merge(into.conditions[c], from.conditions[c]);
}

/// Block results as plain text, for VerifyOptions::runner: numbers as
/// decimal words, strings and exact values (p/q) with their length first.
class Writer {
 public:
  void number(long long n) { text_ += std::to_string(n) + ' '; }
  void string(const std::string& s) {
    number(static_cast<long long>(s.size()));
    text_ += s;
  }
  void point(const Point& x) {
    number(static_cast<long long>(x.size()));
    for (const cl_RA& v : x) string(to_string(v));
  }
  void tally(const Tally& t) {
    for (long long n : {t.points, t.found, t.undrawn, t.unsolved}) number(n);
    for (const Confusion* m : {&t.exact, &t.asymptotic})
      for (long long n : {m->holds_true, m->holds_false, m->fails_true, m->fails_false}) number(n);
    number(static_cast<long long>(t.conditions.size()));
    for (const ConditionTally& c : t.conditions)
      for (long long n : {c.holds, c.fails, c.near_holds, c.near_fails, c.exact_agree, c.asymptotic_agree, c.near_asymptotic_agree}) number(n);
  }
  void block(const BlockResult& r) {
    number(static_cast<long long>(r.epsilon));
    tally(r.tally);
    number(static_cast<long long>(r.points.size()));
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      point(r.points[i]);
      std::string sides;
      for (bool b : r.sides[i]) sides += b ? '1' : '0';
      string(sides);
    }
    number(static_cast<long long>(r.disagreements.size()));
    for (std::size_t i = 0; i < r.disagreements.size(); ++i) {
      const Disagreement& d = r.disagreements[i];
      for (bool b : {d.near, d.truth, d.exact, d.asymptotic, d.exact_form}) number(b);
      point(r.disagreement_points[i]);
      string(d.actual_case);
      string(d.quantity);
      number(static_cast<long long>(d.details.size()));
      for (const std::string& line : d.details) string(line);
    }
  }
  std::string& text() { return text_; }

 private:
  std::string text_;
};

[[noreturn]] void damaged(const std::string& what) { throw std::logic_error("verify_case(): a damaged block result (" + what + ")"); }

/// Reads what Writer wrote; \p space and \p title remake each
/// disagreement's named point and scene from its point, as evaluate() does.
class Reader {
 public:
  Reader(const std::string& text, const ParameterSpace& space, const std::string& title, const std::vector<cl_RA>& epsilons)
      : text_(text), space_(space), title_(title), epsilons_(epsilons) {}
  bool done() const { return at_ == text_.size(); }
  long long number() {
    const std::size_t space = text_.find(' ', at_);
    if (space == std::string::npos) damaged("a number is missing");
    const long long n = std::stoll(text_.substr(at_, space - at_));
    at_ = space + 1;
    return n;
  }
  std::string string() {
    const std::size_t size = static_cast<std::size_t>(number());
    if (size > text_.size() - at_) damaged("a text is cut short");
    at_ += size;
    return text_.substr(at_ - size, size);
  }
  Point point() {
    Point x(static_cast<std::size_t>(number()));
    for (cl_RA& v : x) v = cl_RA(string().c_str());
    return x;
  }
  void tally(Tally& t) {
    for (long long* n : {&t.points, &t.found, &t.undrawn, &t.unsolved}) *n = number();
    for (Confusion* m : {&t.exact, &t.asymptotic})
      for (long long* n : {&m->holds_true, &m->holds_false, &m->fails_true, &m->fails_false}) *n = number();
    t.conditions.resize(static_cast<std::size_t>(number()));
    for (ConditionTally& c : t.conditions)
      for (long long* n : {&c.holds, &c.fails, &c.near_holds, &c.near_fails, &c.exact_agree, &c.asymptotic_agree, &c.near_asymptotic_agree}) *n = number();
  }
  BlockResult block() {
    BlockResult r;
    r.epsilon = static_cast<std::size_t>(number());
    if (r.epsilon >= epsilons_.size()) damaged("no such epsilon");
    tally(r.tally);
    r.points.resize(static_cast<std::size_t>(number()));
    for (Point& x : r.points) {
      x = point();
      std::vector<bool> sides;
      for (char c : string()) sides.push_back(c == '1');
      r.sides.push_back(std::move(sides));
    }
    const std::size_t n = static_cast<std::size_t>(number());
    for (std::size_t i = 0; i < n; ++i) {
      Disagreement d;
      d.epsilon_index = static_cast<int>(r.epsilon);
      for (bool* b : {&d.near, &d.truth, &d.exact, &d.asymptotic, &d.exact_form}) *b = number() != 0;
      const Point x = point();
      d.point = space_.named(x);
      d.scene = space_.scene(x, title_ + " at eps = " + epsilon_name(epsilons_[r.epsilon]));
      d.actual_case = string();
      d.quantity = string();
      d.details.resize(static_cast<std::size_t>(number()));
      for (std::string& line : d.details) line = string();
      r.disagreements.push_back(std::move(d));
      r.disagreement_points.push_back(x);
    }
    return r;
  }

 private:
  const std::string& text_;
  std::size_t at_ = 0;
  const ParameterSpace& space_;
  const std::string& title_;
  const std::vector<cl_RA>& epsilons_;
};

/// The state of each of \p threads worker threads: its own clones of the
/// space, the compiled conditions and the values of ε, sharing no CLN object.
std::vector<Context> contexts(int threads, const ParameterSpace& space, const std::vector<CompiledCondition>& exact,
                              const std::vector<CompiledCondition>& asymptotic, const std::vector<cl_RA>& epsilons, const ContactSet& closed,
                              const std::string& title) {
  std::vector<Context> out;
  for (int t = 0; t < threads; ++t) {
    Context ctx{space.clone(), {}, {}, {}, closed, title};
    for (std::size_t c = 0; c < exact.size(); ++c) {
      ctx.exact.push_back(exact[c].clone());
      ctx.asymptotic.push_back(asymptotic[c].clone());
    }
    for (const cl_RA& e : epsilons) ctx.epsilons.push_back(deep_copy(e));
    out.push_back(std::move(ctx));
  }
  return out;
}

/// One block of the boundary stage: an ε and a condition.
struct Work {
  std::size_t epsilon;
  int condition;
  std::vector<std::pair<Point, Point>> pairs;  ///< (holds, fails)
  std::vector<Point> starts;                   ///< points to search from, best first
  bool want_holds = false;                     ///< the side searched for
};

/// The boundary stage's blocks, one per ε and condition: pair the drawn
/// points of \p bulk (\p per_eps blocks per ε) where the \p exact form holds
/// with those where it fails (in run order), to bisect between them; when a
/// side has fewer than \p boundary_pairs points, search for more of it from
/// the other side's points nearest to it.
std::vector<Work> boundary_work(const std::vector<BlockResult>& bulk, std::size_t n_eps, std::size_t per_eps,
                                const std::vector<CompiledCondition>& exact, int boundary_pairs) {
  std::vector<Work> work;
  for (std::size_t e = 0; e < n_eps; ++e) {
    for (std::size_t c = 0; c < exact.size(); ++c) {
      Work w{e, static_cast<int>(c), {}, {}, false};
      std::vector<const Point*> hold, fails;
      for (std::size_t b = e * per_eps; b < (e + 1) * per_eps; ++b)
        for (std::size_t i = 0; i < bulk[b].points.size(); ++i)
          if (!on_boundary(exact[c], bulk[b].points[i]))  // a segment's ends are strictly on a side
            (bulk[b].sides[i][c] ? hold : fails).push_back(&bulk[b].points[i]);
      const std::size_t wanted = static_cast<std::size_t>(boundary_pairs);
      const std::size_t n = std::min({wanted, hold.size(), fails.size()});
      for (std::size_t i = 0; i < n; ++i) w.pairs.emplace_back(deep_copy(*hold[i]), deep_copy(*fails[i]));
      if (n < wanted && (hold.size() < wanted || fails.size() < wanted)) {
        w.want_holds = hold.size() < fails.size();
        std::vector<std::pair<double, const Point*>> from;
        for (const Point* x : w.want_holds ? fails : hold) from.emplace_back(-toward(exact[c], *x, w.want_holds), x);
        std::stable_sort(from.begin(), from.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (std::size_t i = 0; i < from.size() && i < wanted - n; ++i) w.starts.push_back(deep_copy(*from[i].second));
      }
      work.push_back(std::move(w));
    }
  }
  return work;
}

/// The blocks' results into \p v in run order: per ε, the bulk blocks then the boundary blocks.
void merge_stages(Verification& v, const std::vector<BlockResult>& bulk, const std::vector<BlockResult>& boundary, std::size_t per_eps) {
  for (std::size_t e = 0; e < v.epsilons.size(); ++e) {
    for (std::size_t b = e * per_eps; b < (e + 1) * per_eps; ++b) {
      merge(v.epsilons[e].drawn, bulk[b].tally);
      v.disagreements.insert(v.disagreements.end(), bulk[b].disagreements.begin(), bulk[b].disagreements.end());
    }
    for (const BlockResult& r : boundary) {
      if (r.epsilon != e) continue;
      merge(v.epsilons[e].boundary, r.tally);
      v.disagreements.insert(v.disagreements.end(), r.disagreements.begin(), r.disagreements.end());
    }
  }
}

}  // namespace
}  // namespace detail

std::string epsilon_name(const cln::cl_RA& epsilon) {
  if (cln::numerator(epsilon) == 1) {
    cln::cl_I d = cln::denominator(epsilon);
    int k = 0;
    while (k < 100 && cln::zerop(cln::mod(d, 10)) && d > 1) {
      d = cln::exquo(d, 10);
      ++k;
    }
    if (d == 1 && k > 0) return "1e-" + std::to_string(k);
  }
  return to_string(epsilon);
}

Tally EpsilonResult::all() const {
  Tally t = drawn;
  detail::merge(t, boundary);
  return t;
}

ConditionTally Verification::condition_total(std::size_t c) const {
  ConditionTally all;
  for (const EpsilonResult& e : epsilons) {
    detail::merge(all, e.drawn.conditions[c]);
    detail::merge(all, e.boundary.conditions[c]);
  }
  return all;
}

bool Verification::exact_agrees() const {
  for (const EpsilonResult& e : epsilons) {
    const Tally t = e.all();
    if (t.exact.agree() != t.exact.total()) return false;
    for (const ConditionTally& c : t.conditions)
      if (c.exact_agree != c.points()) return false;
  }
  return true;
}

Verification verify_case(const symbolic::Deriver& deriver, const ContactSet& closed, const VerifyOptions& options) {
  using detail::BlockResult;
  using detail::Context;
  using cln::cl_RA;
  options.check();
  const int threads = numeric::thread_count(options.threads);

  // Everything symbolic, in this thread.
  const symbolic::Symbols& sy = deriver.symbols();
  const symbolic::Derivation d = deriver.derive(closed);
  Verification v;
  v.case_name = d.case_name;
  v.pattern = sy.pattern().describe();
  v.obstacle = sy.obstacle() == symbolic::Obstacle::Infinite ? "infinite" : "finite";
  v.scaling = deriver.scaling().describe(sy, symbolic::Style::Text);
  v.samples = options.samples;
  v.boundary_pairs = options.boundary_pairs;
  v.seed = options.seed;
  ParameterSpace space = [&] {
    try {
      return ParameterSpace(deriver);
    } catch (const std::invalid_argument& e) {
      detail::fail(without_function_prefix(e.what()));
    }
  }();
  for (const cl_RA& e : options.epsilons) {  // every eps samplable, before any work
    try {
      const RegimeSampler sampler(space, e, options.seed);
    } catch (const std::invalid_argument& x) {
      detail::fail(without_function_prefix(x.what()));
    }
  }
  // Stage 2 pairs the points drawn at each eps, so every drawn point is held until then: estimated
  // before any work, and refused in one line when it would not fit.
  const double drawn = static_cast<double>(options.epsilons.size()) * options.samples, per_point = verify_point_bytes(space.size());
  numeric::check_memory("verify_case()",
                        "drawing " + std::to_string(options.samples) + " points at each of " + std::to_string(options.epsilons.size()) + " values of epsilon",
                        drawn * per_point, numeric::bytes_text(per_point) + " per point", numeric::available_memory(), "draw fewer points (--samples)");
  std::vector<CompiledCondition> exact, asymptotic;
  for (const symbolic::Condition& c : d.conditions) {
    if (c.kind == symbolic::ConditionKind::Psd) continue;
    const symbolic::ConditionForm& form = c.finite ? *c.finite : c.exact;
    v.conditions.push_back({c.kind, c.about, symbolic::format_condition(form, c.relation, sy, symbolic::Style::Text),
                            symbolic::format_condition(c.asymptotic, c.relation, sy, symbolic::Style::Text), c.asymptotic.verdict});
    exact.emplace_back(c, form, sy);
    asymptotic.emplace_back(c, c.asymptotic, sy);
  }
  const std::string title = "superball verify: case " + d.case_name + ", " + v.pattern;
  std::vector<Context> contexts = detail::contexts(threads, space, exact, asymptotic, options.epsilons, closed, title);
  const std::size_t n_eps = options.epsilons.size(), n_cond = exact.size();
  auto fresh = [&](std::size_t e) {
    BlockResult r;
    r.epsilon = e;
    r.tally.conditions.resize(n_cond);
    return r;
  };
  for (const cl_RA& e : options.epsilons) {
    EpsilonResult r;
    r.epsilon = e;
    r.drawn.conditions.resize(n_cond);
    r.boundary.conditions.resize(n_cond);
    v.epsilons.push_back(std::move(r));
  }

  // Progress, reported under a lock by whichever worker finishes a block.
  std::mutex progress_lock;
  long long done = 0;
  const long long planned = static_cast<long long>(n_eps) * (options.samples + 2LL * options.boundary_pairs * static_cast<long long>(n_cond));
  auto report = [&](long long points) {
    if (!options.progress) return;
    std::lock_guard<std::mutex> lock(progress_lock);
    done += points;
    options.progress(std::min(done, planned), planned);
  };

  // Stage 1: the bulk, blocks of verify_block_points per ε.
  const std::size_t per_eps = static_cast<std::size_t>((options.samples + verify_block_points - 1) / verify_block_points);
  // Each worker thread takes one of the contexts cloned above (its state in numeric::parallel_map).
  std::atomic<std::size_t> taken{0};
  auto context = [&] { return &contexts.at(taken++); };
  // A stage: its blocks here on the threads, or, with options.runner, in
  // tasks of \p group blocks run wherever the runner runs them, each sent
  // back as text.
  auto stage = [&](std::size_t blocks, std::size_t group, const std::function<BlockResult(Context&, std::size_t)>& block) {
    auto on_threads = [&](std::size_t first, std::size_t size) {
      taken = 0;
      return numeric::parallel_map(size, threads, context, [&](Context* worker, std::size_t i) { return block(*worker, first + i); });
    };
    std::vector<BlockResult> all = numeric::in_tasks<BlockResult>(
        options.runner, blocks, group, "verify_case()", on_threads,
        [](const std::vector<BlockResult>& results) {
          detail::Writer out;
          for (const BlockResult& r : results) out.block(r);
          return std::move(out.text());
        },
        [&](const std::string& text) {
          std::vector<BlockResult> some;
          for (detail::Reader in(text, space, title, options.epsilons); !in.done();) some.push_back(in.block());
          return some;
        });
    if (all.size() != blocks) throw std::logic_error("verify_case(): the runner's results hold " + std::to_string(all.size()) + " of " + std::to_string(blocks) + " blocks");
    return all;
  };
  const auto bulk = stage(n_eps * per_eps, verify_task_blocks, [&](Context& ctx, std::size_t block) {
    const std::size_t e = block / per_eps, k = block % per_eps;
    BlockResult r = fresh(e);
    const int count = std::min<int>(verify_block_points, options.samples - static_cast<int>(k) * verify_block_points);
    RegimeSampler sampler(ctx.space, ctx.epsilons[e], detail::block_seed(options.seed, e, k));
    for (int i = 0; i < count; ++i) {
      const std::optional<Point> x = sampler.draw();
      if (x)
        detail::evaluate(ctx, v.conditions, *x, detail::drawn_point, r);
      else
        ++r.tally.undrawn;
    }
    report(count);
    return r;
  });

  // Stage 2, one block per ε and condition (detail::boundary_work()).
  const std::vector<detail::Work> work = detail::boundary_work(bulk, n_eps, per_eps, exact, options.boundary_pairs);
  const auto boundary = stage(work.size(), 1, [&](Context& ctx, std::size_t block) {
    const detail::Work& w = work[block];
    BlockResult r = fresh(w.epsilon);
    for (const auto& [hold, fails] : w.pairs) detail::bisect(ctx, v.conditions, hold, fails, w.condition, r);
    for (std::size_t i = 0; i < w.starts.size(); ++i) {
      const std::optional<Point> found =
          detail::reach(ctx, w.starts[i], w.condition, w.want_holds, w.epsilon, detail::block_seed(options.seed, w.epsilon, (block << 20) + i));
      if (!found) break;  // the side is out of reach (or empty): do not spend the budget again
      detail::evaluate(ctx, v.conditions, *found, detail::found_point, r);
      detail::bisect(ctx, v.conditions, w.want_holds ? *found : w.starts[i], w.want_holds ? w.starts[i] : *found, w.condition, r);
    }
    report(2 * static_cast<long long>(w.pairs.size() + w.starts.size()));
    return r;
  });
  if (options.progress) options.progress(planned, planned);

  detail::merge_stages(v, bulk, boundary, per_eps);
  return v;
}

}  // namespace superball::verify
