#include "superball/cases/model.hpp"

#include <cctype>
#include <stdexcept>

namespace superball {
namespace {

int parse_index(std::string_view s, std::string_view whole, const char* who) {
  if (s.empty() || s.size() > 9) throw std::invalid_argument(std::string(who) + "'" + std::string(whole) + "' is not of the form i-j");
  int v = 0;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c)))
      throw std::invalid_argument(std::string(who) + "'" + std::string(whole) + "' is not of the form i-j");
    v = v * 10 + (c - '0');
  }
  return v;
}

}  // namespace

Pair Pair::parse(std::string_view text) {
  const auto dash = text.find('-');
  if (dash == std::string_view::npos)
    throw std::invalid_argument("Pair::parse(): '" + std::string(text) + "' is not of the form i-j");
  Pair p{parse_index(text.substr(0, dash), text, "Pair::parse(): "),
         parse_index(text.substr(dash + 1), text, "Pair::parse(): ")};
  if (p.i < 1 || p.j <= p.i)
    throw std::invalid_argument("Pair::parse(): '" + std::string(text) + "' needs 1 <= i < j");
  return p;
}

std::string Pair::name() const { return std::to_string(i) + "-" + std::to_string(j); }

ContactSet ContactSet::parse(std::string_view text, int bodies) {
  ContactSet set(bodies);
  if (text.empty() || text == "none" || text == "{}") return set;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto comma = text.find(',', start);
    const auto item = text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    Pair p;
    try {
      p = Pair::parse(item);
    } catch (const std::invalid_argument&) {
      throw std::invalid_argument("ContactSet::parse(): '" + std::string(item) + "' is not a contact i-(i+1)");
    }
    if (!p.adjacent() || p.j > bodies)
      throw std::invalid_argument("ContactSet::parse(): '" + std::string(item) + "' is not a contact between adjacent bodies of " +
                                  std::to_string(bodies));
    set.set_closed(p.i - 1, true);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return set;
}

ContactSet ContactSet::from_mask(std::uint64_t mask, int bodies) {
  if (bodies > 65) throw std::invalid_argument("ContactSet::from_mask(): at most 65 bodies");
  ContactSet set(bodies);
  for (int c = 0; c < set.contacts(); ++c) set.set_closed(c, (mask >> c) & 1u);
  return set;
}

std::vector<std::string> ContactSet::closed_names() const {
  std::vector<std::string> out;
  for (int c = 0; c < contacts(); ++c)
    if (closed(c)) out.push_back(Pair{c + 1, c + 2}.name());
  return out;
}

std::string ContactSet::to_string() const {
  std::string s = "{";
  for (const auto& name : closed_names()) s += (s.size() > 1 ? "," : "") + name;
  return s + "}";
}

const MatrixEntry* Scene::find(const Pair& p, const Pair& q) const {
  for (const auto& e : entries)
    if ((e.first == p && e.second == q) || (e.first == q && e.second == p)) return &e;
  return nullptr;
}

}  // namespace superball
