#include "superball/cases/vocabulary.hpp"

#include <toml++/toml.h>

#include <stdexcept>

#include "superball/cases/paper_data.hpp"

namespace superball {

namespace {
[[noreturn]] void bad(const std::string& origin, const std::string& what) {
  throw std::runtime_error("Vocabulary: " + origin + ": " + what);
}
}  // namespace

Vocabulary Vocabulary::parse(const std::string& text, const std::string& origin) {
  Vocabulary v;
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    bad(origin, std::string(e.description()));
  }
  v.bodies_ = root["bodies"].value_or(0);
  if (v.bodies_ < 2) bad(origin, "bodies must be >= 2");
  if (const auto* cases = root["case"].as_array()) {
    for (const auto& node : *cases) {
      const auto& t = *node.as_table();
      NamedCase c{t["name"].value_or(std::string()), ContactSet(v.bodies_), t["description"].value_or(std::string())};
      if (const auto* closed = t["closed"].as_array())
        for (const auto& p : *closed) c.closed = [&] {
            ContactSet s = c.closed;
            const Pair pair = Pair::parse(p.value_or(std::string()));
            if (!pair.adjacent() || pair.j > v.bodies_) bad(origin, "case " + c.name + ": " + pair.name() + " is not a contact");
            s.set_closed(pair.i - 1, true);
            return s;
          }();
      for (const auto& other : v.cases_)
        if (other.closed == c.closed || other.name == c.name) bad(origin, "case " + c.name + " is listed twice");
      v.cases_.push_back(std::move(c));
    }
  }
  if (const auto* alphas = root["alpha"].as_array()) {
    for (const auto& node : *alphas) {
      const auto& t = *node.as_table();
      const auto* pairs = t["pairs"].as_array();
      if (!pairs || pairs->size() != 2) bad(origin, "alpha needs two pairs");
      NamedCoupling c{t["index"].value_or(0), Pair::parse((*pairs)[0].value_or(std::string())),
                      Pair::parse((*pairs)[1].value_or(std::string()))};
      if (c.index != static_cast<int>(v.alphas_.size()) + 1) bad(origin, "alphas must be numbered 1, 2, … in order");
      v.alphas_.push_back(c);
    }
  }
  return v;
}

const Vocabulary& Vocabulary::paper() {
  static const Vocabulary v = parse(detail::paper_file("vocabulary.toml"), "cases/paper/vocabulary.toml");
  return v;
}

std::string Vocabulary::case_name(const ContactSet& set) const {
  if (set.bodies() == bodies_)
    for (const auto& c : cases_)
      if (c.closed == set) return c.name;
  return set.to_string();
}

const NamedCase& Vocabulary::named_case(const std::string& name) const {
  for (const auto& c : cases_)
    if (c.name == name) return c;
  std::string list;
  for (const auto& c : cases_) list += (list.empty() ? "" : ", ") + c.name;
  throw std::invalid_argument("Vocabulary::named_case(): no case '" + name + "' (the paper's cases: " + list + ")");
}

const NamedCoupling& Vocabulary::alpha(int k) const {
  if (k < 1 || k > static_cast<int>(alphas_.size()))
    throw std::invalid_argument("Vocabulary::alpha(): alpha_" + std::to_string(k) + " does not exist (1.." +
                                std::to_string(alphas_.size()) + ")");
  return alphas_[static_cast<std::size_t>(k - 1)];
}

std::optional<int> Vocabulary::alpha_index(const Pair& p, const Pair& q) const {
  for (const auto& a : alphas_)
    if ((a.first == p && a.second == q) || (a.first == q && a.second == p)) return a.index;
  return std::nullopt;
}

}  // namespace superball
