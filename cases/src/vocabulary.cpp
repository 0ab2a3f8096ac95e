#include "superball/cases/vocabulary.hpp"

#include <toml++/toml.h>

#include <stdexcept>

#include "superball/cases/error.hpp"
#include "paper_data.hpp"

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
  auto pair = [&](const toml::node& node, const std::string& where) {
    try {
      return Pair::parse(node.value_or(std::string()));
    } catch (const std::invalid_argument& e) {
      bad(origin, where + ": " + without_function_prefix(e.what()));
    }
  };
  v.bodies_ = root["bodies"].value_or(0);
  if (v.bodies_ < 2) bad(origin, "bodies must be >= 2");
  if (const toml::node* cases = root.get("case")) {
    const toml::array* list = cases->as_array();
    if (!list || !list->is_array_of_tables()) bad(origin, "case must be an array of tables [[case]]");
    for (const auto& node : *list) {
      const auto& t = *node.as_table();
      NamedCase c{t["name"].value_or(std::string()), ContactSet(v.bodies_), t["description"].value_or(std::string())};
      if (c.name.empty()) bad(origin, "a case has no name");
      const toml::array* closed = t["closed"].as_array();
      if (!closed) bad(origin, "case " + c.name + ": closed must be an array of contacts");
      for (const auto& p : *closed) {
        const Pair contact = pair(p, "case " + c.name);
        if (!contact.adjacent() || contact.j > v.bodies_) bad(origin, "case " + c.name + ": " + contact.name() + " is not a contact");
        c.closed.set_closed(contact.i - 1, true);
      }
      for (const auto& other : v.cases_)
        if (other.closed == c.closed || other.name == c.name) bad(origin, "case " + c.name + " is listed twice");
      v.cases_.push_back(std::move(c));
    }
  }
  if (const toml::node* alphas = root.get("alpha")) {
    const toml::array* list = alphas->as_array();
    if (!list || !list->is_array_of_tables()) bad(origin, "alpha must be an array of tables [[alpha]]");
    for (const auto& node : *list) {
      const auto& t = *node.as_table();
      const auto* pairs = t["pairs"].as_array();
      if (!pairs || pairs->size() != 2) bad(origin, "alpha needs two pairs");
      const std::string where = "alpha " + std::to_string(v.alphas_.size() + 1);
      NamedCoupling c{t["index"].value_or(0), pair((*pairs)[0], where), pair((*pairs)[1], where)};
      if (c.index != static_cast<int>(v.alphas_.size()) + 1) bad(origin, "alphas must be numbered 1, 2, ... in order");
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
