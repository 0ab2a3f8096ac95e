// The rules of verify's options, each in its type: VerifyOptions::check(),
// AuditOptions::check(), ExploreOptions::check(), ReproduceOptions::check(), and the text forms read by
// parse_epsilon(), parse_epsilons() and parse_box().  The command and the
// Python module add no rule of their own (tests/python/test_same_refusals.py).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "superball/cases/error.hpp"
#include "superball/verify/audit.hpp"
#include "superball/verify/explore.hpp"
#include "superball/verify/reproduce.hpp"
#include "superball/verify/verification.hpp"

#include "support/refusal.hpp"

namespace superball::verify {
namespace {

using superball::test::refusal;

TEST(Options, EpsilonIsReadExactlyAndChecked) {
  EXPECT_EQ(parse_epsilon("epsilon", "1e-3"), cln::cl_RA(1) / 1000);
  EXPECT_EQ(parse_epsilon("epsilon", "0.001"), cln::cl_RA(1) / 1000);
  EXPECT_EQ(parse_epsilons("1/100,1e-4").size(), 2u);
  EXPECT_EQ(refusal([] { parse_epsilons(""); }), "epsilons: no value (e.g. 1e-2,1e-4)");
  EXPECT_EQ(refusal([] { parse_epsilons("1e-2,abc"); }).rfind("epsilons: 'abc': ", 0), 0u);
  EXPECT_EQ(refusal([] { parse_epsilon("epsilon", "nan"); }).rfind("epsilon: 'nan': ", 0), 0u);
  VerifyOptions v;
  EXPECT_EQ(refusal([&] { v.check(); }), "");
  for (const char* bad : {"0", "1", "-1", "2", "3/2"}) {
    v.epsilons = {parse_epsilon("epsilons", bad)};
    EXPECT_EQ(refusal([&] { v.check(); }), std::string("epsilons must be in (0, 1), got ") + bad);
  }
  v.epsilons.clear();
  EXPECT_EQ(refusal([&] { v.check(); }), "epsilons: no value (e.g. 1e-2,1e-4)");
  AuditOptions a;
  EXPECT_EQ(refusal([&] { a.check(); }), "");
  a.epsilon = 2;
  EXPECT_EQ(refusal([&] { a.check(); }), "epsilon must be in (0, 1), got 2");
}

TEST(Options, CountsAndThreads) {
  VerifyOptions v;
  v.samples = 0;
  EXPECT_EQ(refusal([&] { v.check(); }), "samples must be a whole number from 1 to 100000000, got 0");
  v.samples = 1;
  v.boundary_pairs = -1;
  EXPECT_EQ(refusal([&] { v.check(); }), "boundary_pairs must be a whole number from 0 to 1000000, got -1");
  v.boundary_pairs = 0;
  v.threads = -1;
  EXPECT_EQ(refusal([&] { v.check(); }), "threads must be a whole number from 0 (all cores) to 1024, got -1");
  v.threads = 0;
  EXPECT_EQ(refusal([&] { v.check(); }), "");
  AuditOptions a;
  a.samples = max_audit_samples + 1;
  EXPECT_EQ(refusal([&] { a.check(); }), "samples must be a whole number from 1 to 10000000, got 10000001");
  ExploreOptions e;
  EXPECT_EQ(refusal([&] { e.check(); }), "");
  e.starts = 0;
  EXPECT_EQ(refusal([&] { e.check(); }), "starts must be a whole number from 1 to 100000, got 0");
  e.starts = 1;
  e.evaluations = 9;
  EXPECT_EQ(refusal([&] { e.check(); }), "evaluations must be a whole number from 10 to 10000000, got 9");
}

TEST(Options, TheReproductionChecksEachRunsCountsUnderItsOwnName) {
  ReproduceOptions r;
  EXPECT_EQ(refusal([&] { r.check(); }), "");
  EXPECT_EQ(r.audit().samples, AuditOptions{}.samples);
  EXPECT_EQ(r.verification().samples, VerifyOptions{}.samples);
  EXPECT_EQ(r.exploration().starts, ExploreOptions{}.starts);
  r.samples = 0;
  EXPECT_EQ(refusal([&] { r.check(); }), "samples must be a whole number from 1 to 10000000, got 0");
  r.samples = max_audit_samples;
  r.verify_samples = max_verify_samples + 1;
  EXPECT_EQ(refusal([&] { r.check(); }), "verify_samples must be a whole number from 1 to 100000000, got 100000001");
  r.verify_samples = 1;
  r.explore_starts = -5;
  EXPECT_EQ(refusal([&] { r.check(); }), "explore_starts must be a whole number from 1 to 100000, got -5");
  r.explore_starts = max_starts;
  r.threads = 1025;
  EXPECT_EQ(refusal([&] { r.check(); }), "threads must be a whole number from 0 (all cores) to 1024, got 1025");
  r.threads = 3;
  EXPECT_EQ(refusal([&] { r.check(); }), "");
  // Each run receives exactly what the reproduction was given, and its own check agrees.
  EXPECT_EQ(r.audit().samples, max_audit_samples);
  EXPECT_EQ(r.verification().samples, 1);
  EXPECT_EQ(r.verification().threads, 3);
  EXPECT_EQ(r.exploration().starts, max_starts);
  EXPECT_EQ(refusal([&] { r.audit().check(); }), "");
  EXPECT_EQ(refusal([&] { r.verification().check(); }), "");
  EXPECT_EQ(refusal([&] { r.exploration().check(); }), "");
}

TEST(Options, TheBoxAsText) {
  EXPECT_EQ(parse_box("1e-3:1e3"), std::make_pair(1e-3, 1e3));
  for (const char* bad : {"wide", "1:", ":1", "1:2:3", " 1:2", "1;2"})
    EXPECT_EQ(refusal([&] { parse_box(bad); }), std::string("box: '") + bad + "' is not LOW:HIGH (e.g. 1e-3:1e3)") << bad;
}

}  // namespace
}  // namespace superball::verify
