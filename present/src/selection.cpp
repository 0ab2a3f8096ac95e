#include "superball/present/selection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/estimate.hpp"

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

DerivePlan plan_derivation(const Selection& s, int jobs, const numeric::Memory& available) {
  const Deriver& d = *s.deriver;
  const int n = d.symbols().bodies();
  const std::size_t count = s.cases.size();
  const bool every = n <= 64 && count == (std::uint64_t{1} << (n - 1));
  DerivePlan p;
  p.estimate = estimate_derivation(d.symbols().pattern(), d.symbols().obstacle(), count, every);
  const double each = p.estimate.process_bytes;
  const std::string what = (every ? "every case" : count == 1 ? "a case" : std::to_string(count) + " cases") + " of " + std::to_string(n) +
                           " bodies, a pattern of width " + std::to_string(p.estimate.width);
  numeric::check_memory("derive()", "deriving " + what, each, "one process, from the growth measured per pattern width: docs/SYMBOLIC.md, Limits",
                        available, "derive fewer bodies or a narrower pattern");
  const double fit = std::floor(available.bytes / each);
  p.workers = static_cast<int>(std::max(1.0, std::min({static_cast<double>(std::max(jobs, 1)), static_cast<double>(std::max<std::size_t>(count, 1)), fit})));
  p.text = "deriving " + what + ": about " + duration_text(p.estimate.seconds) + " on one core, " + std::to_string(p.workers) +
           (p.workers == 1 ? " worker" : " workers") + (p.workers < jobs && p.workers < static_cast<int>(count) ? " (as many as the memory holds)" : "") +
           ", about " + numeric::bytes_text(each) + (p.workers == 1 ? "" : " each") + " (" + numeric::bytes_text(available.bytes) + " available)";
  return p;
}

}  // namespace superball::present
