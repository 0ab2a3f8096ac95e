#include "superball/cases/printed_conditions.hpp"

#include <toml++/toml.h>

#include <set>
#include <stdexcept>

#include "paper_data.hpp"

namespace superball {
namespace {

class Reader {
 public:
  explicit Reader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw std::invalid_argument("PrintedConditions::parse(): " + origin_ + ": " + where + ": " + what);
  }

  std::string text(const toml::table& t, const std::string& where, const char* key, bool required = true) const {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(where, std::string("missing '") + key + "'");
      return "";
    }
    const auto v = n->value<std::string>();
    if (!v) fail(where, std::string("'") + key + "' must be a string");
    return *v;
  }

  std::vector<int> ints(const toml::table& t, const std::string& where, const char* key) const {
    std::vector<int> out;
    const toml::node* n = t.get(key);
    if (!n) fail(where, std::string("missing '") + key + "'");
    const toml::array* a = n->as_array();
    if (!a) fail(where, std::string("'") + key + "' must be an array of integers");
    for (const auto& x : *a) {
      const auto v = x.value<int64_t>();
      if (!v || *v < 1 || *v > 7) fail(where, std::string("'") + key + "' holds alpha indices 1..7");
      out.push_back(static_cast<int>(*v));
    }
    return out;
  }

 private:
  std::string origin_;
};

}  // namespace

PrintedConditions PrintedConditions::parse(const std::string& source, const std::string& origin) {
  const Reader r(origin);
  toml::table root;
  try {
    root = toml::parse(source, origin);
  } catch (const toml::parse_error& e) {
    r.fail("line " + std::to_string(e.source().begin.line), std::string(e.description()));
  }
  for (const auto& [key, node] : root)
    if (key.str() != "condition" && key.str() != "claim") r.fail(std::string(key.str()), "unknown table (expected [[condition]] or [[claim]])");
  PrintedConditions out;
  static const std::set<std::string> kinds = {"superball", "evolution", "contact", "psd", "velocity"};
  static const std::set<std::string> relations = {">", ">=", "<", "<=", "="};
  if (const toml::array* list = root["condition"].as_array()) {
    for (std::size_t k = 0; k < list->size(); ++k) {
      const toml::table* t = (*list)[k].as_table();
      const std::string where = "condition[" + std::to_string(k + 1) + "]";
      if (!t) r.fail(where, "must be a table");
      PrintedCondition c;
      c.section = r.text(*t, where, "section");
      c.case_name = r.text(*t, where, "case");
      c.alphas = r.ints(*t, where, "alphas");
      c.kind = r.text(*t, where, "kind");
      if (!kinds.count(c.kind)) r.fail(where, "kind '" + c.kind + "' is not superball, evolution, contact, psd or velocity");
      c.about = r.text(*t, where, "about");
      c.printed = r.text(*t, where, "printed");
      c.lhs = r.text(*t, where, "lhs");
      c.relation = r.text(*t, where, "relation");
      if (!relations.count(c.relation)) r.fail(where, "relation '" + c.relation + "' is not one of > >= < <= =");
      if ((c.relation == "=") != (c.kind == "velocity")) r.fail(where, "relation '=' goes with kind 'velocity' only");
      c.rhs = r.text(*t, where, "rhs");
      c.words = r.text(*t, where, "words");
      c.note = r.text(*t, where, "note", false);
      out.conditions.push_back(std::move(c));
    }
  }
  if (const toml::array* list = root["claim"].as_array()) {
    for (std::size_t k = 0; k < list->size(); ++k) {
      const toml::table* t = (*list)[k].as_table();
      const std::string where = "claim[" + std::to_string(k + 1) + "]";
      if (!t) r.fail(where, "must be a table");
      PaperClaim c;
      c.id = r.text(*t, where, "id");
      c.section = r.text(*t, where, "section");
      c.case_name = r.text(*t, where, "case");
      c.alphas = r.ints(*t, where, "alphas");
      c.like = r.ints(*t, where, "like");
      c.claim = r.text(*t, where, "claim");
      if (c.claim != "superball possible" && c.claim != "superball impossible")
        r.fail(where, "claim '" + c.claim + "' is not 'superball possible' or 'superball impossible'");
      c.text = r.text(*t, where, "text");
      out.claims.push_back(std::move(c));
    }
  }
  return out;
}

const PrintedConditions& PrintedConditions::paper() {
  static const PrintedConditions p = parse(detail::paper_file("printed-conditions.toml"), "cases/paper/printed-conditions.toml");
  return p;
}

}  // namespace superball
