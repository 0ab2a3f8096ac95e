// The audit of the paper's printed conditions: known verdicts (the case-1
// formulas are identical, the case-3.2 superball condition is not), every
// "different" verdict comes with a point where the printed condition and the
// exact solution disagree while the derived exact condition agrees, and the
// claims in words are settled as the hand derivation says.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "superball/present/audit.hpp"
#include "superball/verify/audit.hpp"

namespace superball::verify {
namespace {

const Audit& paper_audit() {
  static const Audit a = [] {
    AuditOptions o;
    o.samples = 3000;
    return audit_paper(PrintedConditions::paper(), o);
  }();
  return a;
}

const ConditionAudit& find(const std::string& section, const std::string& kind, const std::string& about) {
  for (const ConditionAudit& c : paper_audit().conditions)
    if (c.printed.section == section && c.printed.kind == kind && c.printed.about == about) return c;
  throw std::runtime_error("no audited condition " + section + " " + kind + " " + about);
}

TEST(Audit, Case1FormulasAreIdentical) {
  EXPECT_EQ(find("4.1", "superball", "U1 > a").agreement, Agreement::IdenticalExact);
  EXPECT_EQ(find("4.1", "evolution", "1-2").agreement, Agreement::IdenticalExact);
  EXPECT_EQ(find("4.1", "velocity", "U1").agreement, Agreement::IdenticalExact);
  EXPECT_EQ(find("4.1", "contact", "3-4").agreement, Agreement::IdenticalAsymptotic);
  EXPECT_EQ(find("4.2", "superball", "U1 > a").agreement, Agreement::IdenticalExact);
}

TEST(Audit, DifferentConditionsComeWithAWitness) {
  int different = 0;
  for (const ConditionAudit& c : paper_audit().conditions) {
    if (c.agreement != Agreement::Different) continue;
    ++different;
    SCOPED_TRACE(c.printed.section + " " + c.printed.kind + " " + c.printed.about);
    ASSERT_TRUE(c.witness.has_value());
    EXPECT_NE(c.witness->printed, c.witness->numeric);
    EXPECT_EQ(c.witness->derived_exact, c.witness->numeric);
    EXPECT_FALSE(c.witness->point.empty());
  }
  EXPECT_GT(different, 0);
  EXPECT_EQ(find("4.3", "superball", "U1 > a").agreement, Agreement::Different);
}

TEST(Audit, Claims) {
  ASSERT_EQ(paper_audit().claims.size(), 3u);
  for (const ClaimAudit& c : paper_audit().claims) {
    SCOPED_TRACE(c.claim.id);
    EXPECT_TRUE(c.supported) << c.verdict;
    if (c.claim.claim == "superball impossible") {
      EXPECT_FALSE(c.certificate.empty());
      EXPECT_EQ(c.hits, 0);
    } else {
      ASSERT_TRUE(c.example.has_value());
      EXPECT_EQ(c.example->actual_case, c.claim.case_name);
    }
  }
}

TEST(Audit, Reproducible) {
  AuditOptions o;
  o.samples = 200;
  o.seed = 5;
  EXPECT_EQ(present::to_text(audit_paper(PrintedConditions::paper(), o)), present::to_text(audit_paper(PrintedConditions::paper(), o)));
}

TEST(Audit, BadDataIsReported) {
  const std::string unknown_symbol =
      "[[condition]]\nsection = \"x\"\ncase = \"1\"\nalphas = [2]\nkind = \"superball\"\nabout = \"U1 > a\"\nprinted = \"\"\n"
      "lhs = \"-alpha9\"\nrelation = \">\"\nrhs = \"0\"\nwords = \"\"\n";
  const PrintedConditions data = PrintedConditions::parse(unknown_symbol, "test");
  try {
    audit_paper(data);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("audit_paper(): ", 0), 0u) << e.what();
  }
  EXPECT_THROW(PrintedConditions::parse("[[condition]]\nsection = \"x\"\n", "test"), std::invalid_argument);
  EXPECT_THROW(PrintedConditions::parse("[other]\n", "test"), std::invalid_argument);
}

}  // namespace
}  // namespace superball::verify
