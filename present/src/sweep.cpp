#include "superball/present/sweep.hpp"

#include "superball/cases/vocabulary.hpp"
#include "text_blocks.hpp"

namespace superball::present {

using detail::csv_field;

/// The rows a task of write_sweep_rows() formats: the command hands it its
/// blocks of 4096 values, which the threads share four tasks each.
constexpr std::size_t rows_per_task = 1024;

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
  const std::string success = numeric::to_string(numeric::Status::Success);
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
