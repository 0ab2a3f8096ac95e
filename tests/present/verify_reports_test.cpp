// The reports of verify/'s results called directly (present/verification,
// audit, explore and overlay .hpp): known answers on the paper's cases
// (case 2.1 of α₂ verified, case 1 of α₂ explored to a witness and of
// {α₁, α₆} to a proof, the audit of §4), and their structure: the JSON's
// keys, every condition of the case in the text and the JSON, the table's
// cells, a witness file that reads back.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <set>
#include <stdexcept>
#include <string>

#include "superball/cases/parameter.hpp"
#include "superball/cases/printed_conditions.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/map.hpp"
#include "superball/present/audit.hpp"
#include "superball/present/explore.hpp"
#include "superball/present/overlay.hpp"
#include "superball/present/verification.hpp"

namespace superball::present {
namespace {

using symbolic::Deriver;
using symbolic::Obstacle;
using symbolic::Pattern;

ContactSet named(const std::string& name) { return Vocabulary::paper().named_case(name).closed; }

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

/// A verification of case 2.1 of α₂ small enough for a unit test.
const verify::Verification& case21() {
  static const verify::Verification v = [] {
    verify::VerifyOptions o;
    o.epsilons = {cln::cl_RA(1) / 100, cln::cl_RA(1) / 1000};
    o.samples = 100;
    o.boundary_pairs = 2;
    o.threads = 1;
    return verify::verify_case(Deriver(Pattern::paper({2}), Obstacle::Infinite), named("2.1"), o);
  }();
  return v;
}

TEST(VerificationReport, Case21TextAndJson) {
  const verify::Verification& v = case21();
  ASSERT_TRUE(v.exact_agrees());  // the known answer: the derived exact conditions are exact
  const std::string text = to_text(v);
  EXPECT_EQ(text.rfind("case 2.1 — ", 0), 0u) << text;
  EXPECT_TRUE(contains(text, "points per eps: 100 drawn")) << text;
  EXPECT_TRUE(contains(text, "\n  1e-2 ") || contains(text, "  1e-2")) << text;
  EXPECT_TRUE(contains(text, "1e-3")) << text;
  const nlohmann::ordered_json j = to_json(v);
  for (const char* key : {"case", "pattern", "obstacle", "scaling", "samples", "boundary_pairs", "boundary_bracket", "seed", "exact_agrees",
                          "conditions", "epsilons", "disagreements"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["case"], "2.1");
  EXPECT_EQ(j["exact_agrees"], true);
  EXPECT_EQ(j["epsilons"].size(), 2u);
  EXPECT_EQ(j["epsilons"][0]["epsilon"], "1/100");
  // Every condition of the case (PSD left out): superball, contact 2-3 opens, contacts 1-2 and 3-4 stay closed.
  ASSERT_EQ(j["conditions"].size(), v.conditions.size());
  std::set<std::string> names;
  for (const auto& c : j["conditions"]) {
    for (const char* key : {"kind", "about", "exact", "asymptotic", "asymptotic_verdict"}) EXPECT_TRUE(c.contains(key)) << key;
    names.insert(c["kind"].get<std::string>() + " " + c["about"].get<std::string>());
  }
  EXPECT_EQ(names, (std::set<std::string>{"superball U1 > a", "evolution 2-3", "contact 1-2", "contact 3-4"}));
  for (const verify::VerifiedCondition& c : v.conditions) {
    EXPECT_TRUE(contains(text, c.name())) << c.name();
    EXPECT_TRUE(contains(text, c.exact_text)) << c.exact_text;
  }
  for (const auto& e : j["epsilons"])
    for (const char* stage : {"all", "drawn", "boundary"}) {
      EXPECT_EQ(e[stage]["conditions"].size(), v.conditions.size());
      EXPECT_EQ(e[stage]["exact"]["agree"], e[stage]["exact"]["total"]);
    }
}

TEST(VerificationReport, DisagreementComment) {
  const verify::Verification& v = case21();
  verify::Disagreement d;
  d.epsilon_index = 1;
  d.near = true;
  d.point = {{"m1", cln::cl_RA(1) / 3}, {"a", 1}};
  d.actual_case = "1";
  d.quantity = "U1 - a = 3/7";
  d.truth = false;
  d.exact = false;
  d.asymptotic = true;
  const std::string text = describe(v, d);
  EXPECT_EQ(text.rfind("superball verify: case 2.1 (", 0), 0u) << text;
  EXPECT_TRUE(contains(text, "eps = 1e-3, a point near a boundary\n")) << text;
  EXPECT_TRUE(contains(text, "the asymptotic conditions hold (disagree)")) << text;
  EXPECT_TRUE(contains(text, "point: m1 = 1/3, a = 1")) << text;
  EXPECT_FALSE(contains(text, "#"));  // a scene file's comment adds its own
}

verify::ExploreOptions quick() {
  verify::ExploreOptions o;
  o.starts = 6;
  o.evaluations = 300;
  return o;
}

TEST(ExploreReport, WitnessOfCase1Alpha2) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  const verify::ExploreResult r = verify::explore_case(d, named("1"), quick());
  ASSERT_EQ(r.reach, verify::Reach::Yes) << to_text(r);
  EXPECT_EQ(cell_text(r).rfind("yes U₁⁺/a = ", 0), 0u) << cell_text(r);
  const std::string text = to_text(r);
  EXPECT_EQ(text.rfind("pattern α₂, case 1 (closed contacts: ", 0), 0u) << text;
  EXPECT_TRUE(contains(text, "  verdict: yes: ")) << text;
  EXPECT_TRUE(contains(text, "  witness: ")) << text;
  const nlohmann::ordered_json j = to_json(r);
  for (const char* key : {"pattern", "case", "closed_contacts", "reach", "box", "seed", "witness", "U1", "ratio", "ratio_decimal", "stats"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["pattern"], "alpha2");
  EXPECT_EQ(j["reach"], "yes");
  EXPECT_EQ(j["ratio"], verify::to_string(r.ratio));
  // The witness file reads back to the witness scene.
  const Scene scene = parse_scene(witness_file(r, "superball explore --alphas 2 --case 1"), "witness.toml");
  EXPECT_EQ(write_scene(scene), write_scene(*r.scene));
  const RenderedCell cell = render(r);
  EXPECT_EQ(cell.text, cell_text(r));
  EXPECT_EQ(cell.json, j);
}

TEST(ExploreReport, ProofOfCase1Alpha1Alpha6) {
  const Deriver d(Pattern::paper({1, 6}), Obstacle::Infinite);
  const verify::ExploreResult r = verify::explore_case(d, named("1"), quick());
  ASSERT_EQ(r.reach, verify::Reach::Impossible);
  EXPECT_EQ(cell_text(r), "no (proved)");
  EXPECT_TRUE(contains(to_text(r), "  clash of the exact conditions:\n")) << to_text(r);
  const nlohmann::ordered_json j = to_json(r);
  EXPECT_EQ(j["pattern"], "alpha1,alpha6");
  ASSERT_TRUE(j.contains("clash"));
  for (const char* key : {"superball", "conditions", "identity"}) EXPECT_TRUE(j["clash"].contains(key)) << key;
  EXPECT_EQ(j.contains("witness"), !r.witness.empty());
  EXPECT_THROW(witness_file(verify::ExploreResult{}, "x"), std::invalid_argument);  // no witness, no file
}

TEST(ExploreReport, TableFromCellsIsTheTable) {
  verify::PatternTable t;
  t.options = quick();
  t.patterns = {{2}, {1, 6}};
  t.cases = {"1"};
  const Deriver two(Pattern::paper({2}), Obstacle::Infinite), one_six(Pattern::paper({1, 6}), Obstacle::Infinite);
  t.cells = {{verify::explore_case(two, named("1"), t.options)}, {verify::explore_case(one_six, named("1"), t.options)}};
  const std::vector<std::vector<RenderedCell>> cells = {{render(t.cells[0][0])}, {render(t.cells[1][0])}};
  EXPECT_EQ(to_text(t), to_text(t, cells));
  EXPECT_EQ(to_json(t), to_json(t, cells));
  const std::string text = to_text(t);
  EXPECT_EQ(text.rfind("| pattern | case 1 |\n|---|---|\n| α₂ | yes U₁⁺/a = ", 0), 0u) << text;
  EXPECT_TRUE(contains(text, "\n| α₁, α₆ | no (proved) |\n")) << text;
  const nlohmann::ordered_json j = to_json(t);
  EXPECT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["rows"][1]["alphas"], nlohmann::ordered_json({1, 6}));
  EXPECT_EQ(j["rows"][1]["cells"][0]["reach"], "no (proved)");
}

TEST(AuditReport, EveryPrintedConditionAndClaim) {
  verify::AuditOptions o;
  o.samples = 200;
  const PrintedConditions& data = PrintedConditions::paper();
  const verify::Audit a = verify::audit_paper(data, o);
  const std::string text = to_text(a);
  EXPECT_EQ(text.rfind("superball audit: the paper's printed conditions against the derivation\n", 0), 0u);
  EXPECT_TRUE(contains(text, "\nsummary: ")) << text;
  const nlohmann::ordered_json j = audit_json(a);
  for (const char* key : {"epsilon", "samples", "seed", "conditions", "claims"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["epsilon"], "1/1000");
  ASSERT_EQ(j["conditions"].size(), data.conditions.size());
  ASSERT_EQ(j["claims"].size(), data.claims.size());
  for (std::size_t k = 0; k < a.conditions.size(); ++k) {
    const verify::ConditionAudit& c = a.conditions[k];
    EXPECT_TRUE(contains(text, "§" + c.printed.section + " case " + c.printed.case_name + ", " + c.printed.kind + " " + c.printed.about)) << k;
    EXPECT_EQ(j["conditions"][k]["verdict"], verify::to_string(c.agreement));
    EXPECT_EQ(j["conditions"][k]["derived_exact"], c.exact.text);
  }
  for (const verify::ClaimAudit& c : a.claims) EXPECT_TRUE(contains(text, "claim (§" + c.claim.section + "): \"" + c.claim.text + "\"\n"));
}

TEST(OverlayReport, K34Alpha2Plane) {
  const Scene scene = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml");
  numeric::MapSettings settings;
  settings.threads = 1;
  const numeric::Map m = numeric::map(scene, {Parameter::parse("K.3-4", scene), 0, 20, 9}, {Parameter::parse("alpha.2", scene), -150, 0, 9}, settings);
  const verify::Overlay o = verify::overlay(scene, m);
  ASSERT_TRUE(o.agrees());
  const std::string text = to_text(o, m);
  EXPECT_EQ(text.rfind("overlay: the derived conditions of case", 0), 0u) << text;
  EXPECT_TRUE(contains(text, "): agree\n")) << text;
  EXPECT_FALSE(contains(text, "disagreement at")) << text;
  const nlohmann::ordered_json j = to_json(o, m);
  for (const char* key : {"cases", "conditions", "agrees", "largest_distance_in_steps", "largest_allowed_in_steps", "zeros", "matches"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["agrees"], true);
  ASSERT_EQ(j["zeros"].size(), o.zeros.size());
  ASSERT_EQ(j["matches"].size(), o.matches.size());
  for (std::size_t k = 0; k < o.zeros.size(); ++k) {
    const auto [x, y] = verify::position(m, o.zeros[k]);
    EXPECT_EQ(j["zeros"][k]["x"], cln::double_approx(x));
    EXPECT_EQ(j["zeros"][k]["y"], cln::double_approx(y));
    EXPECT_EQ(j["zeros"][k]["condition"], o.zeros[k].condition());
    // The zero lies on its grid line: one coordinate is the grid value.
    const double fixed = o.zeros[k].along_x ? cln::double_approx(y) : cln::double_approx(x);
    const numeric::Axis& axis = o.zeros[k].along_x ? m.y : m.x;
    const int index = o.zeros[k].along_x ? o.zeros[k].j : o.zeros[k].i;
    EXPECT_EQ(fixed, cln::double_approx(axis.values()[static_cast<std::size_t>(index)]));
  }
}

}  // namespace
}  // namespace superball::present
