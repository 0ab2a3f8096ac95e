#include "superball/present/selection.hpp"

#include <sstream>

#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"

namespace superball::present {

using namespace superball::symbolic;

std::vector<int> parse_alphas(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty()) continue;
    std::size_t used = 0;
    int k = 0;
    try {
      k = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size()) throw std::invalid_argument("--alphas: '" + item + "' is not an index 1..7 (e.g. --alphas 1,6)");
    out.push_back(k);
  }
  return out;
}

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
  const Obstacle obstacle = o.obstacle == "finite" ? Obstacle::Finite : Obstacle::Infinite;
  Pattern pattern;
  if (!o.scene.empty()) {
    pattern = Pattern::from_scene(load_scene(o.scene));
  } else {
    check_bodies(o.bodies, obstacle);
    if (!o.alphas.empty()) {
      if (o.bodies != Vocabulary::paper().bodies())
        throw std::invalid_argument("--alphas names the paper's couplings of 4 bodies; use --coupling for " + std::to_string(o.bodies));
      pattern = Pattern::paper(parse_alphas(o.alphas));
    } else {
      pattern.bodies = o.bodies;
    }
    pattern.diagonal = Pattern::parse_pairs(o.pairs, o.bodies);
    if (!o.coupling.empty()) {
      const auto more = Pattern::parse_couplings(o.coupling, o.bodies);
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
