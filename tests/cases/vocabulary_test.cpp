// The paper's vocabulary (n = 4): the evolution cases of §4 and the couplings
// α₁…α₇ of the matrix M of §3, checked against the paper's text.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <string>

#include "superball/cases/vocabulary.hpp"

namespace superball {
namespace {

TEST(Vocabulary, FourBodies) { EXPECT_EQ(Vocabulary::paper().bodies(), 4); }

TEST(Vocabulary, EightNamedCasesCoverEveryContactSet) {
  const Vocabulary& v = Vocabulary::paper();
  ASSERT_EQ(v.cases().size(), 8u);
  std::set<std::string> names;
  for (const auto& c : v.cases()) {
    names.insert(c.name);
    EXPECT_EQ(c.closed.bodies(), 4) << c.name;
    EXPECT_FALSE(c.description.empty()) << c.name;
  }
  EXPECT_EQ(names.size(), 8u);
  // 3 contacts: 2³ = 8 sets, each with exactly one name.
  for (std::uint64_t mask = 0; mask < 8; ++mask) {
    const ContactSet s = ContactSet::from_mask(mask, 4);
    const std::string name = v.case_name(s);
    EXPECT_EQ(names.count(name), 1u) << s.to_string() << " -> " << name;
    EXPECT_EQ(v.named_case(name).closed, s);
  }
}

TEST(Vocabulary, ThePapersSixCases) {
  // Paper §4: case 1 — ball 1 bounces, balls 2 and 3 stay on the obstacle
  // (contacts 2-3 and 3-4 closed); 2.1 — 1 and 2 together, 3 on the
  // obstacle; 2.2 — 3 on the obstacle; 3.1 — 1 and 2 together; 3.2 — 2 and 3
  // together; 3.3 — nothing closed.
  const Vocabulary& v = Vocabulary::paper();
  EXPECT_EQ(v.case_name(ContactSet::parse("2-3,3-4", 4)), "1");
  EXPECT_EQ(v.case_name(ContactSet::parse("1-2,3-4", 4)), "2.1");
  EXPECT_EQ(v.case_name(ContactSet::parse("3-4", 4)), "2.2");
  EXPECT_EQ(v.case_name(ContactSet::parse("1-2", 4)), "3.1");
  EXPECT_EQ(v.case_name(ContactSet::parse("2-3", 4)), "3.2");
  EXPECT_EQ(v.case_name(ContactSet::parse("none", 4)), "3.3");
  // The two sets the paper does not name have names of their own.
  EXPECT_EQ(v.named_case(v.case_name(ContactSet::parse("1-2,2-3", 4))).closed, ContactSet::parse("1-2,2-3", 4));
  EXPECT_EQ(v.named_case(v.case_name(ContactSet::parse("1-2,2-3,3-4", 4))).closed, ContactSet::parse("1-2,2-3,3-4", 4));
}

TEST(Vocabulary, OtherSizesAreNamedByTheirSet) {
  const Vocabulary& v = Vocabulary::paper();
  EXPECT_EQ(v.case_name(ContactSet::parse("2-3,4-5", 5)), "{2-3,4-5}");
  EXPECT_EQ(v.case_name(ContactSet(3)), "{}");
}

TEST(Vocabulary, SevenAlphasAsInTheMatrixM) {
  // M, rows and columns 12, 13, 14, 23, 24, 34 (paper §3):
  //   row 12: K12 α1 α2 . . .      row 13: α1 K13 α3 . . .
  //   row 14: α2 α3 K14 α4 α5 α7   row 23: . . α4 K23 α6 .
  //   row 24: . . α5 α6 K24 .      row 34: . . α7 . . K34
  const Vocabulary& v = Vocabulary::paper();
  ASSERT_EQ(v.alphas().size(), 7u);
  const char* expected[7][2] = {{"1-2", "1-3"}, {"1-2", "1-4"}, {"1-3", "1-4"}, {"1-4", "2-3"},
                                {"1-4", "2-4"}, {"2-3", "2-4"}, {"1-4", "3-4"}};
  for (int k = 1; k <= 7; ++k) {
    const NamedCoupling& a = v.alpha(k);
    EXPECT_EQ(a.index, k);
    const Pair p = Pair::parse(expected[k - 1][0]), q = Pair::parse(expected[k - 1][1]);
    EXPECT_TRUE((a.first == p && a.second == q) || (a.first == q && a.second == p))
        << "alpha_" << k << " = (" << a.first.name() << ", " << a.second.name() << ")";
    EXPECT_EQ(v.alpha_index(p, q), k);
    EXPECT_EQ(v.alpha_index(q, p), k);
  }
  EXPECT_FALSE(v.alpha_index(Pair::parse("1-2"), Pair::parse("3-4")).has_value());
  EXPECT_FALSE(v.alpha_index(Pair::parse("1-2"), Pair::parse("1-2")).has_value());
}

TEST(Vocabulary, UnknownNamesAreRejected) {
  const Vocabulary& v = Vocabulary::paper();
  for (int k : {0, 8, -1}) {
    try {
      v.alpha(k);
      ADD_FAILURE() << "alpha(" << k << ") accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("Vocabulary::alpha(): ", 0), 0u) << e.what();
    }
  }
  try {
    v.named_case("4");
    ADD_FAILURE() << "named_case(\"4\") accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("Vocabulary::named_case(): ", 0), 0u) << what;
    EXPECT_NE(what.find("3.3"), std::string::npos) << "the message lists the cases: " << what;
  }
}

TEST(Vocabulary, ParseRejectsInconsistentFiles) {
  const char* bad[] = {
      "bodies = 1\n",
      "this is not toml\n",
      "bodies = 4\n[[case]]\nname = \"a\"\nclosed = [\"1-3\"]\n",
      "bodies = 4\n[[case]]\nname = \"a\"\nclosed = []\n[[case]]\nname = \"b\"\nclosed = []\n",
      "bodies = 4\n[[case]]\nname = \"a\"\nclosed = []\n[[case]]\nname = \"a\"\nclosed = [\"1-2\"]\n",
      "bodies = 4\n[[alpha]]\nindex = 2\npairs = [\"1-2\", \"1-4\"]\n",
      "bodies = 4\n[[alpha]]\nindex = 1\npairs = [\"1-2\"]\n",
  };
  for (const char* text : bad) {
    try {
      Vocabulary::parse(text, "test.toml");
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("Vocabulary: test.toml: ", 0), 0u) << e.what();
    }
  }
}

// Malformed entries ([[case]] or [[alpha]] that are not tables, pair names
// that are not pairs) must give the documented std::runtime_error
// ("Vocabulary: ..."), not a crash and not another exception type.  Each text
// is parsed in a child process so that a crash fails this test only.
class VocabularyMalformed : public ::testing::TestWithParam<const char*> {};

TEST_P(VocabularyMalformed, ThrowsTheDocumentedError) {
  const std::string text = GetParam();
  EXPECT_EXIT(
      {
        int code = 1;
        try {
          Vocabulary::parse(text, "test.toml");
          code = 2;
        } catch (const std::runtime_error& e) {
          code = std::string(e.what()).rfind("Vocabulary: test.toml: ", 0) == 0 ? 0 : 3;
        } catch (...) {
          code = 4;
        }
        std::exit(code);
      },
      ::testing::ExitedWithCode(0), "")
      << "exit 2: accepted, 3: wrong message, 4: another exception type, a signal: a crash.  Text:\n"
      << text;
}

INSTANTIATE_TEST_SUITE_P(Texts, VocabularyMalformed,
                         ::testing::Values("bodies = 4\ncase = [1]\n", "bodies = 4\nalpha = [\"1-2\"]\n",
                                           "bodies = 4\n[[case]]\nname = \"x\"\nclosed = [\"x\"]\n",
                                           "bodies = 4\n[[alpha]]\nindex = 1\npairs = [\"1-2\", \"y\"]\n"));

TEST(Vocabulary, ParseReadsAGoodFile) {
  const Vocabulary v = Vocabulary::parse(
      "bodies = 3\n[[case]]\nname = \"x\"\nclosed = [\"2-3\"]\ndescription = \"d\"\n"
      "[[alpha]]\nindex = 1\npairs = [\"1-2\", \"2-3\"]\n",
      "small.toml");
  EXPECT_EQ(v.bodies(), 3);
  ASSERT_EQ(v.cases().size(), 1u);
  EXPECT_EQ(v.case_name(ContactSet::parse("2-3", 3)), "x");
  EXPECT_EQ(v.case_name(ContactSet::parse("1-2", 3)), "{1-2}");
  EXPECT_EQ(v.alpha_index(Pair::parse("2-3"), Pair::parse("1-2")), 1);
}

}  // namespace
}  // namespace superball
