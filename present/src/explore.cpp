// The exploration of a pattern (verify/explore.hpp) for people and programs:
// `superball explore`, its --json, the table of --all-patterns, and the
// witness scene files.
#include "superball/present/explore.hpp"

#include <cln/rational_io.h>
#include <cln/real.h>

#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/scalar.hpp"
#include "superball/verify/space.hpp"

namespace superball::present {

std::string cell_text(const verify::ExploreResult& r) {
  if (r.reach == verify::Reach::Yes) {
    // Four significant digits, more when fewer would round the ratio (> 1) to 1.
    const double ratio = cln::double_approx(r.ratio);
    int digits = 4;
    while (digits < 17 && std::stod(numeric::to_string(ratio, digits)) <= 1) ++digits;
    return "yes U₁⁺/a = " + numeric::to_string(ratio, digits);
  }
  if (r.reach != verify::Reach::NotFound) return verify::to_string(r.reach);
  std::string notes;
  if (!r.witness.empty()) notes = "best U₁⁺/a = " + numeric::to_string(cln::double_approx(r.ratio), 6);
  if (r.asymptotic_clash) notes += std::string(notes.empty() ? "" : "; ") + "leading order clashes";
  return notes.empty() ? "not found" : "not found (" + notes + ")";
}

std::string to_text(const verify::ExploreResult& r) {
  std::ostringstream os;
  os << "pattern " << r.pattern << ", case " << r.case_name << " (closed contacts: "
     << (r.closed.closed_names().empty() ? std::string("none") : r.closed.to_string()) << ")\n";
  os << "  verdict: " << verify::to_string(r.reach);
  switch (r.reach) {
    case verify::Reach::Yes: os << ": the case is the actual evolution with U₁⁺ > a at the witness (exact solve)\n"; break;
    case verify::Reach::Impossible: os << ": the case's conditions and U₁⁺ > a cannot hold together for any M positive semi-definite\n"; break;
    case verify::Reach::CaseImpossible: os << ": the case's conditions cannot hold together for any M positive semi-definite\n"; break;
    case verify::Reach::NotFound: os << ": no witness with U₁⁺ > a in the box, and no proof of impossibility\n"; break;
  }
  os << "  box: " << r.box << "\n";
  if (!r.witness.empty()) {
    os << "  " << (r.reach == verify::Reach::Yes ? "largest U₁⁺/a found in the box" : "largest U₁⁺/a found with the case actual") << ": "
       << numeric::to_string(cln::double_approx(r.ratio), 8) << " = " << verify::to_string(r.ratio) << " (exact solve; double search "
       << numeric::to_string(r.stats.best_double, 8) << ")\n";
    std::string point;
    for (const auto& [name, v] : r.witness) point += (point.empty() ? "" : ", ") + name + " = " + verify::to_string(v);
    os << "  witness: " << point << "\n";
    os << "  exact solve there: case " << r.case_name << " actual, U1+ = " << verify::to_string(r.u1) << "\n";
  } else {
    os << "  the case was never actual at a searched point\n";
  }
  const verify::ExploreStats& s = r.stats;
  os << "  search: seed " << r.seed << ", " << s.starts << " starts, " << s.evaluations << " evaluations, " << s.feasible_starts
     << " ended with the case's conditions holding (" << s.superball_starts << " with U₁⁺ > a), " << s.exact_solves << " exact solves, "
     << s.inward_steps << " steps inward\n";
  for (const std::optional<verify::Clash>* c : {&r.clash, &r.asymptotic_clash}) {
    if (!*c) continue;
    os << "  clash of the " << ((*c)->asymptotic ? "leading-order (asymptotic)" : "exact") << " conditions:\n";
    for (const std::string& line : (*c)->conditions) os << "    " << line << "\n";
    os << "    " << (*c)->identity << "\n";
  }
  if (r.reach != verify::Reach::Yes) {
    if (!r.clash) os << "  no clash of the exact conditions found (weights {0, 1, 2}, t·xᵀMx with x in {-1, 0, 1} on the coupled pairs)\n";
    if (!r.asymptotic_clash) os << "  no clash of the leading-order conditions found\n";
  }
  return os.str();
}

RenderedCell render(const verify::ExploreResult& r) { return {r.pattern, cell_text(r), to_json(r)}; }

namespace {

std::vector<std::vector<RenderedCell>> render_cells(const verify::PatternTable& t) {
  std::vector<std::vector<RenderedCell>> cells;
  for (const auto& row : t.cells) {
    cells.emplace_back();
    for (const verify::ExploreResult& c : row) cells.back().push_back(render(c));
  }
  return cells;
}

}  // namespace

std::string to_text(const verify::PatternTable& t) { return to_text(t, render_cells(t)); }

std::string to_text(const verify::PatternTable& t, const std::vector<std::vector<RenderedCell>>& cells) {
  std::ostringstream os;
  os << "| pattern |";
  for (const std::string& c : t.cases) os << " case " << c << " |";
  os << "\n|---|";
  for (std::size_t k = 0; k < t.cases.size(); ++k) os << "---|";
  os << "\n";
  for (std::size_t r = 0; r < t.patterns.size(); ++r) {
    os << "| " << (cells[r].empty() ? std::string() : cells[r].front().pattern) << " |";
    for (const RenderedCell& c : cells[r]) os << " " << c.text << " |";
    os << "\n";
  }
  os << "\nbox: " << verify::describe_box(t.options) << "; per cell: seed " << t.options.seed << ", " << t.options.starts << " starts of at most "
     << t.options.evaluations << " evaluations (Nelder–Mead), the best ends confirmed by exact solves; \"no (proved)\" and \"case impossible\" "
     << "are proofs (a clash of the exact conditions), \"not found\" is neither a witness nor a proof\n";
  return os.str();
}

nlohmann::ordered_json to_json(const verify::ExploreResult& r) {
  nlohmann::ordered_json j;
  j["pattern"] = r.pattern_ascii;
  j["case"] = r.case_name;
  j["closed_contacts"] = r.closed.closed_names();
  j["reach"] = verify::to_string(r.reach);
  j["box"] = r.box;
  j["seed"] = r.seed;
  if (!r.witness.empty()) {
    nlohmann::ordered_json point = nlohmann::ordered_json::object();
    for (const auto& [name, v] : r.witness) point[name] = verify::to_string(v);
    j["witness"] = point;
    j["U1"] = verify::to_string(r.u1);
    j["ratio"] = verify::to_string(r.ratio);
    j["ratio_decimal"] = cln::double_approx(r.ratio);
  }
  const verify::ExploreStats& s = r.stats;
  j["stats"] = {{"starts", s.starts},           {"evaluations", s.evaluations},   {"feasible_starts", s.feasible_starts},
                {"superball_starts", s.superball_starts}, {"exact_solves", s.exact_solves}, {"inward_steps", s.inward_steps},
                {"best_double", s.best_double}};
  for (const auto& [key, c] : {std::make_pair("clash", &r.clash), std::make_pair("asymptotic_clash", &r.asymptotic_clash)})
    if (*c) j[key] = {{"superball", (*c)->superball}, {"conditions", (*c)->conditions}, {"identity", (*c)->identity}};
  return j;
}

nlohmann::ordered_json to_json(const verify::PatternTable& t) { return to_json(t, render_cells(t)); }

nlohmann::ordered_json to_json(const verify::PatternTable& t, const std::vector<std::vector<RenderedCell>>& cells) {
  nlohmann::ordered_json j;
  j["box"] = verify::describe_box(t.options);
  j["seed"] = t.options.seed;
  j["starts"] = t.options.starts;
  j["evaluations"] = t.options.evaluations;
  j["cases"] = t.cases;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < t.patterns.size(); ++r) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (const RenderedCell& c : cells[r]) row.push_back(c.json);
    rows.push_back({{"alphas", t.patterns[r]}, {"cells", row}});
  }
  j["rows"] = rows;
  return j;
}

std::string witness_file(const verify::ExploreResult& r, const std::string& command) {
  if (!r.scene) throw std::invalid_argument("witness_file(): the result has no witness");
  const std::string comment = "Found by `" + command + "`: multi-start Nelder-Mead on the derived conditions of case " + r.case_name +
                              " in the box (" + r.box + "), rounded to rationals.\nExact solve (CollisionSolver over rationals, case not imposed): case " +
                              r.case_name + " is the actual evolution, U1+ = " + verify::to_string(r.u1) + " = " +
                              numeric::to_string(cln::double_approx(r.ratio), 10) + " a" + (r.ratio > 1 ? " > a (superball)" : " <= a (no superball)") +
                              ".\nCheck: superball solve FILE --precision exact";
  return write_scene(*r.scene, comment);
}

}  // namespace superball::present
