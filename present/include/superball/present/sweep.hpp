#pragma once
/// \file sweep.hpp
/// A sweep along one parameter (numeric/sweep.hpp) as people and programs
/// read it: a table or CSV of the velocities after the collision, one row
/// per value, formatted on threads and handed over in blocks as they are
/// made; and the rows of a sweep of drops.  What `superball sweep` prints.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "superball/numeric/range.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/present/export.hpp"
#include "superball/present/text_sink.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// The first line of the rows of a sweep of \p key over a scene of \p bodies
/// bodies: KEY, U1 … Un, case, and status in CSV (\p csv: fields separated
/// by commas, else by two spaces).
std::string sweep_header(const std::string& key, int bodies, bool csv);

/// The rows of \p points, which are the values first, first + 1, … of the
/// range \p r (numeric::linspace(r.from, r.to, r.steps)), one a line:
/// the value (exact, to 10 significant digits), U1 … Un (17 significant
/// digits in CSV, 8 in the table), the paper's name of the case (in CSV
/// quoted when it holds a comma: "{1-2,2-3}"), then the status: in CSV
/// always, in the table only when it is not success.  Formatted on \p threads
/// threads (0: all cores) and given to \p sink in order, a block of rows at
/// a time; the text does not depend on \p threads.
void write_sweep_rows(const numeric::Range& r, std::size_t first, const std::vector<numeric::SweepPoint>& points, bool csv, int threads,
                      const TextSink& sink);

/// The switch points of a sweep of \p key (numeric::switch_points()), one a
/// line: in CSV "AT,WIDTH,BELOW,ABOVE" (the middle of the bracket to 17
/// significant digits, its width to 3, the paper's names of the cases, quoted
/// when they hold a comma); in text "KEY = AT  (bracket width WIDTH): case
/// BELOW {…} -> case ABOVE {…}" with each case's closed contacts.
std::string switch_rows(const std::string& key, const std::vector<numeric::SwitchPoint>& points, bool csv);
/// The first line of switch_rows() in CSV: KEY,bracket_width,case_below,case_above.
std::string switch_header(const std::string& key);

/// Reads back the rows of write_sweep_rows() for \p size values of a scene
/// of \p bodies bodies (text from a file: a checkpoint, a part) and checks
/// them: \p size whole lines, each with the fields of the header, the name of
/// a case of this scene, and a status (in the table only one that is not
/// success).  Returns the number of rows whose status is not success;
/// std::invalid_argument("a damaged result (WHAT)") otherwise.
int check_sweep_rows(std::string_view text, int bodies, std::size_t size, bool csv);

/// Reads back switch_rows() of a sweep of \p key over a scene of \p bodies
/// bodies, whose values ran from \p low to \p high, and checks them: each
/// line of its form, its two cases cases of this scene that differ (and in
/// the text their contacts), its point inside [low, high] and its bracket's
/// width in (0, high − low]; std::invalid_argument("a damaged result
/// (WHAT)") otherwise.
void check_switch_rows(std::string_view text, const std::string& key, int bodies, const cln::cl_RA& low, const cln::cl_RA& high, bool csv);

/// The first line of the rows of a sweep of drops (drop_rows()).
std::string drop_sweep_header(const std::string& key, bool csv);

/// The rows of a sweep of drops: per value of \p values (exact; points[k]
/// is values[k]'s) the value to 10 significant digits, the top body's apex
/// ratio (17 significant digits in CSV, 9 in the table), the number of
/// collisions, why the run ended and its label (numeric::drop_label(); in
/// CSV quoted when it holds a comma).
std::string drop_rows(const std::vector<cln::cl_RA>& values, const std::vector<numeric::DropPoint>& points, bool csv);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
