#include "superball/present/selection.hpp"

#include <stdexcept>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/symbolic/estimate.hpp"

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
  if (!scene.empty() && (bodies || !alphas.empty() || !coupling.empty() || pairs))
    throw std::invalid_argument("SelectionOptions::check(): scene gives the number of bodies and the pattern: drop bodies, alphas, coupling and pairs");
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

Selection resolve(const SelectionOptions& o) {
  o.check();
  const Obstacle obstacle = o.obstacle;
  Pattern pattern;
  if (!o.scene.empty()) {
    pattern = Pattern::from_scene(load_scene(o.scene));
  } else {
    const int bodies = o.bodies.value_or(default_bodies);
    const std::string pairs = o.pairs.value_or(default_pairs);
    check_bodies(bodies, obstacle);
    if (!o.alphas.empty()) {
      if (bodies != Vocabulary::paper().bodies())
        throw std::invalid_argument("--alphas names the paper's couplings of 4 bodies; use --coupling for " + std::to_string(bodies));
      pattern = Pattern::paper(o.alphas);
    } else {
      pattern.bodies = bodies;
    }
    pattern.diagonal = named("pairs", pairs, [&] { return Pattern::parse_pairs(pairs, bodies); });
    if (!o.coupling.empty()) {
      const auto more = named("coupling", o.coupling, [&] { return Pattern::parse_couplings(o.coupling, bodies); });
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

DeriveFormat parse_derive_format(const std::string& text) {
  if (text == "text") return DeriveFormat::Text;
  if (text == "latex") return DeriveFormat::Latex;
  if (text == "json") return DeriveFormat::Json;
  throw std::invalid_argument("parse_derive_format(): format must be text, latex or json, got '" + text + "'");
}

DerivePlan plan_derivation(const Selection& s, int asked, const numeric::Memory& available) {
  numeric::check_threads(asked, "jobs");
  const int jobs = numeric::thread_count(asked);
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
