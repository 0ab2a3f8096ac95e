// `superball reproduce`: recompute the paper's numbers and write a report
// (report.md, report.tex, figures as PNG and SVG drawn by gnuplot).
#include <sys/stat.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "document.hpp"
#include "gnuplot.hpp"
#include "map.hpp"
#include "present.hpp"
#include "superball/cases/printed.hpp"
#include "superball/cases/printed_conditions.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/drop_limit.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/present/explore.hpp"
#include "superball/verify/audit.hpp"
#include "superball/verify/explore.hpp"
#include "superball/verify/overlay.hpp"
#include "superball/verify/reproduce.hpp"
#include "superball/verify/verification.hpp"

#ifndef SUPERBALL_SCENES_DIR
#define SUPERBALL_SCENES_DIR "cases/scenes"
#endif

namespace superball::cli {
namespace {

const numeric::Precision exact_precision{numeric::Precision::Kind::Exact, 0};
const numeric::Precision double_precision{numeric::Precision::Kind::Double, 0};

/// Half a unit of the last digit printed in \p printed ("3.3069" -> 5e-5).
double printed_half_ulp(const Number& printed) {
  const auto dot = printed.text.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(printed.text.size() - dot - 1);
  return 0.5 * std::pow(10.0, -decimals);
}

/// Whether \p computed rounds to the printed digits of \p printed.
bool matches_printed(double computed, const Number& printed) {
  return std::fabs(computed - printed.approx()) <= printed_half_ulp(printed) * (1 + 1e-12);
}

std::string fixed(double x, int decimals) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(decimals);
  os << x;
  return os.str();
}

std::string decimal(const cln::cl_RA& x, int digits) { return numeric::to_decimal(x, digits); }
std::string decimal(double x, int digits) { return numeric::to_string(x, digits); }

/// A report run: where the scenes are, where the report goes, how much each of its runs computes.
struct Run {
  std::string scenes, out;
  verify::ReproduceOptions options;
  Scene scene(const std::string& file) const { return load_scene(scenes + "/" + file); }
};

/// The values of a sweep and its curves U_i(parameter).
struct Curves {
  std::vector<double> x;
  std::vector<std::vector<double>> u;  // u[i][k]: body i+1 at value k
};

Curves curves_of(const std::vector<numeric::SweepPoint>& points) {
  Curves c;
  for (const auto& p : points) {
    c.x.push_back(cln::double_approx(p.value));
    if (c.u.size() < p.velocities_after.size()) c.u.resize(p.velocities_after.size());
    for (std::size_t i = 0; i < p.velocities_after.size(); ++i) c.u[i].push_back(p.velocities_after[i]);
  }
  return c;
}

/// Eq. (16): both readings of §4.4, exact, and every single-alpha placement.
void eq16(const Run& run, Document& doc) {
  const PrintedNumbers& printed = PrintedNumbers::paper();
  const char* files[] = {"paper-4.4-as-printed.toml", "paper-4.4-alpha2.toml"};
  std::vector<Presented> runs;
  for (const char* f : files) runs.push_back(solve_scene(run.scene(f), exact_precision));
  doc.heading("Eq. (16): velocities after the collision, §" + printed.eq16_section);
  doc.paragraph(
      "Exact solves (CLN rationals) of two readings of §4.4: the coupling -100 on alpha_4 as printed "
      "(`paper-4.4-as-printed.toml`), and on alpha_2 (`paper-4.4-alpha2.toml`).  A velocity matches when it rounds to "
      "the paper's printed digits.");
  std::vector<std::vector<Cell>> rows;
  std::vector<int> matches(runs.size(), 0);
  for (std::size_t i = 0; i < printed.eq16_velocities.size(); ++i) {
    const Number& p = printed.eq16_velocities[i];
    std::vector<Cell> row{"U" + std::to_string(i + 1) + "+ (m/s)", p.text};
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const bool ok = matches_printed(runs[r].after[i], p);
      matches[r] += ok;
      row.push_back(decimal(runs[r].after[i], 8));
      row.push_back(ok ? "yes" : "**no**");
    }
    rows.push_back(row);
  }
  std::vector<Cell> case_row{"case", printed.eq16_case};
  for (const auto& r : runs) {
    case_row.push_back(r.case_name);
    case_row.push_back(r.case_name == printed.eq16_case ? "yes" : "**no**");
  }
  rows.push_back(case_row);
  doc.table({"", "paper", "alpha_4 = -100 (as printed)", "match", "alpha_2 = -100", "match"}, rows);
  std::vector<std::string> notes;
  for (std::size_t r = 0; r < runs.size(); ++r)
    notes.push_back("`" + runs[r].origin + "`: " + std::to_string(matches[r]) + " of " +
                    std::to_string(printed.eq16_velocities.size()) + " velocities match; exact U1+ = " + runs[r].after_text[0] +
                    " m/s; superball: " + (runs[r].superball ? "yes" : "no") + ".");
  doc.bullets(notes);

  doc.paragraph("Which single coupling carries the -100?  Every alpha_k = +-100 in place of alpha_4 = -100, the rest as "
                "printed, exact solves:");
  rows.clear();
  const Scene printed_scene = run.scene(files[0]);
  for (const auto& alpha : Vocabulary::paper().alphas())
    for (const char* value : {"-100", "100"}) {
      Scene scene = printed_scene;
      scene.entries.erase(std::remove_if(scene.entries.begin(), scene.entries.end(), [](const MatrixEntry& e) { return !e.diagonal(); }),
                          scene.entries.end());
      Parameter::parse("alpha." + std::to_string(alpha.index), scene).set(scene, Number::parse(value));
      std::vector<Cell> row{"alpha_" + std::to_string(alpha.index), value};
      try {
        const Presented r = solve_scene(scene, exact_precision);
        int m = 0;
        for (std::size_t i = 0; i < printed.eq16_velocities.size(); ++i) m += matches_printed(r.after[i], printed.eq16_velocities[i]);
        row.insert(row.end(), {"yes", std::to_string(m) + " of " + std::to_string(printed.eq16_velocities.size()), r.case_name});
      } catch (const InputError&) {
        row.insert(row.end(), {"no", "-", "-"});
      }
      rows.push_back(row);
    }
  doc.table({"coupling", "value", "M positive semi-definite", "velocities matching eq. (16)", "case"}, rows);
}

/// Fig. 5: U1+ against alpha_2 (alpha_5 = 0) and against alpha_5 (alpha_2 = 0).
void fig5(const Run& run, Document& doc) {
  doc.heading("Fig. 5: U1+ against alpha_2 and against alpha_5, §4.3");
  Plot plot{"Fig. 5: velocity of ball 1 after the collision", "coupling alpha_k (kg)", "U_1^+ (m/s)", false, false,
            "inside bottom center box opaque spacing 1.4", {}, {}};
  std::vector<std::vector<Cell>> rows;
  double a = 0;
  for (const auto& [file, key, pair_a, pair_b] :
       {std::tuple<const char*, const char*, const char*, const char*>{"paper-fig5-alpha2.toml", "alpha.2", "K.1-2", "K.1-4"},
        {"paper-fig5-alpha5.toml", "alpha.5", "K.1-4", "K.2-4"}}) {
    const Scene scene = run.scene(file);
    const Parameter p = Parameter::parse(key, scene);
    // The range where M stays positive semi-definite: alpha^2 <= K_a K_b, kept 0.1 % inside.
    double ka = 0, kb = 0;
    for (const auto& e : scene.entries)
      if (e.diagonal()) {
        if ("K." + e.first.name() == pair_a) ka = e.value.approx();
        if ("K." + e.first.name() == pair_b) kb = e.value.approx();
      }
    const cln::cl_RA limit = cln::rational(cln::floor1(cln::rational(cln::cl_float(std::sqrt(ka * kb) * 0.999)) * 10)) / 10;
    const auto values = numeric::linspace(-limit, limit, 401);
    const auto points = numeric::sweep(scene, p, values, double_precision);
    const Curves c = curves_of(points);
    const auto exact = numeric::ExactScene::from(scene);
    a = std::sqrt(cln::double_approx(*exact.a_squared));
    plot.series.push_back({"U_1^+ against " + std::string(key == std::string("alpha.2") ? "alpha_2 (alpha_5 = 0)" : "alpha_5 (alpha_2 = 0)"),
                           c.x, c.u[0], false});
    const numeric::Label superball = [](const numeric::ExactPoint& e) {
      return e.solution.velocities_after[0] > -e.problem.u[0] ? std::string("U1+ > a") : std::string("U1+ <= a");
    };
    // The paper's stack falls (U1- = -a < 0), so U1+ > -U1- is U1+ > |U1-|, the verdict a certified solve proves.
    const numeric::ProvenLabel proven = [](const numeric::ProvenPoint& q) -> std::optional<std::string> {
      if (!q.superball) return std::nullopt;
      return *q.superball ? std::string("U1+ > a") : std::string("U1+ <= a");
    };
    for (const auto& change : numeric::label_changes(scene, p, values, superball, 64, 1, proven)) {
      const cln::cl_RA mid = (change.low + change.high) / 2;
      rows.push_back({"`" + std::string(file) + "`", key, decimal(mid, 6), change.below + " -> " + change.above});
      plot.markers.push_back({cln::double_approx(mid), p.key() + " = " + decimal(mid, 4), true, true, 0.97, false});
    }
  }
  plot.markers.push_back({a, "a = " + decimal(a, 6) + " m/s", false, false, 0.97, false});
  draw(run.out, "fig5", plot);
  doc.paragraph("Parameters of §4.3 (m1 = 0.001, m2 = m3 = 15, m4 = 5e6 kg, K12 = 7, K23 = 1, K13 = 5, K24 = 13, K34 = 12, "
                "K14 = 1500, a = 3.13209 m/s), each coupling swept over the range where M stays positive semi-definite "
                "(401 values, double), and the superball threshold U1+ = a located by bisection on the exact solution:");
  doc.table({"scene", "coupling", "U1+ = a at", "change"}, rows);
  doc.figure("fig5", "U1+ against alpha_2 (alpha_5 = 0) and against alpha_5 (alpha_2 = 0); the horizontal line is U1+ = a.");
  doc.paragraph("As the paper says, both couplings produce the superball; alpha_2 must be negative and alpha_5 positive "
                "(read the thresholds above).");
}

/// Fig. 7: U1+, U2+, U3+ against K34 with the switch points, both readings.
void fig7(const Run& run, Document& doc) {
  const PrintedNumbers& printed = PrintedNumbers::paper();
  const Vocabulary& v = Vocabulary::paper();
  doc.heading("Fig. 7: where the evolution case changes along K34, §4.4");
  doc.paragraph("`superball sweep SCENE --vary K.3-4=0:20:401 --switch-points`: bisection on the exact solution between "
                "sweep values of different cases, beside the values the paper reads off its Fig. 7.");
  std::vector<std::vector<Cell>> rows;
  for (const char* f : {"paper-4.4-as-printed.toml", "paper-4.4-alpha2.toml"}) {
    const Scene scene = run.scene(f);
    const Parameter k34 = Parameter::parse("K.3-4", scene);
    const auto points = numeric::sweep(scene, k34, numeric::linspace(0, 20, 401), double_precision);
    const auto switches = numeric::switch_points(scene, k34, points);
    const bool alpha2 = std::string(f) == "paper-4.4-alpha2.toml";
    Plot plot{std::string("Fig. 7: velocities after the collision against K_{34} (") + (alpha2 ? "alpha_2" : "alpha_4") +
                  " = -100)",
              "K_{34} (kg)", "velocity after the collision (m/s)", false, false, "inside center right box opaque spacing 1.4", {}, {}};
    const Curves c = curves_of(points);
    for (int i = 0; i < 3; ++i) plot.series.push_back({"U_" + std::to_string(i + 1) + "^+", c.x, c.u[i], false});
    for (const auto& sw : switches) {
      const cln::cl_RA mid = (sw.low + sw.high) / 2;
      plot.markers.push_back({cln::double_approx(mid), "switch " + decimal(mid, 4) + " (" + v.case_name(sw.below) + " -> " +
                                                           v.case_name(sw.above) + ")", true, false, 0.97, false});
    }
    for (const auto& p : printed.switches) {
      plot.markers.push_back({p.value.approx(), "paper: " + p.value.text, true, true, 0.6, true});
      std::vector<Cell> row{"`" + std::string(f) + "`", p.value.text + " (case " + p.case_name + ")"};
      const numeric::SwitchPoint* found = nullptr;
      for (const auto& sw : switches)
        if (v.case_name(sw.below) == p.case_name || v.case_name(sw.above) == p.case_name) found = &sw;
      if (!found) {
        row.insert(row.end(), {"none in 0..20", "-", "-"});
      } else {
        const cln::cl_RA mid = (found->low + found->high) / 2;
        row.insert(row.end(), {decimal(mid, 4) + " (" + decimal(mid, 15) + ")",
                               v.case_name(found->below) + " -> " + v.case_name(found->above),
                               fixed(100 * (cln::double_approx(mid) - p.value.approx()) / p.value.approx(), 2) + " %"});
      }
      rows.push_back(row);
    }
    draw(run.out, alpha2 ? "fig7-alpha2" : "fig7-as-printed", plot);
  }
  doc.table({"scene", "paper", "computed switch K34", "cases", "relative difference"}, rows);
  doc.figure("fig7-alpha2", "U1+, U2+, U3+ against K34 with alpha_2 = -100 (the reading that reproduces eq. 16); solid lines: "
                            "computed switch points, dashed: the paper's values.");
  doc.figure("fig7-as-printed", "The same with alpha_4 = -100 as printed: balls 2 and 3 never stay together for K34 <= 20.");
}

/// One map of the report: computed, overlaid with the derived conditions,
/// drawn into OUT/STEM with the points \p marks gives for it, and summed up
/// in a table row per case and notes on the boundaries and the overlay.
void report_map(const Run& run, const Scene& scene, const std::string& stem, const std::string& title, const numeric::Axis& x,
                     const numeric::Axis& y, const std::function<std::vector<present::MapMark>(const numeric::Map&)>& marks, Document& doc) {
  numeric::MapSettings settings;
  settings.threads = run.options.threads;
  struct {
    numeric::Map map;
    verify::Overlay overlay;
  } r{numeric::map(scene, x, y, settings), {}};
  r.overlay = verify::overlay(scene, r.map);
  std::vector<std::pair<double, double>> derived;
  for (const verify::DerivedZero& z : r.overlay.zeros)
    if (z.at_case) derived.push_back(numeric::position(r.map, {z.along_x, z.i, z.j, z.low, z.high, {}, {}, true, true}));
  draw_map(run.out + "/" + stem, r.map, title, marks(r.map), derived);
  const Vocabulary& v = Vocabulary::paper();
  std::size_t solved = 0;
  for (const auto& p : r.map.points) solved += p.admissible;
  std::vector<std::vector<Cell>> rows;
  std::vector<ContactSet> cases;
  for (const auto& p : r.map.points)
    if (p.admissible && std::find(cases.begin(), cases.end(), p.region.closed) == cases.end()) cases.push_back(p.region.closed);
  std::sort(cases.begin(), cases.end(), [&](const ContactSet& a, const ContactSet& b) { return v.case_name(a) < v.case_name(b); });
  for (const ContactSet& c : cases) {
    std::size_t in = 0, sb = 0;
    for (const auto& p : r.map.points)
      if (p.admissible && p.region.closed == c) ++in, sb += p.region.superball;
    rows.push_back({"case " + v.case_name(c), fixed(100.0 * static_cast<double>(in) / static_cast<double>(solved), 1) + " %",
                    fixed(100.0 * static_cast<double>(sb) / static_cast<double>(solved), 1) + " %"});
  }
  doc.table({"case", "share of the solved points", "of which superball"}, rows);
  double widest = 0;
  for (const auto& b : r.map.boundaries) widest = std::max(widest, cln::double_approx(b.high - b.low));
  doc.bullets({std::to_string(r.map.points.size()) + " grid points (" + std::to_string(x.steps) + " x " + std::to_string(y.steps) +
                   ", double), " + std::to_string(r.map.points.size() - solved) + " of them with M not positive semi-definite (not solved).",
               std::to_string(r.map.boundaries.size()) + " boundary points located by bisection on the exact solution (widest bracket " +
                   decimal(widest, 3) + "), on " + std::to_string(r.map.curves.size()) + " curves.",
               "Overlay: " + std::to_string(r.overlay.conditions) + " derived conditions of the cases present, " +
                   std::to_string(r.overlay.zeros.size()) + " zeros on the grid lines; every exact boundary point within the brackets' widths of a "
                   "derived zero: " + (r.overlay.agrees() ? "yes" : "**no**") + " (largest distance " + decimal(r.overlay.largest_distance, 3) +
                   " of the grid step, allowed " + decimal(r.overlay.largest_allowed, 3) + ")."});
}

/// The superball edge's points on the grid line \p fixed = \p value (Fig. 5's and Fig. 7's cuts), as marks.
std::vector<present::MapMark> edge_on_line(const numeric::Map& m, bool along_x, int index, const std::string& label) {
  std::vector<present::MapMark> marks;
  for (const auto& b : m.boundaries)
    if (b.along_x == along_x && (along_x ? b.j : b.i) == index && b.below_psd && b.above_psd && b.below.superball != b.above.superball) {
      const auto [x, y] = numeric::position(m, b);
      marks.push_back({x, y, label});
    }
  return marks;
}

/// Two maps over two parameters (issue 15): (alpha_2, alpha_5) at the §4.3
/// parameters, whose axes are Fig. 5's two cuts, and (K34, alpha_2) at the
/// §4.4 parameters, whose line alpha_2 = -100 is Fig. 7's cut.
void maps(const Run& run, Document& doc) {
  const PrintedNumbers& printed = PrintedNumbers::paper();
  doc.heading("Maps: the cases and the superball in a plane of two parameters");
  doc.paragraph("`superball map SCENE --x KEY=FROM:TO:N --y KEY=FROM:TO:N --overlay --plot STEM`: each grid point solved in "
                "double (case, U1+/a, superball), M positive semi-definite decided exactly (grey where it is not), every boundary "
                "between neighbours of different case or verdict located by bisection on the exact solution and drawn as a curve, "
                "and the zeros of the conditions derived symbolically for the cases present drawn as red circles.");
  {
    const Scene scene = run.scene("paper-fig5-alpha2.toml");
    const numeric::Axis x{Parameter::parse("alpha.2", scene), -110, 110, 111}, y{Parameter::parse("alpha.5", scene), -150, 150, 101};
    doc.paragraph("(alpha_2, alpha_5) at the parameters of §4.3 (`paper-fig5-alpha2.toml`, alpha_5 added): the two cuts of "
                  "Fig. 5 are the axes alpha_5 = 0 and alpha_2 = 0; the black dots mark where they cross the superball edge "
                  "(the thresholds of Fig. 5).");
    // Row 50 of y is alpha_5 = 0; column 55 of x is alpha_2 = 0.
    report_map(run, scene, "map-alpha2-alpha5", "alpha_2 and alpha_5 at the parameters of Sec. 4.3 (Fig. 5)", x, y,
               [](const numeric::Map& m) {
                 std::vector<present::MapMark> marks = edge_on_line(m, true, 50, "Fig. 5");
                 for (auto& mark : edge_on_line(m, false, 55, "Fig. 5")) marks.push_back(mark);
                 return marks;
               },
               doc);
    doc.figure("map-alpha2-alpha5", "Cases and U1+/a over (alpha_2, alpha_5), Sec. 4.3 parameters; black curve: the superball "
                                    "edge U1+ = a (exact); red circles: zeros of the derived conditions; dots: Fig. 5's thresholds.");
  }
  {
    const Scene scene = run.scene("paper-4.4-alpha2.toml");
    const numeric::Axis x{Parameter::parse("K.3-4", scene), 0, 20, 81}, y{Parameter::parse("alpha.2", scene), -110, 0, 111};
    std::vector<present::MapMark> marks{{10, -100, "eq. (16)"}};
    for (const auto& p : printed.switches) marks.push_back({p.value.approx(), -100, "paper: " + p.value.text});
    doc.paragraph("(K34, alpha_2) at the parameters of §4.4 read with alpha_2 (`paper-4.4-alpha2.toml`): Fig. 7's cut is the "
                  "line alpha_2 = -100; marked are eq. (16)'s point and the switch values the paper reads off Fig. 7.");
    report_map(run, scene, "map-k34-alpha2", "K_{34} and alpha_2 at the parameters of Sec. 4.4 (Fig. 7)", x, y,
               [&](const numeric::Map&) { return marks; }, doc);
    doc.figure("map-k34-alpha2", "Cases and U1+/a over (K34, alpha_2), Sec. 4.4 parameters; Fig. 7 is the line alpha_2 = -100.");
  }
}

/// §4.1: the epsilon family, exact, obstacle of infinite mass.
void epsilon_family(const Run& run, Document& doc) {
  const Scene base = run.scene("paper-4.1-family.toml");
  const Vocabulary& v = Vocabulary::paper();
  doc.heading("The epsilon family of §4.1 (case 1, alpha_2 = -1, m4 = infinity, a = 1)");
  doc.paragraph("K12 = -alpha2 (1 - eps + eps^2), K13 = -alpha2 eps^2, K14 = -alpha2 (1 + eps), m1 = -alpha2 eps^3; the other "
                "parameters from `cases/scenes/paper-4.1-family.toml`.  Exact solves.");
  std::vector<std::vector<Cell>> rows;
  Plot plot{"Sec. 4.1: U_1^+/a against 1/(2 eps)", "1/(2 eps)", "U_1^+ / a", true, true, "inside top left box opaque spacing 1.4", {}, {}};
  Series computed{"U_1^+/a, exact solve", {}, {}, true}, claim_line{"U_1^+ = a/(2 eps) (paper)", {}, {}, false};
  for (int k = 1; k <= 6; ++k) {
    cln::cl_RA eps = 1;
    for (int j = 0; j < k; ++j) eps = eps / 10;
    Scene scene = base;
    const cln::cl_RA alpha2 = -1;
    auto set = [&](const std::string& key, const cln::cl_RA& x) {
      Parameter::parse(key, scene).set(scene, Number::parse(numeric::to_string(x)));
    };
    set("K.1-2", -alpha2 * (1 - eps + eps * eps));
    set("K.1-3", -alpha2 * eps * eps);
    set("K.1-4", -alpha2 * (1 + eps));
    set("mass.1", -alpha2 * eps * eps * eps);
    set("alpha.2", alpha2);
    const auto problem = numeric::Problem<cln::cl_RA>::from(numeric::ExactScene::from(scene));
    const auto sol = numeric::solve(problem);
    const cln::cl_RA u1 = sol.velocities_after[0] * problem.unit;
    const cln::cl_RA claim = 1 / (2 * eps);
    rows.push_back({"1e-" + std::to_string(k), v.case_name(sol.closed), numeric::to_string(u1), decimal(u1, 10), decimal(claim, 10),
                    decimal(u1 / claim, 10)});
    computed.x.push_back(cln::double_approx(claim));
    computed.y.push_back(cln::double_approx(u1));
    claim_line.x.push_back(cln::double_approx(claim));
    claim_line.y.push_back(cln::double_approx(claim));
  }
  plot.series = {claim_line, computed};
  draw(run.out, "epsilon", plot);
  doc.table({"eps", "case", "U1+/a exact", "U1+/a", "1/(2 eps)", "U1+ / (a/(2 eps))"}, rows);
  doc.figure("epsilon", "U1+/a against 1/(2 eps), log-log: the exact solves lie on the paper's line.");
  doc.paragraph("The ratio tends to 1 as eps -> 0: U1+ = a/(2 eps) holds to leading order; the paper's own case-1 formula gives "
                "exactly a (1 - eps^2) / (eps (2 + eps)) = a/(2 eps) - a/4 + O(eps) on this family.");
}

/// The §4.4 stack released with small gaps, against the simultaneous collision (superball drop --gaps-to-zero).
void drop_gaps(const Run& run, Document& doc) {
  const char* file = "drop-paper-4.4.toml";
  doc.heading("The §4.4 stack dropped with gaps, against the simultaneous collision");
  doc.paragraph(std::string("`superball drop ") + file + " --gaps-to-zero --decades 6`: the stack (alpha_4 = -100 as printed) released "
                "from 0.5 m with both gaps 1 mm, then 0.1 mm, ... 1 nm, each drop followed collision by collision (the touching cluster "
                "collides by Fremond's law), against the same stack released with every gap 0, whose one collision is the paper's "
                "simultaneous collision.  Compared: the velocities after the first cascade (the collisions until every ball moves up at "
                "least as fast as the one below it), over the landing speed a.");
  const Scene scene = run.scene(file);
  numeric::GapLimitOptions options;
  options.decades = 6;
  const numeric::GapLimit limit = numeric::gaps_to_zero(scene, double_precision, options);
  const double a = limit.landing_speed;
  const double gap = scene.bodies[0].gap->approx();
  std::vector<std::vector<Cell>> rows;
  auto row = [&](const numeric::GapLimitStep& step, const std::string& gaps) {
    std::string collisions;
    for (const auto& c : step.cascade.collisions) collisions += (collisions.empty() ? "" : ", ") + c;
    rows.push_back({gaps, collisions, decimal(step.cascade.velocities[0] / a, 6), decimal(step.cascade.velocities[1] / a, 6),
                    decimal(step.cascade.velocities[2] / a, 6), decimal(step.drop.top_apex_ratio, 6), decimal(step.deviation, 3)});
  };
  for (const auto& step : limit.steps) row(step, decimal(gap * step.scale, 3) + " m");
  row(limit.simultaneous, "0 (simultaneous)");
  const Plot plot = gap_limit_plot(limit, scene, "The paragraph 4.4 stack dropped with gaps: velocities after the first cascade");
  draw(run.out, "drop-gaps", plot);
  doc.table({"gaps", "first cascade (balls, case)", "U1+/a", "U2+/a", "U3+/a", "top apex / release height", "deviation / a"}, rows);
  doc.figure("drop-gaps", "Velocities of the three balls after the first cascade against the gap (points), and after the simultaneous "
                          "collision (dashed lines).");
  const bool converges = limit.verdict == numeric::GapVerdict::Converges;
  doc.paragraph(std::string("The gapped drops converge (the cascades differ by about ten times less each decade) but ") +
                (converges ? "to the simultaneous collision." : "not to the simultaneous collision: ") +
                (converges ? std::string()
                                 : "at 1 nm ball 1 leaves at " + decimal(limit.steps.back().cascade.velocities[0] / a, 4) +
                                       " a after " + std::to_string(limit.steps.back().cascade.events) +
                                       " binary collisions, against " + decimal(limit.simultaneous.cascade.velocities[0] / a, 4) +
                                       " a in the paper's case " + limit.simultaneous.drop.events.at(0).case_name +
                                       ".  A sequence of collisions of touching clusters never lets K14, the coupling of ball 1 with "
                                       "the obstacle through the stack, act: it is the simultaneous collision that does."));
}

/// The symbols of the paper's couplings \p alphas, bottom body fixed (m4 = infinity), as audited.
symbolic::Symbols paper_symbols(const std::vector<int>& alphas) {
  return symbolic::Symbols(symbolic::Pattern::paper(alphas), symbolic::Obstacle::Infinite);
}

/// The couplings α_k of a pattern ("α₂, α₆"), in \p style.
std::string pattern_name(const symbolic::Symbols& s, symbolic::Style style) {
  std::string out;
  for (const symbolic::SymbolInfo& info : s.all())
    if (info.kind == symbolic::SymbolKind::Coupling) out += (out.empty() ? "" : ", ") + info.name(style);
  return out;
}

/// A parameter point of the audit: "m₁ = 21/1250 (0.0168), …" and its LaTeX.
Cell point_cell(const verify::Witness& w, const symbolic::Symbols& s) {
  std::string text, latex;
  for (const auto& [name, v] : w.point) {
    const symbolic::SymbolInfo& info = s.info(s.by_name(name));
    const std::string value = verify::to_string(v) + (cln::denominator(v) == 1 ? "" : " (" + decimal(v, 6) + ")");
    text += (text.empty() ? "" : ", ") + info.text + " = " + value;
    latex += (latex.empty() ? "" : ", ") + ("$" + info.latex + " = " + verify::to_string(v) + "$") +
             (cln::denominator(v) == 1 ? "" : " (" + decimal(v, 6) + ")");
  }
  return Cell(text, latex);
}

/// "holds" or "fails".
std::string holds(bool b) { return b ? "holds" : "fails"; }

/// What a condition says at a point and whether that is right: "printed: holds, **wrong**".
std::string judged(const std::string& who, bool says, bool truth) { return who + ": " + holds(says) + (says == truth ? ", right" : ", **wrong**"); }

/// The paper's LaTeX with plain parentheses for \left( \right), so that a
/// narrow table column may break the formula inside them.
std::string breakable(std::string latex) {
  for (const char* sized : {"\\left", "\\right"})
    for (std::size_t at = latex.find(sized); at != std::string::npos; at = latex.find(sized, at)) latex.erase(at, std::string(sized).size());
  return latex;
}

/// §4.1–§4.3: the paper's printed conditions and claims in words against the
/// derivation, as audited by verify::audit_paper (the audit of `superball
/// audit`): per case of the paper a table of the printed, derived exact and
/// derived asymptotic conditions with the verdict, the parameter points where
/// a printed condition disagrees with the exact solution, then the claims.
void printed_conditions(const verify::Audit& audit, Document& doc) {
  using symbolic::Style;
  int counts[3] = {0, 0, 0};
  for (const auto& c : audit.conditions) ++counts[static_cast<int>(c.agreement)];
  doc.heading("The printed conditions of §4.1–§4.3 against the derivation");
  doc.paragraph(
      "Every condition the paper prints for its cases 1, 2.1 and 3.2 (transcribed in `cases/paper/printed-conditions.toml`) beside "
      "the condition derived symbolically for the same case and couplings: exact (bottom body fixed, m4 = infinity) and asymptotic "
      "(its dominant balance for m1 ~ eps, K14 ~ 1/eps).  Verdict: identical to the exact condition, identical at the asymptotic "
      "order, or different; a different one comes with a parameter point (M positive semi-definite, eps = " +
      verify::to_string(audit.options.epsilon) + ", found among " + std::to_string(audit.options.samples) +
      " pseudo-random points per search, seed " + std::to_string(audit.options.seed) +
      ") where it disagrees with the exact solution of the case (numeric backend, rationals).  This run: " + std::to_string(counts[0]) +
      " printed conditions identical to the exact condition, " + std::to_string(counts[1]) + " identical at the asymptotic order, " +
      std::to_string(counts[2]) + " different.  The same audit as text: `superball audit --samples " +
      std::to_string(audit.options.samples) + "`.");

  // One group per (section, case, couplings), in the paper's order.
  std::vector<std::vector<const verify::ConditionAudit*>> groups;
  for (const auto& c : audit.conditions) {
    auto same = [&](const std::vector<const verify::ConditionAudit*>& g) {
      return g[0]->printed.section == c.printed.section && g[0]->printed.case_name == c.printed.case_name && g[0]->printed.alphas == c.printed.alphas;
    };
    auto it = std::find_if(groups.begin(), groups.end(), same);
    if (it == groups.end())
      groups.push_back({&c});
    else
      it->push_back(&c);
  }
  for (const auto& group : groups) {
    const PrintedCondition& first = group[0]->printed;
    const symbolic::Symbols s = paper_symbols(first.alphas);
    doc.subheading("§" + first.section + ", case " + first.case_name + ", coupling " + pattern_name(s, Style::Text) + " (the other couplings zero)");
    std::vector<std::vector<Cell>> rows, points;
    std::vector<std::string> notes;
    for (const verify::ConditionAudit* c : group) {
      const PrintedCondition& p = c->printed;
      const Cell title(c->title.text, c->title.latex);
      const Cell exact = Cell::math(c->exact.text, c->exact.latex);
      const Cell asymptotic = p.kind == "velocity" ? Cell("the exact formula (a velocity is compared exactly)")
                                                   : Cell::math(c->asymptotic.text, c->asymptotic.latex);
      std::string words = verify::to_string(c->agreement);
      if (c->agreement == verify::Agreement::Different) words = "**" + words + "**";
      Cell verdict(words);
      if (c->agreement != verify::Agreement::IdenticalExact && !c->printed_asymptotic.text.empty()) {
        words += "; the printed one at leading order: ";
        verdict = Cell(words + c->printed_asymptotic.text, latex_text(words) + "$" + c->printed_asymptotic.latex + "$");
      }
      rows.push_back({title, Cell::math(c->as_printed.text, breakable(p.printed)), exact, asymptotic, verdict});
      for (const std::string& n : c->notes) notes.push_back(title.text + ": " + n + ".");
      if (c->agreement != verify::Agreement::Different) continue;
      if (!c->witness) {
        points.push_back({title, "none found in " + std::to_string(c->tried) + " points", "-", "-", "-"});
        continue;
      }
      const verify::Witness& w = *c->witness;
      points.push_back({title, point_cell(w, s), w.quantity + ": the condition " + holds(w.numeric),
                        judged("printed", w.printed, w.numeric) + "; " + judged("derived exact", w.derived_exact, w.numeric) + "; " +
                            judged("derived asymptotic", w.derived_asymptotic, w.numeric),
                        (w.actual_case.empty() ? "-" : w.actual_case) + " (point " + std::to_string(c->tried) + " of the search)"});
    }
    doc.table({"condition (what it ensures)", "printed (paper)", "derived exact", "derived asymptotic", "verdict"}, rows,
              {0.16, 0.22, 0.30, 0.15, 0.17});
    if (!notes.empty()) doc.bullets(notes);
    if (!points.empty()) {
      doc.paragraph("Where the printed condition is wrong: a parameter point of the regime for each different condition, the exact "
                    "solution of case " + first.case_name + " there (forced: the case's closed contacts kept closed), and what each "
                    "condition says.  The last column is the case the unforced exact solution takes.");
      doc.table({"condition", "point", "exact solution of case " + first.case_name, "the conditions there", "actual case"}, points,
                {0.15, 0.37, 0.18, 0.19, 0.11});
    }
  }

  doc.subheading("The claims in words");
  doc.paragraph("\"Superball possible\" is supported by a point where the case is the actual evolution with U1+ > a; \"superball "
                "impossible\" needs a proof from M positive semi-definite.  The derived superball condition is the exact one of the "
                "claim's couplings; the evidence follows the table.");
  std::vector<std::vector<Cell>> rows;
  std::vector<std::string> evidence;
  for (const verify::ClaimAudit& c : audit.claims) {
    const symbolic::Symbols s = paper_symbols(c.claim.alphas);
    const std::string couplings = pattern_name(s, Style::Text);
    rows.push_back({"§" + c.claim.section, "\"" + c.claim.text + "\"",
                    Cell("case " + c.claim.case_name + ", " + couplings, "case " + c.claim.case_name + ", $" + pattern_name(s, Style::Latex) + "$"),
                    Cell::math(c.superball.text, c.superball.latex),
                    (c.supported ? "" : "**") + c.verdict + (c.supported ? "" : "**") + " (" + std::to_string(c.tried) + " points tried, " +
                        std::to_string(c.hits) + " with the superball in the case)"});
    const std::string who = "Case " + c.claim.case_name + " with " + couplings;
    if (!c.certificate.empty()) evidence.push_back(who + ", proof: " + c.certificate + ".");
    if (c.example) evidence.push_back(who + ", example: " + point_cell(*c.example, s).text + ": " + c.example->quantity + ", actual case " + c.example->actual_case + ".");
    for (const std::string& line : c.comparisons) evidence.push_back(who + " against " + pattern_name(paper_symbols(c.claim.like), Style::Text) + ", " + line + ".");
  }
  doc.table({"", "the paper says", "case, couplings", "derived superball condition", "verdict"}, rows, {0.1, 0.28, 0.12, 0.26, 0.24});
  doc.bullets(evidence);
}

/// The paper's investigated cases (§4.1–§4.4) with their couplings: what the verification runs check.
const std::vector<std::pair<std::string, std::vector<int>>>& paper_cases() {
  static const std::vector<std::pair<std::string, std::vector<int>>> cases{{"1", {2}}, {"2.1", {1, 6}}, {"3.2", {5}}, {"3.3", {4}}};
  return cases;
}

/// "a/b" of two counts.
std::string ratio(long long a, long long b) { return std::to_string(a) + "/" + std::to_string(b); }

/// Section 6: the derived conditions of the paper's cases against exact solutions over ε (`superball verify`),
/// and which single coupling of M gives the superball in which case (`superball explore --all-patterns`).
/// "α₂" or "α₁, α₆" (Style::Text), "alpha_2" (Markdown-safe ASCII), or "1,6" (the --alphas list).
std::string alpha_names(const std::vector<int>& alphas, const std::string& prefix, const std::string& separator) {
  std::string out;
  for (int k : alphas) out += (out.empty() ? "" : separator) + prefix + std::to_string(k);
  return out;
}

void verification_and_patterns(const std::vector<verify::Verification>& runs, const verify::PatternTable& table, Document& doc) {
  doc.heading("The derived conditions against exact solutions, and the alpha-patterns");
  doc.paragraph(
      "Section 5 checks the paper against the derivation; this section checks the derivation itself.  For each case the paper "
      "investigates, parameter points of the asymptotic regime (m1 ~ eps, K14 ~ 1/eps, others O(1); M positive semi-definite; "
      "bottom body fixed) are solved exactly, and the derived conditions of the case are compared with the exact solution: "
      "the truth is \"the case is the actual evolution and U1+ > a\".  Besides the drawn points, each condition's boundary is "
      "approached by bisection (\"near\": within 2^-20 of it along a segment).  The exact conditions must agree everywhere; "
      "the asymptotic ones only as eps -> 0, and near a boundary only once eps is below the bracket width.");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const verify::Verification& v = runs[i];
    const std::vector<int>& alphas = paper_cases()[i].second;
    doc.subheading("Case " + v.case_name + ", coupling " + alpha_names(alphas, "alpha_", ", "));
    std::vector<std::vector<Cell>> rows;
    for (const verify::EpsilonResult& e : v.epsilons) {
      const verify::Tally all = e.all();
      rows.push_back({verify::epsilon_name(e.epsilon), std::to_string(all.points), ratio(all.exact.agree(), all.exact.total()),
                      ratio(e.drawn.asymptotic.agree(), e.drawn.asymptotic.total()),
                      ratio(e.boundary.asymptotic.agree(), e.boundary.asymptotic.total()),
                      std::to_string(all.exact.holds_true)});
    }
    doc.table({"eps", "points", "exact conditions agree", "asymptotic agree (drawn)", "asymptotic agree (near)", "superball in the case"}, rows);
    std::vector<std::string> notes;
    notes.push_back(std::string("The exact conditions ") + (v.exact_agrees() ? "agree with the exact solution at every point" : "**DISAGREE** somewhere") +
                    " (" + std::to_string(v.samples) + " drawn points per eps, seed " + std::to_string(v.seed) + ").");
    long long near_disagree = 0, drawn_disagree = 0;
    for (const verify::Disagreement& d : v.disagreements) (d.near ? near_disagree : drawn_disagree) += 1;
    notes.push_back(std::to_string(drawn_disagree) + " drawn and " + std::to_string(near_disagree) +
                    " near-boundary points where a form disagrees; `superball verify --case " + v.case_name + " --alphas " +
                    alpha_names(alphas, "", ",") + " --samples " + std::to_string(v.samples) + " --out DIR` writes each as a scene file.");
    doc.bullets(notes);
  }
  doc.subheading("Which coupling gives the superball in which case");
  doc.paragraph("`superball explore --all-patterns`: each single α_k and the pair {α₁, α₆} of §4.1's remark against every "
                "case.  \"yes\" is a witness confirmed by an exact solve (the case is the actual evolution and U1+ > a; the ratio is the "
                "largest U1+/a found in the box " + table.cells.front().front().box + ", a lower bound that depends on the box and the search budget: " +
                std::to_string(table.options.starts) + " local searches of " + std::to_string(table.options.evaluations) +
                " evaluations per cell); \"no (proved)\" is a proof that the case's conditions and U1+ > a clash for every M positive "
                "semi-definite; \"not found\" is neither.");
  std::vector<std::string> header{"pattern"};
  for (const std::string& c : table.cases) header.push_back("case " + c);
  std::vector<std::vector<Cell>> rows;
  for (std::size_t r = 0; r < table.cells.size(); ++r) {
    std::vector<Cell> row{table.cells[r].front().pattern};
    for (const verify::ExploreResult& cell : table.cells[r]) row.push_back(present::cell_text(cell));
    rows.push_back(row);
  }
  doc.table(header, rows);
  std::vector<std::string> claims;
  auto cell = [&](const std::vector<int>& pattern, const std::string& case_name) -> const verify::ExploreResult& {
    for (std::size_t r = 0; r < table.patterns.size(); ++r)
      if (table.patterns[r] == pattern)
        for (std::size_t c = 0; c < table.cases.size(); ++c)
          if (table.cases[c] == case_name) return table.cells[r][c];
    throw std::logic_error("verification_and_patterns(): no cell for case " + case_name);
  };
  const struct {
    std::vector<int> pattern;
    const char* case_name;
    const char* paper;
    bool possible;
  } said[] = {{{2}, "1", "§4.1: α₂ gives the superball in case 1", true},
              {{3}, "1", "§4.1: α₃ alone gives it in case 1, like α₂", true},
              {{1, 6}, "1", "§4.1: α₁ with α₆ cannot give it in case 1", false},
              {{5}, "3.2", "§4.3: α₅ gives it in case 3.2", true},
              {{7}, "3.2", "§4.3: α₇ gives it in case 3.2, like α₅", true},
              {{4}, "3.3", "§4.4: α₄ gives it in case 3.3", true}};
  for (const auto& c : said) {
    const verify::ExploreResult& r = cell(c.pattern, c.case_name);
    const bool agrees = c.possible ? r.reach == verify::Reach::Yes : r.reach == verify::Reach::Impossible || r.reach == verify::Reach::CaseImpossible;
    claims.push_back(std::string(c.paper) + ": " + (agrees ? "agrees" : "**does not agree**") + " (" + present::cell_text(r) + ").");
  }
  doc.bullets(claims);
}

/// cases/scenes below the working folder when there is one (paths in the
/// report stay relative), else the installed scenes beside the command
/// (share/superball/scenes), else the source tree's.
std::string default_scenes() {
  const auto is_folder = [](const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
  };
  if (is_folder("cases/scenes")) return "cases/scenes";
#ifdef SUPERBALL_INSTALLED_SCENES
  char self[4096];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (n > 0) {
    std::string installed(self, static_cast<std::size_t>(n));
    installed = installed.substr(0, installed.rfind('/') + 1) + SUPERBALL_INSTALLED_SCENES;
    if (is_folder(installed)) return installed;
  }
#endif
  return SUPERBALL_SCENES_DIR;
}

/// Create the report folder \p out if missing and make sure files can be
/// written in it, before anything is computed: a bad --out is one line, exit 2,
/// and leaves nothing behind.  Throws std::invalid_argument("--out ...").
void prepare_folder(const std::string& out) {
  if (::mkdir(out.c_str(), 0777) != 0 && errno != EEXIST)
    throw OutputError("--out " + out + ": cannot create the folder (" + std::strerror(errno) + ")");
  struct stat st {};
  if (::stat(out.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) throw OutputError("--out " + out + ": not a folder");
  if (::access(out.c_str(), W_OK | X_OK) != 0) throw OutputError("--out " + out + ": cannot write in the folder (" + std::strerror(errno) + ")");
}

}  // namespace

void add_reproduce(CLI::App& app, Action& action) {
  auto o = std::make_shared<Run>(Run{default_scenes(), "report", {}});
  CLI::App* cmd = app.add_subcommand("reproduce", "Recompute the paper's numbers and figures and write a report");
  cmd->footer(
      "Writes OUT/report.md, OUT/report.tex and the figures (PNG and SVG, with their gnuplot data and scripts).\n"
      "Every number is computed by this run from the scene files in --scenes and the transcription of the\n"
      "paper's printed conditions; the paper's printed numbers (cases/paper/printed-numbers.toml) are shown\n"
      "beside them for comparison only.  The section on the printed conditions is `superball audit`'s audit;\n"
      "--samples makes it faster (fewer points tried per search).  The next section verifies the derived conditions\n"
      "of the paper's cases against exact solutions (superball verify; --verify-samples) and tabulates which coupling\n"
      "gives the superball in which case (superball explore --all-patterns; --explore-starts).  Needs gnuplot.\n\n"
      "Examples:\n  superball reproduce --out report\n  superball reproduce --out report-quick --samples 500 --verify-samples 200 --explore-starts 4");
  cmd->add_option("--out,-o", o->out, "Report folder (created if missing)")->capture_default_str()->check(non_empty());
  cmd->add_option("--scenes", o->scenes, "Folder of the paper's scene files")->capture_default_str();
  verify::ReproduceOptions& options = o->options;
  cmd->add_option("--samples", options.samples, "Points tried per search of the audit of the printed conditions (as superball audit --samples)")
      ->capture_default_str();
  cmd->add_option("--verify-samples", options.verify_samples, "Drawn points per eps of each verification run (as superball verify --samples)")
      ->capture_default_str();
  cmd->add_option("--explore-starts", options.explore_starts, "Local searches per cell of the pattern table (as superball explore --starts)")
      ->capture_default_str();
  cmd->add_option("--threads,-j", options.threads, "Threads of the verification runs (0: all cores)")->capture_default_str();
  cmd->callback([o, &action] {
    action = [o] {
      o->options.check();
      prepare_folder(o->out);
      Document doc("superball reproduce: the paper's numbers recomputed");
      doc.paragraph("Paper: Collision of four balls aligned (Fremond's theory of collisions).  Scenes: `" + o->scenes + "`.");
      eq16(*o, doc);
      fig5(*o, doc);
      fig7(*o, doc);
      maps(*o, doc);
      epsilon_family(*o, doc);
      drop_gaps(*o, doc);
      printed_conditions(verify::audit_paper(PrintedConditions::paper(), o->options.audit()), doc);
      std::vector<verify::Verification> runs;
      const verify::VerifyOptions verification = o->options.verification();
      for (const auto& [name, alphas] : paper_cases()) {
        const symbolic::Deriver deriver(symbolic::Pattern::paper(alphas), symbolic::Obstacle::Infinite);
        runs.push_back(verify::verify_case(deriver, Vocabulary::paper().named_case(name).closed, verification));
      }
      verification_and_patterns(runs, verify::explore_all_patterns(o->options.exploration()), doc);
      write_output(o->out + "/report.tex", doc.latex());
      write_output(o->out + "/report.md", doc.markdown());
      write_output("", doc.markdown() + "(written to " + o->out + "/report.md and report.tex)\n");
      return ok;
    };
  });
}

}  // namespace superball::cli
