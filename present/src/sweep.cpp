#include "superball/present/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>

#include "superball/cases/vocabulary.hpp"
#include "text_blocks.hpp"

namespace superball::present {

using detail::csv_field;

/// The rows a task of write_sweep_rows() formats: the command hands it its
/// blocks of 4096 values, which the threads share four tasks each.
constexpr std::size_t rows_per_task = 1024;

namespace {

/// What a reader of a result says of text that is not that result.
std::invalid_argument damaged(const std::string& what) { return std::invalid_argument("a damaged result (" + what + ")"); }

/// Whether \p name is the name of a case of a scene of \p n bodies
/// (Vocabulary::case_name() of one of its contact sets); the set in \p set.
bool case_of_scene(const std::string& name, int n, ContactSet& set) {
  const Vocabulary& v = Vocabulary::paper();
  if (name.size() >= 2 && name.front() == '{' && name.back() == '}') {
    try {
      set = ContactSet::parse(name.substr(1, name.size() - 2), n);
    } catch (const std::exception&) {
      return false;
    }
    return v.case_name(set) == name;
  }
  for (const NamedCase& c : v.cases())
    if (c.name == name && c.closed.bodies() == n) return set = c.closed, true;
  return false;
}

/// The cases of a scene of \p n bodies named in a text read back, each name
/// checked once.
class SceneCases {
 public:
  explicit SceneCases(int n) : n_(n) {}
  /// The contact set of the case called \p name; damaged() when no case of the scene is called so.
  const ContactSet& of(std::string_view name) {
    const auto it = known_.find(name);
    if (it != known_.end()) return it->second;
    ContactSet set;
    if (!case_of_scene(std::string(name), n_, set)) throw damaged("'" + std::string(name.substr(0, 40)) + "' is not a case of this scene");
    return known_.emplace(std::string(name), set).first->second;
  }

 private:
  int n_;
  std::map<std::string, ContactSet, std::less<>> known_;
};

/// The fields of \p line split at each \p sep ("," or two spaces), into
/// \p out (reused: no allocation per row); a CSV field in quotes
/// ("{1-2,2-3}", no quote inside) kept whole, without its quotes.
void fields(std::string_view line, std::string_view sep, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t start = 0;
  bool quoted = false;
  for (std::size_t k = 0; k <= line.size(); ++k) {
    if (k < line.size() && sep == "," && line[k] == '"') {
      quoted = !quoted;
    } else if (k == line.size() || (!quoted && line.compare(k, sep.size(), sep) == 0)) {
      std::string_view f = line.substr(start, k - start);
      if (f.size() >= 2 && f.front() == '"' && f.back() == '"') f = f.substr(1, f.size() - 2);
      out.push_back(f);
      start = k + sep.size();
      k += sep.size() - 1;
    }
  }
}

/// A number printed by the sweep: the whole of \p text; nullopt otherwise.
std::optional<double> number(const std::string& text) {
  char* end = nullptr;
  const double v = text.empty() ? 0 : std::strtod(text.c_str(), &end);
  if (text.empty() || *end) return std::nullopt;
  return v;
}

/// The lines of \p text, each given to line(): std::invalid_argument when the last is not whole.
template <class Line>
void each_line(std::string_view text, const Line& line) {
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t eol = text.find('\n', at);
    if (eol == std::string_view::npos) throw damaged("its last line is cut");
    line(text.substr(at, eol - at));
    at = eol + 1;
  }
}

}  // namespace

std::string sweep_header(const std::string& key, int bodies, bool csv) {
  const std::string sep = csv ? "," : "  ";
  std::string text = key;
  for (int i = 1; i <= bodies; ++i) text += sep + "U" + std::to_string(i);
  return text + sep + "case" + (csv ? ",status\n" : "\n");
}

void write_sweep_rows(const numeric::Range& r, std::size_t first, const std::vector<numeric::SweepPoint>& points, bool csv, int threads,
                      const TextSink& sink) {
  if (points.empty()) return;
  const std::string sep = csv ? "," : "  ";
  const std::vector<std::string> values = detail::decimals(r.from, r.to, r.steps, static_cast<int>(first), static_cast<int>(points.size()), threads);
  // A case's field, made on first use by each thread.
  using Cases = std::vector<std::pair<ContactSet, std::string>>;
  detail::in_blocks<Cases>(points.size(), threads, [&](Cases& cases, std::string& out, std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to; ++k) {
      const numeric::SweepPoint& p = points[k];
      out += values[k];
      for (double w : p.velocities_after) {
        out += sep;
        numeric::append_to(out, w, csv ? 17 : 8);
      }
      out += sep;
      out += detail::cached(cases, p.closed, [&] {
        const std::string name = Vocabulary::paper().case_name(p.closed);
        return csv ? csv_field(name) : name;
      });
      // CSV: every row has the header's fields; the table names only a status that is not success.
      if (csv || p.status != numeric::Status::Success) {
        out += sep;
        out += numeric::to_string(p.status);
      }
      out += '\n';
    }
  }, sink, rows_per_task);
}

std::string switch_rows(const std::string& key, const std::vector<numeric::SwitchPoint>& points, bool csv) {
  const Vocabulary& v = Vocabulary::paper();
  std::string text;
  for (const numeric::SwitchPoint& s : points) {
    const std::string at = detail::decimal((s.low + s.high) / 2), width = detail::decimal(s.high - s.low, 3);
    if (csv)
      text += at + ',' + width + ',' + csv_field(v.case_name(s.below)) + ',' + csv_field(v.case_name(s.above)) + '\n';
    else
      text += key + " = " + at + "  (bracket width " + width + "): case " + v.case_name(s.below) + " " + s.below.to_string() + " -> case " +
              v.case_name(s.above) + " " + s.above.to_string() + '\n';
  }
  return text;
}

int check_sweep_rows(std::string_view text, int bodies, std::size_t size, bool csv) {
  const std::string sep = csv ? "," : "  ";
  const auto n = static_cast<std::size_t>(bodies);
  const std::string success = numeric::to_string(numeric::Status::Success);
  const std::set<std::string, std::less<>> statuses = {success, numeric::to_string(numeric::Status::NumericalIssue),
                                                       numeric::to_string(numeric::Status::NoConvergence)};
  SceneCases cases(bodies);
  std::vector<std::string_view> f;
  std::size_t rows = 0;
  int failures = 0;
  each_line(text, [&](std::string_view line) {  // VALUE U1 … Un CASE [STATUS]: the case and the status checked
    ++rows;
    fields(line, sep, f);
    if (f.size() != n + 3 && (csv || f.size() != n + 2)) throw damaged("a row of the wrong fields");
    cases.of(f[n + 1]);
    if (f.size() == n + 3) {
      if (!statuses.count(f.back()) || (!csv && f.back() == success))
        throw damaged("'" + std::string(f.back().substr(0, 40)) + "' is not a status");
      failures += f.back() != success;
    }
  });
  if (rows != size) throw damaged("not the rows of its block");
  return failures;
}

void check_switch_rows(std::string_view text, const std::string& key, int bodies, const cln::cl_RA& low, const cln::cl_RA& high, bool csv) {
  const double lo = cln::double_approx(low), hi = cln::double_approx(high), slack = 1e-12 * std::max({std::abs(lo), std::abs(hi), hi - lo});
  SceneCases cases(bodies);
  std::vector<std::string_view> f;
  each_line(text, [&](std::string_view line) {  // AT  (bracket width W): case B {..} -> case A {..}, or AT,W,B,A.
    std::string below, above, where, width;
    if (csv) {
      fields(line, ",", f);
      if (f.size() != 4) throw damaged("a switch point of the wrong fields");
      where = std::string(f[0]), width = std::string(f[1]), below = std::string(f[2]), above = std::string(f[3]);
      cases.of(below);
      cases.of(above);
    } else {
      const std::string start = key + " = ", mid = "  (bracket width ", cases_at = "): case ", arrow = " -> case ";
      const std::size_t m = line.find(mid), c = line.find(cases_at), a = line.find(arrow);
      if (line.rfind(start, 0) != 0 || m == std::string::npos || c == std::string::npos || a == std::string::npos || !(start.size() <= m && m < c && c < a))
        throw damaged("a switch point of the wrong form");
      where = std::string(line.substr(start.size(), m - start.size()));
      width = std::string(line.substr(m + mid.size(), c - m - mid.size()));
      for (auto [from, to, name] : {std::make_tuple(c + cases_at.size(), a, &below), std::make_tuple(a + arrow.size(), line.size(), &above)}) {
        const std::string both(line.substr(from, to - from));
        const std::size_t space = both.find(' ');
        *name = both.substr(0, space);
        const ContactSet& set = cases.of(*name);
        if (space == std::string::npos || both.substr(space + 1) != set.to_string())
          throw damaged("'" + both.substr(0, 40) + "' is not a case and its contacts");
      }
    }
    if (below == above) throw damaged("a switch point between a case and itself");
    const std::optional<double> x = number(where), w = number(width);
    if (!x || !(*x >= lo - slack && *x <= hi + slack))
      throw damaged("a switch point at " + where.substr(0, 40) + ", outside the values of its block (" + detail::decimal(low) + " to " +
                               detail::decimal(high) + ")");
    if (!w || !(*w > 0 && *w <= hi - lo + slack)) throw damaged("a bracket width of " + width.substr(0, 40));
  });
}

std::string switch_header(const std::string& key) { return key + ",bracket_width,case_below,case_above\n"; }

std::string drop_sweep_header(const std::string& key, bool csv) {
  const std::string sep = csv ? "," : "  ";
  return key + sep + "top_apex_ratio" + sep + "events" + sep + "end" + sep + "label\n";
}

std::string drop_rows(const std::vector<cln::cl_RA>& values, const std::vector<numeric::DropPoint>& points, bool csv) {
  const std::string sep = csv ? "," : "  ";
  std::string text;
  for (std::size_t k = 0; k < points.size() && k < values.size(); ++k) {
    const numeric::DropPoint& p = points[k];
    text += detail::decimal(values[k], 10) + sep;
    numeric::append_to(text, p.ratio, csv ? 17 : 9);
    text += sep + std::to_string(p.events) + sep + p.end + sep + (csv ? csv_field(p.label) : p.label) + '\n';
  }
  return text;
}

}  // namespace superball::present
