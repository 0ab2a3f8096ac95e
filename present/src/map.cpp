#include "superball/present/map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/scalar.hpp"
#include "text_blocks.hpp"

namespace superball::present {
namespace {

using numeric::Map;
using numeric::MapBoundary;
using numeric::MapPoint;
using numeric::Region;
using detail::append_number;
using detail::cached;
using detail::csv_field;
using detail::decimal;
using detail::in_blocks;
using detail::number;

/// decimal(a.value(k), 10) for k = first … first + count − 1, on \p threads threads.
std::vector<std::string> decimals(const numeric::Axis& a, int first, int count, int threads) {
  return detail::decimals(a.from, a.to, a.steps, first, count, threads);
}

/// Bytes per grid point of each output beside the map at its peak
/// (map_output_bytes_per_point()): the peak resident size of 1000 x 1000
/// maps of the paper's plane less that of its summary, rounded up
/// (docs/MAPS.md).  CSV and JSON are written in blocks as they are made,
/// so theirs is mostly a fixed 5 MB (CSV) or 20 MB (JSON) that 1000 x 1000
/// points spread to 5 and 25 bytes a point.  The Python module's arrays
/// and lists (superball.map()): about 40 bytes a point.
constexpr double csv_bytes_per_point = 10, json_bytes_per_point = 40, figure_bytes_per_point = 240, arrays_bytes_per_point = 50;




/// A case present among the solved points: how many are in it, and how many of them are superball.
struct CaseCount {
  ContactSet closed;
  std::size_t in = 0, superball = 0;
};

/// The cases present among the solved points with their counts, in the
/// paper's order of names: one pass over the points.
std::vector<CaseCount> case_counts(const Map& m) {
  std::vector<CaseCount> cases;
  std::size_t last = 0;  // neighbours are mostly of one case
  for (const MapPoint& p : m.points) {
    if (!p.admissible) continue;
    if (last >= cases.size() || cases[last].closed != p.region.closed) {
      last = 0;
      while (last < cases.size() && cases[last].closed != p.region.closed) ++last;
      if (last == cases.size()) cases.push_back({p.region.closed});
    }
    ++cases[last].in;
    cases[last].superball += p.region.superball;
  }
  const Vocabulary& v = Vocabulary::paper();
  std::sort(cases.begin(), cases.end(), [&](const CaseCount& a, const CaseCount& b) {
    const std::string na = v.case_name(a.closed), nb = v.case_name(b.closed);
    return na != nb ? na < nb : a.closed.to_string() < b.closed.to_string();
  });
  return cases;
}

/// The cases present among the solved points, in the paper's order of names.
std::vector<ContactSet> cases_present(const Map& m) {
  std::vector<ContactSet> cases;
  for (const CaseCount& c : case_counts(m)) cases.push_back(c.closed);
  return cases;
}

/// Distinct colours for the cases (Tableau 10), then grey for M not PSD.
constexpr const char* kColours[] = {"#4E79A7", "#F28E2B", "#59A14F", "#E15759", "#B07AA1",
                                    "#76B7B2", "#EDC948", "#9C755F", "#FF9DA7", "#3B3B98"};
constexpr int kColourCount = sizeof kColours / sizeof kColours[0];
constexpr const char* kNotPsd = "#C8C8C8";
/// How far toward white the part of a case without the superball is drawn.
constexpr double kPale = 0.6;
/// The top of the legend, under the panels, as a fraction of the figure's height.
constexpr double kLegendTop = 0.19;
/// The data file's first curve: after the regions, U1+/a, the marks and the derived zeros.
constexpr int kFirstCurve = 4;

struct Rgb {
  int r, g, b;
};
Rgb rgb(const char* hex) {
  unsigned r = 0, g = 0, b = 0;
  std::sscanf(hex + 1, "%2x%2x%2x", &r, &g, &b);
  return {static_cast<int>(r), static_cast<int>(g), static_cast<int>(b)};
}
Rgb pale(Rgb c) {
  auto mix = [](int v) { return static_cast<int>(std::lround(v + (255 - v) * kPale)); };
  return {mix(c.r), mix(c.g), mix(c.b)};
}
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

/// What curve \p c separates, for people.
std::string curve_text(const numeric::MapCurve& c) {
  const Vocabulary& v = Vocabulary::paper();
  switch (c.kind) {
    case numeric::MapCurve::Kind::Superball: return "superball edge (U1+ = a)";
    case numeric::MapCurve::Kind::Psd: return "edge of M positive semi-definite";
    case numeric::MapCurve::Kind::Case: break;
  }
  return "case " + v.case_name(c.first) + " | case " + v.case_name(c.second);
}



}  // namespace

std::string case_name(const Region& r) { return Vocabulary::paper().case_name(r.closed); }

std::string axis_label(const std::string& key) {
  if (key.rfind("alpha.", 0) == 0) return "α_{" + key.substr(6) + "}";
  if (key.rfind("K.", 0) == 0) {
    std::string pair = key.substr(2);
    pair.erase(std::remove(pair.begin(), pair.end(), '-'), pair.end());
    return "K_{" + pair + "}";
  }
  std::string out;
  for (char c : key) out += c == '_' ? std::string("\\\\_") : std::string(1, c);
  return out;
}

std::string map_csv_header(const numeric::Axis& x, const numeric::Axis& y) {
  return x.parameter.key() + ',' + y.parameter.key() + ",psd,case,closed,U1_over_a,superball,status\n";
}

std::string map_csv_rows(const numeric::Axis& x, const numeric::Axis& y, std::size_t first, const std::vector<MapPoint>& points, int threads) {
  std::string text;
  write_csv_rows(x, y, first, points, threads, [&](std::string_view rows) { text += rows; });
  return text;
}

void write_csv_rows(const numeric::Axis& x, const numeric::Axis& y, std::size_t first, const std::vector<MapPoint>& points, int threads,
                    const TextSink& sink) {
  if (points.empty()) return;
  const auto nx = static_cast<std::size_t>(x.steps);
  // The axes' texts made once for the rows' tasks: every x, the y of the rows of these points.
  const std::size_t j0 = first / nx, j1 = (first + points.size() - 1) / nx;
  const std::vector<std::string> xs = decimals(x, 0, x.steps, threads), ys = decimals(y, static_cast<int>(j0), static_cast<int>(j1 - j0 + 1), threads);
  // A case's fields, made on first use by each thread.
  using Cases = std::vector<std::pair<ContactSet, std::string>>;
  in_blocks<Cases>(points.size(), threads, [&](Cases& cases, std::string& out, std::size_t from, std::size_t to) {
    for (std::size_t at = from; at < to; ++at) {
      const std::size_t k = first + at;
      const MapPoint& p = points[at];
      out += xs[k % nx];
      out += ',';
      out += ys[k / nx - j0];
      if (!p.admissible) {
        out += ",0,,,,,\n";
        continue;
      }
      out += ",1,";
      out += cached(cases, p.region.closed, [&] { return csv_field(case_name(p.region)) + ',' + csv_field(p.region.closed.to_string()); });
      out += ',';
      append_number(out, p.ratio);
      out += p.region.superball ? ",1," : ",0,";
      out += numeric::to_string(p.status);
      out += '\n';
    }
  }, sink);
}

std::string map_csv(const Map& m, int threads) { return map_csv_header(m.x, m.y) + map_csv_rows(m.x, m.y, 0, m.points, threads); }

void write_map_csv(const Map& m, int threads, const TextSink& sink) {
  sink(map_csv_header(m.x, m.y));
  write_csv_rows(m.x, m.y, 0, m.points, threads, sink);
}

double map_output_bytes_per_point(MapOutput output) {
  switch (output) {
    case MapOutput::Summary: return 0;
    case MapOutput::Csv: return csv_bytes_per_point;
    case MapOutput::Json: return json_bytes_per_point;
    case MapOutput::Figure: return figure_bytes_per_point;
    case MapOutput::Arrays: return arrays_bytes_per_point;
  }
  return 0;
}

std::string boundaries_csv(const Map& m) {
  std::ostringstream os;
  os << "along," << m.x.parameter.key() << ',' << m.y.parameter.key()
     << ",bracket_width,psd_low,case_low,superball_low,psd_high,case_high,superball_high\n";
  for (const MapBoundary& b : m.boundaries) {
    const cln::cl_RA mid = (b.low + b.high) / 2;
    os << (b.along_x ? m.x.parameter.key() : m.y.parameter.key()) << ',' << decimal(b.along_x ? mid : m.x.value(b.i)) << ','
       << decimal(b.along_x ? m.y.value(b.j) : mid) << ',' << decimal(b.high - b.low, 3);
    for (const auto& [psd, r] : {std::pair<bool, const Region&>{b.below_psd, b.below}, {b.above_psd, b.above}})
      os << ',' << psd << ',' << (psd ? csv_field(case_name(r)) + ',' + std::to_string(r.superball) : std::string(","));
    os << '\n';
  }
  return os.str();
}

namespace {

nlohmann::ordered_json region_json(const Region& r) {
  return nlohmann::ordered_json{{"case", case_name(r)}, {"closed", r.closed.closed_names()}, {"superball", r.superball}};
}

/// The grid point (i, jy) of map_json(); \p x and \p y its values in double.
nlohmann::ordered_json point_json(const MapPoint& p, int i, int jy, double x, double y) {
  nlohmann::ordered_json q{{"i", i}, {"j", jy}, {"x", x}, {"y", y}, {"psd", p.admissible}};
  if (p.admissible) {
    q.update(region_json(p.region));
    q["U1_over_a"] = std::isnan(p.ratio) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(p.ratio);
    q["status"] = numeric::to_string(p.status);
  }
  return q;
}

/// The members of \p object as dump(1) writes them inside an object at depth
/// \p depth (0: the document): its text without the braces, each line
/// indented by depth more spaces.
std::string members_text(const nlohmann::ordered_json& object, int depth) {
  const std::string text = object.dump(1), indent(static_cast<std::size_t>(depth), ' ');
  std::string out = indent;
  for (std::size_t k = 2; k + 2 < text.size(); ++k) out += text[k] == '\n' ? '\n' + indent : std::string(1, text[k]);
  return out;
}

/// map_json() without its points (an empty array in their place).
nlohmann::ordered_json map_json_frame(const Map& m, const Scene& scene, const std::string& precision) {
  nlohmann::ordered_json j;
  j["scene"] = scene.origin;
  j["title"] = scene.title;
  j["precision"] = precision;
  for (const numeric::Axis* a : {&m.x, &m.y})
    j[a == &m.x ? "x" : "y"] = {{"key", a->parameter.key()},
                                {"from", numeric::to_string(a->from)},
                                {"to", numeric::to_string(a->to)},
                                {"steps", a->steps}};
  j["points"] = nlohmann::ordered_json::array();
  auto& bounds = j["boundaries"] = nlohmann::ordered_json::array();
  for (const MapBoundary& b : m.boundaries) {
    const auto [x, y] = numeric::position(m, b);
    bounds.push_back({{"along", b.along_x ? m.x.parameter.key() : m.y.parameter.key()},
                      {"i", b.i},
                      {"j", b.j},
                      {"x", x},
                      {"y", y},
                      {"low", numeric::to_string(b.low)},
                      {"high", numeric::to_string(b.high)},
                      {"bracket_width", cln::double_approx(b.high - b.low)},
                      {"below", b.below_psd ? region_json(b.below) : nlohmann::ordered_json{{"psd", false}}},
                      {"above", b.above_psd ? region_json(b.above) : nlohmann::ordered_json{{"psd", false}}}});
  }
  auto& curves = j["curves"] = nlohmann::ordered_json::array();
  for (const numeric::MapCurve& c : m.curves) {
    nlohmann::ordered_json xy = nlohmann::ordered_json::array();
    for (std::size_t k : c.points) {
      const auto [x, y] = numeric::position(m, m.boundaries[k]);
      xy.push_back({x, y});
    }
    using Kind = numeric::MapCurve::Kind;
    nlohmann::ordered_json curve{{"kind", c.kind == Kind::Superball ? "superball edge" : c.kind == Kind::Psd ? "psd edge" : "case change"}};
    if (c.kind == Kind::Case) curve["cases"] = {Vocabulary::paper().case_name(c.first), Vocabulary::paper().case_name(c.second)};
    curve["closed"] = c.closed;
    curve["boundaries"] = c.points;
    curve["points"] = std::move(xy);
    curves.push_back(std::move(curve));
  }
  return j;
}

/// The grid values of \p a in double (CLN, on the calling thread).
std::vector<double> doubles(const numeric::Axis& a) {
  std::vector<double> v;
  for (const cln::cl_RA& x : a.values()) v.push_back(cln::double_approx(x));
  return v;
}

}  // namespace

nlohmann::ordered_json map_json(const Map& m, const Scene& scene, const std::string& precision) {
  nlohmann::ordered_json j = map_json_frame(m, scene, precision);
  const std::vector<double> xs = doubles(m.x), ys = doubles(m.y);
  auto& points = j["points"];
  for (int jy = 0; jy < m.y.steps; ++jy)
    for (int i = 0; i < m.x.steps; ++i) points.push_back(point_json(m.at(i, jy), i, jy, xs[static_cast<std::size_t>(i)], ys[static_cast<std::size_t>(jy)]));
  return j;
}

void write_map_json(const Map& m, const Scene& scene, const std::string& precision, const nlohmann::ordered_json& extra, int threads,
                    const TextSink& sink) {
  nlohmann::ordered_json j = map_json_frame(m, scene, precision);
  for (const auto& [key, value] : extra.items()) j[key] = value;
  const std::string frame = j.dump(1) + "\n";
  // The points go where the frame's empty array is (a line of the document's own members: no string holds a line break).
  const std::string empty = "\n \"points\": []";
  const std::size_t at = frame.find(empty);
  if (at == std::string::npos) throw std::logic_error("write_map_json(): no points in the frame");
  sink(std::string_view(frame).substr(0, at + empty.size() - 1));
  // Each point's member texts from dump(1) of its parts, so that the bytes are those of map_json().dump(1):
  // the numbers of the axes made once, a region's members on first use by each thread.
  const std::vector<double> xd = doubles(m.x), yd = doubles(m.y);
  std::vector<std::string> xs, ys;
  for (double v : xd) xs.push_back(nlohmann::ordered_json(v).dump());
  for (double v : yd) ys.push_back(nlohmann::ordered_json(v).dump());
  const auto nx = static_cast<std::size_t>(m.x.steps);
  using Regions = std::vector<std::pair<Region, std::string>>;
  in_blocks<Regions>(m.points.size(), threads, [&](Regions& regions, std::string& out, std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to; ++k) {
      const MapPoint& p = m.points[k];
      out += k == 0 ? "\n  {\n   \"i\": " : ",\n  {\n   \"i\": ";
      out += std::to_string(k % nx);
      out += ",\n   \"j\": ";
      out += std::to_string(k / nx);
      out += ",\n   \"x\": ";
      out += xs[k % nx];
      out += ",\n   \"y\": ";
      out += ys[k / nx];
      if (!p.admissible) {
        out += ",\n   \"psd\": false\n  }";
        continue;
      }
      out += ",\n   \"psd\": true,\n";
      out += cached(regions, p.region, [&] { return members_text(region_json(p.region), 2); });
      out += ",\n   \"U1_over_a\": ";
      out += std::isnan(p.ratio) ? std::string("null") : nlohmann::ordered_json(p.ratio).dump();
      out += ",\n   \"status\": ";
      out += nlohmann::ordered_json(numeric::to_string(p.status)).dump();
      out += "\n  }";
    }
  }, sink);
  sink("\n ]");
  sink(std::string_view(frame).substr(at + empty.size()));
}

std::string map_summary(const Map& m, const Scene& scene, const std::string& precision) {
  std::ostringstream os;
  auto axis = [](const numeric::Axis& a) {
    return a.parameter.key() + " from " + numeric::to_string(a.from) + " to " + numeric::to_string(a.to) + " (" + std::to_string(a.steps) +
           " values)";
  };
  os << "map of " << scene.origin << ": " << axis(m.x) << " by " << axis(m.y) << ", in " << precision << '\n';
  std::size_t solved = 0, superball = 0, failed = 0;
  double low = INFINITY, high = -INFINITY;
  for (const MapPoint& p : m.points) {
    if (!p.admissible) continue;
    ++solved;
    superball += p.region.superball;
    failed += p.status != numeric::Status::Success;
    if (!std::isnan(p.ratio)) low = std::min(low, p.ratio), high = std::max(high, p.ratio);
  }
  auto share = [](std::size_t k, std::size_t of) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f %%", of ? 100.0 * static_cast<double>(k) / static_cast<double>(of) : 0.0);
    return std::string(buf);
  };
  os << "points: " << m.points.size() << ", solved " << solved;
  if (solved < m.points.size()) os << " (M is not positive semi-definite at the other " << m.points.size() - solved << ": not solved)";
  os << '\n';
  for (const CaseCount& c : case_counts(m))
    os << "  case " << Vocabulary::paper().case_name(c.closed) << ' ' << c.closed.to_string() << ": " << c.in << " points ("
       << share(c.in, solved) << "), superball at " << c.superball << '\n';
  os << "superball (U1+ > a): " << superball << " points (" << share(superball, solved) << " of the solved)";
  if (low <= high) os << "; U1+/a from " << numeric::to_string(low, 6) << " to " << numeric::to_string(high, 6);
  os << '\n';
  if (failed) os << "status not success: " << failed << " points\n";
  double widest = 0;
  for (const MapBoundary& b : m.boundaries) widest = std::max(widest, cln::double_approx(b.high - b.low));
  os << "boundaries: " << m.boundaries.size() << " points located exactly (widest bracket " << numeric::to_string(widest, 3) << ") on "
     << m.curves.size() << " curves\n";
  for (const numeric::MapCurve& c : m.curves) {
    const auto [x0, y0] = numeric::position(m, m.boundaries[c.points.front()]);
    const auto [x1, y1] = numeric::position(m, m.boundaries[c.points.back()]);
    os << "  " << curve_text(c) << ": " << c.points.size() << " points, "
       << (c.closed ? "closed, through (" : "from (") << numeric::to_string(x0, 6) << ", " << numeric::to_string(y0, 6) << ")";
    if (!c.closed) os << " to (" << numeric::to_string(x1, 6) << ", " << numeric::to_string(y1, 6) << ")";
    os << '\n';
  }
  return os.str();
}

std::string map_figure_data(const Map& m, const std::vector<MapMark>& marks, const std::vector<std::pair<double, double>>& derived) {
  const std::vector<ContactSet> cases = cases_present(m);
  auto colour = [&](const MapPoint& p) {
    if (!p.admissible) return rgb(kNotPsd);
    const auto k = std::find(cases.begin(), cases.end(), p.region.closed) - cases.begin();
    const Rgb c = rgb(kColours[k % kColourCount]);
    return p.region.superball ? c : pale(c);
  };
  std::ostringstream os;
  os.precision(17);
  const std::vector<double> xs = doubles(m.x), ys = doubles(m.y);
  os << "# index 0: x y r g b, the regions\n";
  for (int j = 0; j < m.y.steps; ++j) {
    for (int i = 0; i < m.x.steps; ++i) {
      const Rgb c = colour(m.at(i, j));
      os << xs[static_cast<std::size_t>(i)] << ' ' << ys[static_cast<std::size_t>(j)] << ' ' << c.r << ' ' << c.g << ' ' << c.b << '\n';
    }
    os << '\n';
  }
  os << "\n# index 1: x y U1+/a (NaN where M is not positive semi-definite)\n";
  for (int j = 0; j < m.y.steps; ++j) {
    for (int i = 0; i < m.x.steps; ++i) {
      const MapPoint& p = m.at(i, j);
      os << xs[static_cast<std::size_t>(i)] << ' ' << ys[static_cast<std::size_t>(j)] << ' ' << (p.admissible ? number(p.ratio) : std::string("NaN")) << '\n';
    }
    os << '\n';
  }
  os << "\n# index 2: marks\n";
  for (const MapMark& k : marks) os << k.x << ' ' << k.y << ' ' << quoted(k.label) << '\n';
  if (marks.empty()) os << "NaN NaN \"\"\n";
  os << "\n\n# index 3: zeros of the derived conditions\n";
  for (const auto& [x, y] : derived) os << x << ' ' << y << '\n';
  if (derived.empty()) os << "NaN NaN\n";
  for (std::size_t c = 0; c < m.curves.size(); ++c) {
    os << "\n\n# index " << kFirstCurve + c << ": " << curve_text(m.curves[c]) << '\n';
    for (std::size_t k : m.curves[c].points) {
      const auto [x, y] = numeric::position(m, m.boundaries[k]);
      os << x << ' ' << y << '\n';
    }
    if (m.curves[c].closed) {
      const auto [x, y] = numeric::position(m, m.boundaries[m.curves[c].points.front()]);
      os << x << ' ' << y << '\n';
    }
  }
  return os.str();
}

namespace {

/// The opening of a figure over the plane of \p x and \p y (map and drop map): terminal, output, ranges, axis labels,
/// tics and fill style; numbers in 17 digits from here on.
void plane_preamble(std::ostringstream& gp, const numeric::Axis& x, const numeric::Axis& y, const std::string& terminal,
                    const std::string& output) {
  const double x0 = cln::double_approx(x.from), x1 = cln::double_approx(x.to);
  const double y0 = cln::double_approx(y.from), y1 = cln::double_approx(y.to);
  gp.precision(17);
  gp << "set terminal " << terminal << "\nset output " << output << '\n'
     << "set xrange [" << std::min(x0, x1) << ':' << std::max(x0, x1) << "] noextend\n"
     << "set yrange [" << std::min(y0, y1) << ':' << std::max(y0, y1) << "] noextend\n"
     << "set xlabel " << quoted(axis_label(x.parameter.key())) << "\nset ylabel " << quoted(axis_label(y.parameter.key())) << '\n'
     << "set tics out nomirror\nset border lw 1\nset style fill solid 1.0 noborder\n";
}

}  // namespace

std::string map_figure_script(const Map& m, const std::vector<MapMark>& marks, bool derived, const std::string& title,
                              const std::string& data, const std::string& terminal, const std::string& output) {
  const std::vector<ContactSet> cases = cases_present(m);
  const bool not_psd = std::any_of(m.points.begin(), m.points.end(), [](const MapPoint& p) { return !p.admissible; });
  const std::string d = quoted(data);
  std::ostringstream gp;
  plane_preamble(gp, m.x, m.y, terminal, output);
  // The contour lines of U1+/a, into a datablock, before the panels.
  double low = INFINITY, high = -INFINITY;
  for (const MapPoint& p : m.points)
    if (p.admissible && !std::isnan(p.ratio)) low = std::min(low, p.ratio), high = std::max(high, p.ratio);
  const bool contours = low < high && std::isfinite(low) && std::isfinite(high);
  double step = 0;  // about 8 contour levels, at round values
  if (contours) {
    const double raw = (high - low) / 8, magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    step = raw / magnitude < 2 ? 2 * magnitude : raw / magnitude < 5 ? 5 * magnitude : 10 * magnitude;
    gp << "set contour base\nunset surface\nset view map\nset cntrparam linear\nset cntrparam levels incremental "
       << std::ceil(low / step) * step << ',' << step << ',' << high << "\nset table $contours\nsplot " << d
       << " index 1 using 1:2:3 with lines notitle\nunset table\nunset contour\nset surface\n";
  }
  // Two panels of the same size side by side, the legend under both.
  gp << "set multiplot title " << quoted(title) << " font ',13'\n"
     << "set tmargin at screen 0.89\nset bmargin at screen " << kLegendTop + 0.1 << '\n'
     << "set lmargin at screen 0.06\nset rmargin at screen 0.45\n";
  // Left: the cases.
  gp << "set title 'Evolution cases (full colour: superball U_1^+ > a; pale: not)'\n"
     << "set key at screen 0.06, screen " << kLegendTop << " left top vertical reverse Left maxrows 4 samplen 2 spacing 1.15 width 3 font ',10'\n"
     << "plot " << d << " index 0 using 1:2:3:4:5 with rgbimage notitle";
  const Vocabulary& v = Vocabulary::paper();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::string name = v.case_name(cases[k]);
    const auto named = std::find_if(v.cases().begin(), v.cases().end(), [&](const NamedCase& c) { return c.closed == cases[k]; });
    gp << ", NaN with boxes lc rgb '" << kColours[k % kColourCount] << "' title "
       << quoted("case " + name + (named != v.cases().end() && cases[k].bodies() == v.bodies() ? ": " + named->description : ""));
  }
  if (not_psd) gp << ", NaN with boxes lc rgb '" << kNotPsd << "' title 'M not PSD'";
  // Each kind of curve, with its legend entry on its first curve.
  using Kind = numeric::MapCurve::Kind;
  std::vector<bool> legend(3, false);
  for (std::size_t c = 0; c < m.curves.size(); ++c) {
    const Kind kind = m.curves[c].kind;
    const auto k = static_cast<std::size_t>(kind);
    const char* style = kind == Kind::Superball ? "lw 3 lc rgb 'black'" : kind == Kind::Psd ? "lw 1.5 lc rgb '#606060' dt 2" : "lw 1.5 lc rgb '#303030'";
    const char* name = kind == Kind::Superball ? "superball edge (exact)" : kind == Kind::Psd ? "edge of M PSD (exact)" : "case change (exact)";
    gp << ", " << d << " index " << kFirstCurve + c << " using 1:2 with lines " << style << ' ' << (legend[k] ? std::string("notitle") : "title " + quoted(name));
    legend[k] = true;
  }
  if (derived) gp << ", " << d << " index 3 using 1:2 with points pt 6 ps 0.7 lw 1 lc rgb '#D01010' title 'derived conditions (symbolic)'";
  if (!marks.empty())
    gp << ", " << d << " index 2 using 1:2 with points pt 7 ps 1.2 lc rgb 'black' notitle, " << d
       << " index 2 using 1:2:3 with labels left offset 0.8,0.5 font ',10' notitle";
  gp << '\n';
  // Right: U1+/a.
  gp << "set lmargin at screen 0.55\nset rmargin at screen 0.91\nunset key\n"
     << "set object 1 rectangle from graph 0, graph 0 to graph 1, graph 1 behind fc rgb '" << kNotPsd << "' fs solid noborder\n"
     << "set title " << quoted(std::string("U_1^+ / a") + (contours ? " (white: contours every " + number(step, 3) + "; " : " (") +
                               "black: U_1^+ = a, exact)") << '\n'

     << "set palette defined (0 '#0D0887', 1 '#6A00A8', 2 '#B12A90', 3 '#E16462', 4 '#FCA636', 5 '#F0F921')\n"
     << "set cbtics out nomirror\n"
     << "plot " << d << " index 1 using 1:2:3 with image notitle";
  if (contours) gp << ", $contours using 1:2 with lines lw 1 lc rgb '#FFFFFF' notitle";
  for (std::size_t c = 0; c < m.curves.size(); ++c)
    if (m.curves[c].kind == numeric::MapCurve::Kind::Superball) gp << ", " << d << " index " << kFirstCurve + c << " using 1:2 with lines lw 3 lc rgb 'black' notitle";
  if (!marks.empty()) gp << ", " << d << " index 2 using 1:2 with points pt 7 ps 1.2 lc rgb 'white' notitle";
  gp << "\nunset multiplot\n";
  return gp.str();
}

std::vector<std::string> drop_map_labels(const numeric::DropMap& m) {
  std::vector<std::string> labels;
  for (const numeric::DropPoint& p : m.points)
    if (std::find(labels.begin(), labels.end(), p.label) == labels.end()) labels.push_back(p.label);
  return labels;
}

std::string drop_map_csv(const numeric::DropMap& m) {
  std::ostringstream os;
  os << m.x.parameter.key() << ',' << m.y.parameter.key() << ",top_apex_ratio,events,end,label\n";
  const std::vector<std::string> xs = decimals(m.x, 0, m.x.steps, 1), ys = decimals(m.y, 0, m.y.steps, 1);
  for (int j = 0; j < m.y.steps; ++j) {
    const std::string& y = ys[static_cast<std::size_t>(j)];
    for (int i = 0; i < m.x.steps; ++i) {
      const numeric::DropPoint& p = m.at(i, j);
      os << xs[static_cast<std::size_t>(i)] << ',' << y << ',' << number(p.ratio) << ',' << p.events << ',' << p.end << ',' << csv_field(p.label) << '\n';
    }
  }
  return os.str();
}

nlohmann::ordered_json drop_map_json(const numeric::DropMap& m, const Scene& scene, const std::string& precision) {
  nlohmann::ordered_json j;
  j["scene"] = scene.origin;
  j["title"] = scene.title;
  j["precision"] = precision;
  for (const numeric::Axis* a : {&m.x, &m.y})
    j[a == &m.x ? "x" : "y"] = {{"key", a->parameter.key()}, {"from", numeric::to_string(a->from)}, {"to", numeric::to_string(a->to)}, {"steps", a->steps}};
  const std::vector<std::string> labels = drop_map_labels(m);
  j["labels"] = labels;
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  for (int jy = 0; jy < m.y.steps; ++jy)
    for (int i = 0; i < m.x.steps; ++i) {
      const numeric::DropPoint& p = m.at(i, jy);
      points.push_back({{"i", i},
                        {"j", jy},
                        {"label", std::find(labels.begin(), labels.end(), p.label) - labels.begin()},
                        {"top_apex_ratio", p.ratio},
                        {"events", p.events},
                        {"end", p.end}});
    }
  j["points"] = std::move(points);
  j["boundaries"] = drop_map_no_boundaries;
  return j;
}

std::string drop_map_summary(const numeric::DropMap& m, const Scene& scene, const std::string& precision) {
  std::ostringstream os;
  auto axis = [](const numeric::Axis& a) {
    return a.parameter.key() + " from " + numeric::to_string(a.from) + " to " + numeric::to_string(a.to) + " (" + std::to_string(a.steps) +
           " values)";
  };
  os << "drop map of " << scene.origin << ": " << axis(m.x) << " by " << axis(m.y) << ", in " << precision << '\n';
  os << "points: " << m.points.size() << "; value: the top body's apex ratio; label: its collisions in time order (CONTACTS:CASE, a run as *k)\n";
  const std::vector<std::string> labels = drop_map_labels(m);
  double low = INFINITY, high = -INFINITY;
  std::size_t unfinished = 0;
  for (std::size_t k = 0; k < labels.size(); ++k) {
    std::size_t in = 0;
    double lo = INFINITY, hi = -INFINITY;
    for (const numeric::DropPoint& p : m.points)
      if (p.label == labels[k]) ++in, lo = std::min(lo, p.ratio), hi = std::max(hi, p.ratio);
    os << "  L" << k + 1 << ": " << in << (in == 1 ? " point" : " points") << ", ratio " << numeric::to_string(lo, 6) << " to " << numeric::to_string(hi, 6) << ": " << labels[k]
       << '\n';
  }
  for (const numeric::DropPoint& p : m.points) {
    low = std::min(low, p.ratio), high = std::max(high, p.ratio);
    unfinished += !numeric::drop_finished(p.end);
  }
  os << "top apex ratio from " << numeric::to_string(low, 6) << " to " << numeric::to_string(high, 6) << '\n';
  if (unfinished) os << "runs ended by max-events or an unsolved collision: " << unfinished << " points\n";
  std::size_t changes = 0;
  for (int j = 0; j < m.y.steps; ++j)
    for (int i = 0; i < m.x.steps; ++i) {
      if (i + 1 < m.x.steps && m.at(i, j).label != m.at(i + 1, j).label) ++changes;
      if (j + 1 < m.y.steps && m.at(i, j).label != m.at(i, j + 1).label) ++changes;
    }
  os << "neighbouring points of different labels: " << changes << "; boundaries: " << drop_map_no_boundaries << '\n';
  return os.str();
}

std::string drop_map_figure_data(const numeric::DropMap& m) {
  const std::vector<std::string> labels = drop_map_labels(m);
  const std::vector<double> xs = doubles(m.x), ys = doubles(m.y);
  std::ostringstream os;
  os.precision(17);
  for (int index = 0; index < 2; ++index) {
    os << (index == 0 ? "# index 0: x y r g b, the colour of the label\n" : "\n\n# index 1: x y top apex ratio\n");
    for (int j = 0; j < m.y.steps; ++j) {
      for (int i = 0; i < m.x.steps; ++i) {
        const numeric::DropPoint& p = m.at(i, j);
        os << xs[static_cast<std::size_t>(i)] << ' ' << ys[static_cast<std::size_t>(j)] << ' ';
        if (index == 0) {
          const Rgb c = rgb(kColours[(std::find(labels.begin(), labels.end(), p.label) - labels.begin()) % kColourCount]);
          os << c.r << ' ' << c.g << ' ' << c.b << '\n';
        } else {
          os << number(p.ratio) << '\n';
        }
      }
      os << '\n';
    }
  }
  return os.str();
}

std::string drop_map_figure_script(const numeric::DropMap& m, const std::string& title, const std::string& data, const std::string& terminal,
                                   const std::string& output) {
  const std::vector<std::string> labels = drop_map_labels(m);
  const std::string d = quoted(data);
  std::ostringstream gp;
  plane_preamble(gp, m.x, m.y, terminal, output);
  gp << "set multiplot title " << quoted(title) << " font ',13'\n"
     << "set tmargin at screen 0.89\nset bmargin at screen " << kLegendTop + 0.1 << '\n'
     << "set lmargin at screen 0.06\nset rmargin at screen 0.45\n";
  // Left: the labels, each in its colour (cycled after 10), named in the legend.
  gp << "set title 'Sequences of collisions (labels)'\n"
     << "set key at screen 0.06, screen " << kLegendTop << " left top vertical reverse Left maxrows 4 samplen 2 spacing 1.15 width 3 font ',9'\n"
     << "plot " << d << " index 0 using 1:2:3:4:5 with rgbimage notitle";
  for (std::size_t k = 0; k < labels.size(); ++k) {
    const std::string name = labels[k].size() > 60 ? labels[k].substr(0, 57) + "..." : labels[k];
    gp << ", NaN with boxes lc rgb '" << kColours[k % kColourCount] << "' title " << quoted("L" + std::to_string(k + 1) + ": " + name) << " noenhanced";
  }
  gp << "\nunset key\n";
  // Right: the top apex ratio.
  gp << "set lmargin at screen 0.55\nset rmargin at screen 0.91\n"
     << "set title 'Top body apex ratio (apex / release height)'\n"
     << "set palette defined (0 '#0D0887', 1 '#6A00A8', 2 '#B12A90', 3 '#E16462', 4 '#FCA636', 5 '#F0F921')\n"
     << "set cbtics out nomirror\n"
     << "plot " << d << " index 1 using 1:2:3 with image notitle\nunset multiplot\n";
  return gp.str();
}

}  // namespace superball::present
