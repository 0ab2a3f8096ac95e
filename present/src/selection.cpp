#include "superball/present/selection.hpp"

#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"

namespace superball::present {

using namespace superball::symbolic;

std::vector<int> parse_alphas(const std::string& text) {
  const int count = static_cast<int>(Vocabulary::paper().alphas().size());
  std::vector<int> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const bool digits = !item.empty() && item.size() < 4 && item.find_first_not_of("0123456789") == std::string::npos;
    const int k = digits ? std::stoi(item) : 0;
    if (k < 1 || k > count)
      throw std::invalid_argument("parse_alphas(): alphas: '" + text + "': " + (item.empty() ? std::string("an empty item") : "'" + item + "'") +
                                  " is not an index 1.." + std::to_string(count) + " (e.g. 1,6)");
    out.push_back(k);
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

void require_case(const SelectionOptions& o, bool or_all_patterns) {
  if (o.case_name.empty() && o.closed.empty() && !o.all)
    throw std::invalid_argument(std::string("require_case(): give a case: case, closed or all") + (or_all_patterns ? ", or all_patterns" : ""));
}

void check_all_patterns(const SelectionOptions& o) {
  if (!o.case_name.empty() || !o.closed.empty() || o.all || !o.alphas.empty() || !o.coupling.empty() || !o.scene.empty())
    throw std::invalid_argument("check_all_patterns(): all_patterns chooses the patterns and cases: drop case, closed, all, alphas, coupling and scene");
}

Obstacle parse_obstacle(const std::string& text) {
  if (text == "infinite") return Obstacle::Infinite;
  if (text == "finite") return Obstacle::Finite;
  throw std::invalid_argument("parse_obstacle(): obstacle must be infinite or finite, got '" + text + "'");
}

void SelectionOptions::check() const {
  if (order < 0 || order > max_order)
    throw std::invalid_argument("SelectionOptions::check(): order must be a whole number from 0 to " + std::to_string(max_order) + ", got " +
                                std::to_string(order));
  if ((!case_name.empty()) + (!closed.empty()) + all > 1)
    throw std::invalid_argument("SelectionOptions::check(): case, closed and all each choose the cases: give one of them");
}

namespace {

/// parse() of the text \p text of the option \p option, its refusal naming
/// them: "pairs: '1-9': pair 1-9 is outside bodies 1..5".
template <class Parse>
auto named(const char* option, const std::string& text, Parse parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("resolve(): ") + option + ": '" + text + "': " + without_function_prefix(e.what()));
  }
}

}  // namespace

namespace detail {

int body_limit(int width, bool all_cases) {
  // The largest n under about 10 s (docs/SYMBOLIC.md, "Limits"), for width 1 (--pairs near), 2 (near2), 3 and
  // more (all, or near2 with couplings): one case (--closed none, the slowest) and every case (--all).
  constexpr int one[] = {11, 8, 6}, every[] = {9, 7, 6};
  const int k = std::min(std::max(width, 1), 3) - 1;
  return all_cases ? every[k] : one[k];
}

/// The width of \p p: how many bodies apart the widest declared entry joins
/// (a diagonal K or a coupled pair), one more when there are couplings
/// (they were measured to cost as much as one more step of width).
int width(const Pattern& p) {
  int r = 1;
  for (const Pair& q : p.diagonal) r = std::max(r, q.j - q.i);
  for (const PairCoupling& c : p.couplings) r = std::max({r, c.first.j - c.first.i, c.second.j - c.second.i});
  return r + (p.couplings.empty() ? 0 : 1);
}

}  // namespace detail

Selection resolve(const SelectionOptions& o) {
  o.check();
  const Obstacle obstacle = o.obstacle;
  Pattern pattern;
  if (!o.scene.empty()) {
    pattern = Pattern::from_scene(load_scene(o.scene));
  } else {
    check_bodies(o.bodies, obstacle);
    if (!o.alphas.empty()) {
      if (o.bodies != Vocabulary::paper().bodies())
        throw std::invalid_argument("--alphas names the paper's couplings of 4 bodies; use --coupling for " + std::to_string(o.bodies));
      pattern = Pattern::paper(o.alphas);
    } else {
      pattern.bodies = o.bodies;
    }
    pattern.diagonal = named("pairs", o.pairs, [&] { return Pattern::parse_pairs(o.pairs, o.bodies); });
    if (!o.coupling.empty()) {
      const auto more = named("coupling", o.coupling, [&] { return Pattern::parse_couplings(o.coupling, o.bodies); });
      pattern.couplings.insert(pattern.couplings.end(), more.begin(), more.end());
    }
    pattern.check();
  }
  const int n = pattern.bodies;
  if (!o.no_limit) {
    const int w = detail::width(pattern), limit = detail::body_limit(w, o.all);
    if (n > limit)
      throw std::invalid_argument("--bodies " + std::to_string(n) + ": deriving " + (o.all ? "every case" : "a case") + " of a pattern of width " +
                                  std::to_string(w) + " was measured to take over 10 s past " + std::to_string(limit) +
                                  " bodies (docs/SYMBOLIC.md, Limits); --no-limit derives anyway");
  }
  const Symbols symbols(pattern, obstacle);
  std::optional<Scaling> scaling;
  if (!o.scaling.empty()) scaling = Scaling::parse(o.scaling, symbols);
  Selection s;
  s.deriver = std::make_unique<Deriver>(pattern, obstacle, scaling, o.order);
  if (o.all) {
    if (n > 16) throw std::invalid_argument("--all with " + std::to_string(n) + " bodies means 2^" + std::to_string(n - 1) + " cases; choose one with --closed");
    for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << (n - 1)); ++mask) s.cases.push_back(ContactSet::from_mask(mask, n));
  } else if (!o.case_name.empty()) {
    if (n != Vocabulary::paper().bodies()) throw std::invalid_argument("--case names the paper's cases of 4 bodies; use --closed");
    s.cases.push_back(Vocabulary::paper().named_case(o.case_name).closed);
  } else if (!o.closed.empty()) {
    s.cases.push_back(ContactSet::parse(o.closed, n));
  }
  return s;
}

}  // namespace superball::present
