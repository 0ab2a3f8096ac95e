// The JSON of a derivation (`superball derive --format json`, the Python module's derive()).
#include "superball/present/derivation.hpp"

#include <sstream>

#include "superball/symbolic/format.hpp"

namespace superball::present {

using namespace superball::symbolic;

namespace {

/// Whether a form is written out expanded: always with \p expanded, else
/// only when the case does not write it through its elimination (compact).
bool written(const ConditionForm& form, bool expanded) { return expanded || !form.eliminated; }

}  // namespace

bool through_elimination(const Derivation& d, const GiNaC::ex& p) {
  return d.elimination && (GiNaC::is_a<GiNaC::add>(p) ? p.nops() : 1) > max_inline_exact_terms;
}

Forms printed_forms(bool expanded) { return expanded ? Forms::All : Forms::Printed; }

bool through_elimination(const Derivation& d, const Fraction& f) { return d.elimination && f.terms > max_inline_exact_terms; }

nlohmann::ordered_json condition_json(const Condition& c, const Symbols& s, bool expanded) {
  nlohmann::ordered_json j;
  j["kind"] = to_string(c.kind);
  j["about"] = c.about;
  const bool with_exact = written(c.exact, expanded), with_asymptotic = written(c.asymptotic, expanded);
  const StyledText exact = with_exact ? format_condition_styles(c.exact, c.relation, s) : StyledText{};
  // The asymptotic form is often the exact one again (every term of the leading order): formatted once.
  const bool same = with_exact && c.asymptotic.numerator.is_equal(c.exact.numerator) && c.asymptotic.denominator.is_equal(c.exact.denominator);
  const StyledText asymptotic = !with_asymptotic ? StyledText{} : same ? exact : format_condition_styles(c.asymptotic, c.relation, s);
  if (with_exact) j["exact"] = exact.ascii;
  if (with_asymptotic) j["asymptotic"] = asymptotic.ascii;
  if (with_exact) {
    j["text"] = exact.text;
    j["latex"] = exact.latex;
  }
  if (with_asymptotic) {
    j["asymptotic_text"] = asymptotic.text;
    j["asymptotic_latex"] = asymptotic.latex;
  }
  if (c.finite && written(*c.finite, expanded)) j["finite"] = format_condition(*c.finite, c.relation, s, Style::Ascii);
  // The same conditions as a person writes them (isolated or grouped; derivation.hpp, Readable).
  nlohmann::ordered_json readable = nlohmann::ordered_json::object();
  auto add = [&](const char* key, const ConditionForm& form) {
    if (!form.readable) return;
    readable[key] = {{"ascii", format_readable(*form.readable, c.relation, s, Style::Ascii)},
                     {"text", format_readable(*form.readable, c.relation, s, Style::Text)},
                     {"latex", format_readable(*form.readable, c.relation, s, Style::Latex)}};
  };
  add("exact", c.exact);
  if (c.finite) add("finite", *c.finite);
  add("asymptotic", c.asymptotic);
  if (!readable.empty()) j["readable"] = readable;
  // Long forms through the case's elimination (derivation.hpp, Elimination): Σ ℓ_c V_c + β REL 0.
  nlohmann::ordered_json eliminated = nlohmann::ordered_json::object();
  auto add_eliminated = [&](const char* key, const ConditionForm& form) {
    if (!form.eliminated) return;
    eliminated[key] = {{"ascii", format_eliminated(*form.eliminated, c.relation, s, Style::Ascii)},
                       {"text", format_eliminated(*form.eliminated, c.relation, s, Style::Text)},
                       {"latex", format_eliminated(*form.eliminated, c.relation, s, Style::Latex)},
                       {"limit", form.eliminated->limit}};
  };
  add_eliminated("exact", c.exact);
  if (c.finite) add_eliminated("finite", *c.finite);
  add_eliminated("asymptotic", c.asymptotic);
  if (!eliminated.empty()) j["eliminated"] = eliminated;
  std::ostringstream order;
  order << c.leading_order;
  j["order"] = order.str();
  j["orders_kept"] = c.orders_kept;
  j["verdict"] = to_string(c.exact.verdict);
  j["asymptotic_verdict"] = to_string(c.asymptotic.verdict);
  j["proof"] = c.proof;
  return j;
}

nlohmann::ordered_json derivation_json(const Derivation& d, const Deriver& deriver, std::vector<nlohmann::ordered_json>& psd, bool expanded,
                                       bool with_psd) {
  const Symbols& s = *d.symbols;
  nlohmann::ordered_json j;
  j["case"] = d.case_name;
  j["closed_contacts"] = d.closed.closed_names();
  j["pattern"] = s.pattern().describe();
  j["obstacle"] = s.obstacle() == Obstacle::Infinite ? "infinite" : "finite";
  j["scaling"] = deriver.scaling().describe(s, Style::Ascii);
  nlohmann::ordered_json symbols = nlohmann::ordered_json::array();
  for (const SymbolInfo& i : s.all()) {
    const char* kind = i.kind == SymbolKind::Mass ? "mass" : i.kind == SymbolKind::Diagonal ? "K" : i.kind == SymbolKind::Coupling ? "coupling" : "fall_speed";
    nlohmann::ordered_json sym{{"name", i.ascii}, {"kind", kind}, {"text", i.text}, {"latex", i.latex}, {"positive", i.kind != SymbolKind::Coupling}};
    if (i.kind == SymbolKind::Diagonal || i.kind == SymbolKind::Coupling) sym["pairs"] = {i.first.name(), i.second.name()};
    symbols.push_back(sym);
  }
  j["symbols"] = symbols;
  // Compact: a value the report writes through the elimination (over max_inline_exact_terms terms) is that
  // form, over the names of elimination.definitions: V1, -(...V1 + ...), p1*p2*...
  auto through = [&](const auto& p) { return !expanded && through_elimination(d, p); };
  nlohmann::ordered_json v = nlohmann::ordered_json::object();
  for (int i = 1, cluster = 1; i <= s.bodies(); ++i) {
    const Fraction& f = d.velocities[static_cast<std::size_t>(i - 1)];
    v["U" + std::to_string(i)] = through(f) ? cluster_velocity_name(cluster, Style::Ascii) : format_fraction(f, s, Style::Ascii);
    if (i < s.bodies() && !d.closed.closed(i - 1)) ++cluster;  // the next body starts a cluster
  }
  j["velocities_after"] = v;
  nlohmann::ordered_json r = nlohmann::ordered_json::object();
  for (int c = 0; c + 1 < s.bodies(); ++c) {
    if (!d.closed.closed(c)) continue;
    const Fraction& f = d.reactions[static_cast<std::size_t>(c)];
    r[Pair{c + 1, c + 2}.name()] = through(f) ? format_linear(d.reactions_eliminated[static_cast<std::size_t>(c)], s, Style::Ascii, true)
                                                        : format_fraction(f, s, Style::Ascii);
  }
  j["reactions"] = r;
  std::string determinant;  // det(ZᵀAZ) = Π p_j when written through the elimination
  if (through(d.determinant))
    for (const auto& [name, value] : elimination_definitions(*d.elimination, s, Style::Ascii))
      if (name[0] == 'p') determinant = name + (determinant.empty() ? "" : "*" + determinant);
  j["determinant"] = determinant.empty() ? format_polynomial(d.determinant, s, Style::Ascii) : determinant;
  j["check"] = d.check;
  nlohmann::ordered_json named = nlohmann::ordered_json::array();
  for (const NamedPart& p : d.named)
    named.push_back({{"name", named_part_name(p.index, Style::Ascii)},
                     {"value", format_polynomial(p.value, s, Style::Ascii)},
                     {"text", format_polynomial(p.value, s, Style::Text)},
                     {"latex", format_polynomial(p.value, s, Style::Latex)},
                     {"positive", p.positive}});
  j["named"] = named;
  if (d.elimination) {
    const Elimination& e = *d.elimination;
    nlohmann::ordered_json order = nlohmann::ordered_json::array(), small = nlohmann::ordered_json::array(),
                           definitions = nlohmann::ordered_json::array();
    for (int c : e.order) order.push_back(c + 1);
    for (const GiNaC::ex& x : e.small) small.push_back(s.info(x).ascii);
    const auto ascii = elimination_definitions(e, s, Style::Ascii), text = elimination_definitions(e, s, Style::Text),
               latex = elimination_definitions(e, s, Style::Latex);
    for (std::size_t k = 0; k < ascii.size(); ++k)
      definitions.push_back({{"name", ascii[k].first}, {"value", ascii[k].second}, {"text", text[k].first + " = " + text[k].second},
                             {"latex", latex[k].first + " = " + latex[k].second}});
    j["elimination"] = {{"order", order}, {"small", small}, {"definitions", definitions}};
  }
  j["actual"] = to_string(d.actual);
  if (d.actual == Verdict::Never) j["actual_reason"] = d.actual_reason;
  nlohmann::ordered_json conditions = nlohmann::ordered_json::array();
  if (psd.empty() && with_psd)
    for (const Condition& c : deriver.psd()) psd.push_back(condition_json(c, s, expanded));
  for (const Condition& c : d.conditions)
    if (c.kind != ConditionKind::Psd) conditions.push_back(condition_json(c, s, expanded));
  if (with_psd)
    for (const nlohmann::ordered_json& c : psd) conditions.push_back(c);
  j["conditions"] = conditions;
  return j;
}

}  // namespace superball::present
