// Pairs "i-j", contact sets (evolution cases) and Scene::find.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "superball/cases/model.hpp"

namespace superball {
namespace {

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Pair, ParsesAndNamesRoundTrip) {
  for (int i = 1; i <= 12; ++i)
    for (int j = i + 1; j <= 13; ++j) {
      const Pair p = Pair::parse(std::to_string(i) + "-" + std::to_string(j));
      EXPECT_EQ(p.i, i);
      EXPECT_EQ(p.j, j);
      EXPECT_EQ(p.name(), std::to_string(i) + "-" + std::to_string(j));
      EXPECT_EQ(Pair::parse(p.name()), p);
      EXPECT_EQ(p.adjacent(), j == i + 1);
    }
}

TEST(Pair, OrderIsThePapersOrder) {
  // Rows of M in the paper: 12, 13, 14, 23, 24, 34.
  std::vector<Pair> pairs = {Pair::parse("3-4"), Pair::parse("1-4"), Pair::parse("2-3"),
                             Pair::parse("1-2"), Pair::parse("2-4"), Pair::parse("1-3")};
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::string> names;
  for (const auto& p : pairs) names.push_back(p.name());
  EXPECT_EQ(names, (std::vector<std::string>{"1-2", "1-3", "1-4", "2-3", "2-4", "3-4"}));
  EXPECT_FALSE(Pair::parse("1-2") < Pair::parse("1-2"));
  EXPECT_NE(Pair::parse("1-2"), Pair::parse("1-3"));
}

class PairBad : public ::testing::TestWithParam<const char*> {};

TEST_P(PairBad, IsRejectedWithTheFunctionPrefix) {
  const std::string text = GetParam();
  const std::string what = error_of([&] { Pair::parse(text); });
  ASSERT_FALSE(what.empty()) << "'" << text << "' was accepted";
  EXPECT_EQ(what.rfind("Pair::parse(): ", 0), 0u) << what;
  EXPECT_NE(what.find("'" + text + "'"), std::string::npos) << what;
}

INSTANTIATE_TEST_SUITE_P(Spellings, PairBad,
                         ::testing::Values("", "1", "12", "2-1", "1-1", "0-1", "0-0", "-2", "1-", "-", "a-b", "1-b",
                                           "1-2-3", " 1-2", "1 -2", "1-2 ", "+1-2", "1--2", "1.0-2",
                                           "1234567890-1234567891"));

TEST(Pair, ReasonForOrder) {
  EXPECT_NE(error_of([] { Pair::parse("2-1"); }).find("1 <= i < j"), std::string::npos);
}

TEST(ContactSet, ParsesTheClosedContacts) {
  const ContactSet s = ContactSet::parse("2-3,3-4", 4);
  EXPECT_EQ(s.bodies(), 4);
  EXPECT_EQ(s.contacts(), 3);
  EXPECT_FALSE(s.closed(0));
  EXPECT_TRUE(s.closed(1));
  EXPECT_TRUE(s.closed(2));
  EXPECT_EQ(s.closed_names(), (std::vector<std::string>{"2-3", "3-4"}));
  EXPECT_EQ(s.to_string(), "{2-3,3-4}");
  // Order of listing does not matter.
  EXPECT_EQ(ContactSet::parse("3-4,2-3", 4), s);
}

TEST(ContactSet, EmptySpellings) {
  for (const char* text : {"", "none", "{}"}) {
    const ContactSet s = ContactSet::parse(text, 5);
    EXPECT_EQ(s, ContactSet(5)) << text;
    EXPECT_EQ(s.to_string(), "{}");
    EXPECT_TRUE(s.closed_names().empty());
  }
}

TEST(ContactSet, SetsOfDifferentSizesDiffer) {
  EXPECT_NE(ContactSet(4), ContactSet(5));
  EXPECT_EQ(ContactSet(4).contacts(), 3);
  EXPECT_EQ(ContactSet(2).contacts(), 1);
}

TEST(ContactSet, ManyBodiesEachContactIsItsOwnBit) {
  // Past 65 bodies the set holds its contacts in more words than one: every
  // contact, on both sides of each word's edge, is set and cleared alone.
  for (int n : {64, 65, 66, 129, 130, 200}) {
    ContactSet all(n);
    for (int c = 0; c < n - 1; ++c) {
      ContactSet one(n);
      one.set_closed(c, true);
      EXPECT_EQ(one.closed_names(), (std::vector<std::string>{Pair{c + 1, c + 2}.name()})) << "n=" << n << " c=" << c;
      EXPECT_EQ(ContactSet::parse(one.to_string().substr(1, one.to_string().size() - 2), n), one);
      EXPECT_NE(one, ContactSet(n));
      one.set_closed(c, false);
      EXPECT_EQ(one, ContactSet(n)) << "n=" << n << " c=" << c;
      all.set_closed(c, true);
    }
    EXPECT_EQ(static_cast<int>(all.closed_names().size()), n - 1);
    EXPECT_NE(all, ContactSet(n + 1));
  }
}

TEST(ContactSet, MaskRoundTrip) {
  for (int n = 2; n <= 7; ++n)
    for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << (n - 1)); ++mask) {
      const ContactSet s = ContactSet::from_mask(mask, n);
      std::string list;
      for (const auto& name : s.closed_names()) list += (list.empty() ? "" : ",") + name;
      EXPECT_EQ(ContactSet::parse(list, n), s) << "n=" << n << " mask=" << mask;
      for (int c = 0; c < n - 1; ++c) EXPECT_EQ(s.closed(c), ((mask >> c) & 1u) != 0);
      EXPECT_EQ(static_cast<std::uint64_t>(s.closed_names().size()),
                static_cast<std::uint64_t>(__builtin_popcountll(mask)));
    }
  // Bits beyond the contacts are ignored; 65 bodies (64 contacts) is the limit.
  EXPECT_EQ(ContactSet::from_mask(0xF0, 4), ContactSet(4));
  EXPECT_EQ(ContactSet::from_mask(~std::uint64_t{0}, 65).closed_names().size(), 64u);
  EXPECT_EQ(error_of([] { ContactSet::from_mask(1, 66); }).rfind("ContactSet::from_mask(): ", 0), 0u);
}

class ContactSetBad : public ::testing::TestWithParam<const char*> {};

TEST_P(ContactSetBad, IsRejectedWithTheFunctionPrefix) {
  const std::string text = GetParam();
  const std::string what = error_of([&] { ContactSet::parse(text, 4); });
  ASSERT_FALSE(what.empty()) << "'" << text << "' was accepted";
  EXPECT_EQ(what.rfind("ContactSet::parse(): ", 0), 0u) << what;
}

INSTANTIATE_TEST_SUITE_P(Spellings, ContactSetBad,
                         ::testing::Values("1-3", "4-5", "2-4", "x", "1-2,", ",1-2", "1-2,,2-3", "{2-3}", "1-2;2-3",
                                           "2-1", "nothing"));

TEST(Scene, FindIsSymmetric) {
  Scene s;
  s.entries.push_back({Pair::parse("1-2"), Pair::parse("1-4"), Number::parse("-100")});
  s.entries.push_back({Pair::parse("3-4"), Pair::parse("3-4"), Number::parse("10")});
  ASSERT_NE(s.find(Pair::parse("1-4"), Pair::parse("1-2")), nullptr);
  EXPECT_EQ(s.find(Pair::parse("1-4"), Pair::parse("1-2")), s.find(Pair::parse("1-2"), Pair::parse("1-4")));
  EXPECT_EQ(s.find(Pair::parse("1-2"), Pair::parse("1-4"))->value.text, "-100");
  EXPECT_TRUE(s.find(Pair::parse("3-4"), Pair::parse("3-4"))->diagonal());
  EXPECT_EQ(s.find(Pair::parse("1-2"), Pair::parse("1-2")), nullptr);
  EXPECT_EQ(s.find(Pair::parse("1-3"), Pair::parse("1-4")), nullptr);
}

}  // namespace
}  // namespace superball
