#include "superball/cases/printed.hpp"

#include <toml++/toml.h>

#include <stdexcept>

#include "paper_data.hpp"

namespace superball {
namespace {

std::string str(const toml::node_view<const toml::node>& n, const char* what) {
  const auto v = n.value<std::string>();
  if (!v) throw std::runtime_error(std::string("PrintedNumbers::paper(): printed-numbers.toml: missing ") + what);
  return *v;
}

PrintedNumbers load() {
  const toml::table root = toml::parse(detail::paper_file("printed-numbers.toml"), std::string_view("cases/paper/printed-numbers.toml"));
  PrintedNumbers p;
  const auto eq16 = root["eq16"];
  p.eq16_section = str(eq16["section"], "eq16.section");
  p.eq16_text = str(eq16["text"], "eq16.text");
  p.eq16_case = str(eq16["case"], "eq16.case");
  if (const auto* v = eq16["velocities_after"].as_array())
    for (const auto& x : *v) p.eq16_velocities.push_back(Number::parse(x.value_or(std::string())));
  if (const auto* s = root["switch"].as_array())
    for (const auto& node : *s) {
      const toml::node_view<const toml::node> t(node);
      p.switches.push_back({str(t["section"], "switch.section"), str(t["parameter"], "switch.parameter"),
                            str(t["text"], "switch.text"), str(t["case"], "switch.case"),
                            Number::parse(str(t["value"], "switch.value"))});
    }
  const auto eps = root["epsilon_family"];
  p.epsilon_section = str(eps["section"], "epsilon_family.section");
  p.epsilon_text = str(eps["text"], "epsilon_family.text");
  p.epsilon_claim = str(eps["claim"], "epsilon_family.claim");
  return p;
}

}  // namespace

const PrintedNumbers& PrintedNumbers::paper() {
  static const PrintedNumbers p = load();
  return p;
}

}  // namespace superball
