#include "superball/symbolic/pattern.hpp"

#include <algorithm>
#include <stdexcept>

#include "superball/cases/vocabulary.hpp"

namespace superball::symbolic {
namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const auto at = text.find(sep, start);
    std::string item = text.substr(start, at == std::string::npos ? std::string::npos : at - start);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (!item.empty()) out.push_back(item);
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

Pair pair_in(const std::string& text, int bodies, const char* who) {
  Pair p;
  try {
    p = Pair::parse(text);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(std::string(who) + "'" + text + "' is not a pair i-j with i < j");
  }
  if (p.j > bodies)
    throw std::invalid_argument(std::string(who) + "pair " + p.name() + " is outside bodies 1.." + std::to_string(bodies));
  return p;
}

void need_bodies(int bodies, const char* who) {
  if (bodies < 2) throw std::invalid_argument(std::string(who) + "a pattern needs at least 2 bodies (got " + std::to_string(bodies) + ")");
}

}  // namespace

Pattern Pattern::paper(const std::vector<int>& alphas) {
  const Vocabulary& v = Vocabulary::paper();
  Pattern p = all_pairs(v.bodies());
  for (int k : alphas) {
    if (k < 1 || k > static_cast<int>(v.alphas().size()))
      throw std::invalid_argument("Pattern::paper(): alpha_" + std::to_string(k) + " does not exist (the paper has alpha_1..alpha_" +
                                  std::to_string(v.alphas().size()) + ")");
    const NamedCoupling& c = v.alpha(k);
    p.couplings.emplace_back(c.first, c.second);
  }
  p.check();
  return p;
}

Pattern Pattern::all_pairs(int bodies, const std::vector<PairCoupling>& couplings) {
  need_bodies(bodies, "Pattern::all_pairs(): ");
  Pattern p;
  p.bodies = bodies;
  for (int i = 1; i <= bodies; ++i)
    for (int j = i + 1; j <= bodies; ++j) p.diagonal.push_back({i, j});
  p.couplings = couplings;
  p.check();
  return p;
}

Pattern Pattern::near(int bodies, int reach) {
  need_bodies(bodies, "Pattern::near(): ");
  if (reach < 1) throw std::invalid_argument("Pattern::near(): reach must be >= 1");
  Pattern p;
  p.bodies = bodies;
  for (int i = 1; i <= bodies; ++i)
    for (int j = i + 1; j <= bodies && j - i <= reach; ++j) p.diagonal.push_back({i, j});
  p.check();
  return p;
}

Pattern Pattern::nearest_and_next_nearest(int bodies) {
  Pattern p = near(bodies, 2);
  p.couplings = parse_couplings("near2", bodies);
  p.check();
  return p;
}

Pattern Pattern::from_scene(const Scene& scene) {
  need_bodies(scene.size(), "Pattern::from_scene(): ");
  Pattern p;
  p.bodies = scene.size();
  for (const MatrixEntry& e : scene.entries) {
    if (e.diagonal())
      p.diagonal.push_back(e.first);
    else
      p.couplings.emplace_back(e.first, e.second);
  }
  p.check();
  return p;
}

std::vector<Pair> Pattern::parse_pairs(const std::string& text, int bodies) {
  need_bodies(bodies, "Pattern::parse_pairs(): ");
  if (text == "all") return all_pairs(bodies).diagonal;
  if (text == "near") return near(bodies, 1).diagonal;
  if (text == "near2") return near(bodies, 2).diagonal;
  std::vector<Pair> out;
  for (const auto& item : split(text, ',')) out.push_back(pair_in(item, bodies, "Pattern::parse_pairs(): "));
  return out;
}

std::vector<PairCoupling> Pattern::parse_couplings(const std::string& text, int bodies) {
  need_bodies(bodies, "Pattern::parse_couplings(): ");
  std::vector<PairCoupling> out;
  if (text == "near2") {
    for (int i = 1; i + 2 <= bodies; ++i) {
      out.emplace_back(Pair{i, i + 1}, Pair{i, i + 2});
      out.emplace_back(Pair{i, i + 2}, Pair{i + 1, i + 2});
    }
    return out;
  }
  for (const auto& item : split(text, ',')) {
    const auto slash = item.find('/');
    if (slash == std::string::npos)
      throw std::invalid_argument("Pattern::parse_couplings(): '" + item + "' is not a coupling of two pairs i-j/k-l");
    Pair p = pair_in(item.substr(0, slash), bodies, "Pattern::parse_couplings(): ");
    Pair q = pair_in(item.substr(slash + 1), bodies, "Pattern::parse_couplings(): ");
    if (p == q) throw std::invalid_argument("Pattern::parse_couplings(): '" + item + "' couples a pair with itself (that is K_" + p.name() + ")");
    if (q < p) std::swap(p, q);
    out.emplace_back(p, q);
  }
  return out;
}

void Pattern::check() {
  need_bodies(bodies, "Pattern::check(): ");
  auto inside = [&](const Pair& p) {
    if (p.i < 1 || p.j > bodies || p.i >= p.j)
      throw std::invalid_argument("Pattern::check(): pair " + p.name() + " is outside bodies 1.." + std::to_string(bodies));
  };
  for (const Pair& p : diagonal) inside(p);
  for (auto& c : couplings) {
    inside(c.first);
    inside(c.second);
    if (c.first == c.second) throw std::invalid_argument("Pattern::check(): a coupling joins two different pairs (" + c.first.name() + ")");
    if (c.second < c.first) std::swap(c.first, c.second);
  }
  std::sort(diagonal.begin(), diagonal.end());
  std::sort(couplings.begin(), couplings.end());
  if (const auto twice = std::adjacent_find(diagonal.begin(), diagonal.end()); twice != diagonal.end())
    throw std::invalid_argument("Pattern::check(): the diagonal entry K " + twice->name() + " is declared twice");
  if (const auto twice = std::adjacent_find(couplings.begin(), couplings.end()); twice != couplings.end())
    throw std::invalid_argument("Pattern::check(): the coupling " + twice->first.name() + "/" + twice->second.name() +
                                " is declared twice (the order of its pairs does not matter)");
}

std::vector<Pair> Pattern::pairs() const {
  std::vector<Pair> out = diagonal;
  for (const auto& c : couplings) {
    out.push_back(c.first);
    out.push_back(c.second);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool Pattern::has_diagonal(const Pair& p) const { return std::binary_search(diagonal.begin(), diagonal.end(), p); }

std::string Pattern::describe() const {
  std::string s = std::to_string(bodies) + " bodies; K:";
  for (const Pair& p : diagonal) s += " " + p.name();
  s += "; couplings:";
  if (couplings.empty()) s += " none";
  for (const auto& c : couplings) s += " " + c.first.name() + "/" + c.second.name();
  return s;
}

}  // namespace superball::symbolic
