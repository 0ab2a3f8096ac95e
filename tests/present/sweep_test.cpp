// A sweep's rows (present::write_sweep_rows()), formatted on several threads
// in blocks, read back as data: each row's value is the range's exact value
// to 10 digits, its velocities the points' (exactly, in CSV's 17 digits), its
// case the paper's name (quoted in CSV when it holds a comma), its status as
// the table and the CSV each show it; the text is the same on any number of
// threads and a part of the range starting anywhere is the same rows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/present/sweep.hpp"

namespace {

using namespace superball;

std::string rows_of(const numeric::Range& r, std::size_t first, const std::vector<numeric::SweepPoint>& points, bool csv, int threads,
                    int* pieces = nullptr) {
  std::string text;
  present::write_sweep_rows(r, first, points, csv, threads, [&](std::string_view piece) {
    text += piece;
    if (pieces) ++*pieces;
  });
  return text;
}

/// The fields of \p line split at \p sep, a CSV field in quotes kept whole without them.
std::vector<std::string> split(const std::string& line, const std::string& sep) {
  std::vector<std::string> out;
  std::string field;
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    if (sep == "," && line[k] == '"') {
      quoted = !quoted;
    } else if (!quoted && line.compare(k, sep.size(), sep) == 0) {
      out.push_back(field), field.clear();
      k += sep.size() - 1;
    } else {
      field += line[k];
    }
  }
  out.push_back(field);
  return out;
}

TEST(SweepRows, EachRowReadBackIsItsPointOnAnyThreads) {
  const Scene s = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml");
  const numeric::Range r{Parameter::parse("K.3-4", s), 20, 0, 9001};  // decreasing, nine tasks of rows
  const auto values = numeric::linspace(r.from, r.to, r.steps);
  const auto points = numeric::sweep(s, r.parameter, values, numeric::Precision::parse("double"), 2);
  for (bool csv : {true, false}) {
    int pieces = 0;
    const std::string whole = rows_of(r, 0, points, csv, 1, &pieces);
    EXPECT_EQ(pieces, 9) << "a piece a task of 1024 rows";
    const std::string sep = csv ? "," : "  ";
    std::size_t at = 0, cases = 0;
    std::string last_case;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const std::size_t eol = whole.find('\n', at);
      ASSERT_NE(eol, std::string::npos) << "row " << k;
      const auto f = split(whole.substr(at, eol - at), sep);
      at = eol + 1;
      ASSERT_EQ(f.size(), 4u + 2u + (csv ? 1u : 0u)) << whole.substr(at, 80);
      const double exact = cln::double_approx(values[k]);
      EXPECT_NEAR(std::strtod(f[0].c_str(), nullptr), exact, 1e-9 * std::max(1.0, std::abs(exact))) << f[0];
      for (std::size_t i = 0; i < 4; ++i) {
        const double w = std::strtod(f[1 + i].c_str(), nullptr), u = points[k].velocities_after[i];
        // CSV's 17 digits read back to the double; the table's 8 to within its rounding.
        EXPECT_NEAR(w, u, csv ? 0.0 : 1e-7 * std::abs(u)) << "row " << k << " U" << i + 1;
      }
      EXPECT_EQ(f[5], Vocabulary::paper().case_name(points[k].closed));
      if (csv) {
        EXPECT_EQ(f[6], "success");
      }
      cases += f[5] != last_case, last_case = f[5];
    }
    EXPECT_EQ(at, whole.size());
    EXPECT_GE(cases, 3u) << "the range crosses changes of case";
    for (int threads : {2, 3}) EXPECT_TRUE(rows_of(r, 0, points, csv, threads) == whole) << threads << " threads";
    // The rows of values 150 … 5149 alone: the same lines.
    const std::vector<numeric::SweepPoint> some(points.begin() + 150, points.begin() + 5150);
    std::size_t start = 0;
    for (int k = 0; k < 150; ++k) start = whole.find('\n', start) + 1;
    std::size_t end = start;
    for (int k = 0; k < 5000; ++k) end = whole.find('\n', end) + 1;
    EXPECT_TRUE(rows_of(r, 150, some, csv, 2) == whole.substr(start, end - start)) << (csv ? "csv" : "table");
  }
}

TEST(SweepRows, TheTableNamesAStatusOnlyWhenItIsNotSuccessAndCsvQuotesACaseWithACommaAlways) {
  const Scene s = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/chain-32.toml");
  const numeric::Range r{Parameter::parse("mass.1", s), 1, 3, 3};
  std::vector<numeric::SweepPoint> points(3);
  const numeric::Status statuses[] = {numeric::Status::Success, numeric::Status::NumericalIssue, numeric::Status::NoConvergence};
  for (std::size_t k = 0; k < 3; ++k) {
    points[k].velocities_after.assign(32, -0.5 * static_cast<double>(k));
    points[k].closed = ContactSet::parse(k == 0 ? "" : "1-2,2-3", 32);
    points[k].status = statuses[k];
  }
  const std::string csv = rows_of(r, 0, points, true, 2), table = rows_of(r, 0, points, false, 2);
  const std::string name = Vocabulary::paper().case_name(points[1].closed);
  ASSERT_NE(name.find(','), std::string::npos) << name;
  EXPECT_NE(csv.find(",\"" + name + "\",numerical-issue\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",\"" + name + "\",no-convergence\n"), std::string::npos) << csv;
  EXPECT_EQ(split(csv.substr(0, csv.find('\n')), ",").back(), "success");
  EXPECT_EQ(split(table.substr(0, table.find('\n')), "  ").back(), Vocabulary::paper().case_name(points[0].closed));
  EXPECT_NE(table.find("  " + name + "  numerical-issue\n"), std::string::npos) << table;
  EXPECT_EQ(present::sweep_header("mass.1", 32, true).substr(0, 13), "mass.1,U1,U2,");
  EXPECT_EQ(present::sweep_header("K.3-4", 4, false), "K.3-4  U1  U2  U3  U4  case\n");
  EXPECT_EQ(present::sweep_header("K.3-4", 4, true), "K.3-4,U1,U2,U3,U4,case,status\n");
}

/// The message of what \p f throws (std::invalid_argument), "" when it does not throw.
template <class F>
std::string refusal(const F& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(SweepRows, RowsReadBackAreCheckedAndEachDamageIsNamed) {
  const Scene s = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml");
  const numeric::Range r{Parameter::parse("K.3-4", s), 0, 20, 401};
  auto points = numeric::sweep(s, r.parameter, numeric::linspace(r.from, r.to, r.steps), numeric::Precision::parse("double"), 2);
  points[7].status = numeric::Status::NumericalIssue;  // one failure, as a file may hold
  for (bool csv : {true, false}) {
    const std::string rows = rows_of(r, 0, points, csv, 2);
    EXPECT_EQ(present::check_sweep_rows(rows, 4, 401, csv), 1) << (csv ? "csv" : "table");
    auto damage = [&](const std::string& text, std::size_t size = 401) { return refusal([&] { present::check_sweep_rows(text, 4, size, csv); }); };
    EXPECT_EQ(damage(rows, 400), "a damaged result (not the rows of its block)");
    EXPECT_EQ(damage(rows.substr(0, rows.size() - 1)), "a damaged result (its last line is cut)");
    const std::string sep = csv ? "," : "  ";
    EXPECT_EQ(damage(replaced(rows, sep + "2.2", sep + "9.9")), "a damaged result ('9.9' is not a case of this scene)");
    EXPECT_EQ(damage(replaced(rows, sep + "2.2", sep + "1" + sep + "1" + sep + "2.2")), "a damaged result (a row of the wrong fields)");
    EXPECT_EQ(damage(replaced(rows, "numerical-issue", "numerical_issue")), "a damaged result ('numerical_issue' is not a status)");
    if (!csv) {
      EXPECT_EQ(damage(replaced(rows, "\n", "  success\n")), "a damaged result ('success' is not a status)");
    }
  }
}

TEST(SweepRows, SwitchPointsReadBackAreCheckedAndEachDamageIsNamed) {
  const Scene s = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", s);
  const auto points = numeric::switch_points(s, k34, numeric::linspace(0, 20, 41), 64, 2);
  ASSERT_GE(points.size(), 2u);
  for (bool csv : {true, false}) {
    const std::string text = present::switch_rows("K.3-4", points, csv);
    auto damage = [&](const std::string& t, const cln::cl_RA& low = 0, const cln::cl_RA& high = 20) {
      return refusal([&] { present::check_switch_rows(t, "K.3-4", 4, low, high, csv); });
    };
    EXPECT_EQ(damage(text), "") << text;
    const std::string first = text.substr(0, text.find('\n') + 1);
    const std::string at = csv ? first.substr(0, first.find(',')) : first.substr(8, first.find("  (") - 8);
    EXPECT_NE(damage(first, 10, 20).find("a damaged result (a switch point at " + at + ", outside the values of its block (10 to 20))"), std::string::npos)
        << damage(first, 10, 20);
    EXPECT_EQ(damage(text.substr(0, text.size() - 1)), "a damaged result (its last line is cut)");
    const std::string name = Vocabulary::paper().case_name(points[0].below), other = Vocabulary::paper().case_name(points[0].above);
    const std::string same = csv ? replaced(first, "," + other, "," + name) : replaced(first, "-> case " + other + " " + points[0].above.to_string(),
                                                                                     "-> case " + name + " " + points[0].below.to_string());
    EXPECT_EQ(damage(same), "a damaged result (a switch point between a case and itself)");
    if (csv) {
      EXPECT_EQ(damage(replaced(first, "," + name, ",9.9")), "a damaged result ('9.9' is not a case of this scene)");
      EXPECT_EQ(damage(replaced(first, "," + name, "," + name + ",x")), "a damaged result (a switch point of the wrong fields)");
    } else {
      EXPECT_EQ(damage(replaced(first, "K.3-4 = ", "K.3-5 = ")), "a damaged result (a switch point of the wrong form)");
      EXPECT_EQ(damage(replaced(first, points[0].below.to_string(), "{1-2}")).rfind("a damaged result ('" + name + " {1-2}' is not a case and its contacts", 0), 0u);
    }
  }
}

}  // namespace
