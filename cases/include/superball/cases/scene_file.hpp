#pragma once
/// \file scene_file.hpp
/// The one loader of scene files (TOML).  Every structural check happens here;
/// numerical admissibility (M positive semi-definite) is checked by the
/// numeric backend at its entry point.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "superball/cases/error.hpp"
#include "superball/cases/model.hpp"
#include "superball/cases/export.hpp"
SUPERBALL_CASES_API_BEGIN

namespace superball {

/// Largest scene file read (bytes).  A scene is a few hundred bytes; long
/// chains are generated, not listed.
inline constexpr std::size_t max_scene_file_bytes = 4u << 20;
/// Largest number of bodies a scene file may list.
inline constexpr int max_scene_bodies = 100000;
/// Deepest nesting of tables, arrays and dotted keys in a scene file: a key
/// `a.b.c` is 3 levels, the keys after a `[a.b]` header start 2 levels down,
/// the elements of an array and the keys of an inline table one level below
/// it.  The format itself needs 5 (`[dissipation]`, `coupling = [ { pairs =
/// [...] } ]`); the limit is checked before the TOML parser, which recurses
/// once per level, runs.
inline constexpr int max_scene_nesting = 16;
/// Largest `[drop] max_events` a scene may ask for: a drop keeps every
/// collision (about 150 + 40 n bytes each, n bodies, and about 1 kB of its
/// JSON), so 10⁶ of them is some 0.5 GB and a dozen seconds; 10⁸ was tens of
/// gigabytes, past what a machine holds.
inline constexpr long long max_drop_events = 1000000;
/// The name of standard input in messages and in Scene::origin.
inline constexpr std::string_view stdin_origin = "<stdin>";

/// Read and check a scene file.
///
/// Format (all keys optional unless said):
/// \code
/// title = "Paper 4.4"
/// drop_height = 0.5     # falling bodies move at -sqrt(2 g h) before
/// g = 9.81
/// fall_speed = 3.13209  # or give a = sqrt(2 g h) directly (not both)
/// [[body]]              # required, top to bottom, at least 2
/// mass = 0.001          # required: > 0, "inf" (inf, +inf) for a fixed bottom obstacle
/// velocity = 0          # overrides the fall
/// [dissipation]
/// K = { "1-2" = 7 }                       # diagonal of M
/// alpha = { "2" = -100 }                  # paper's α_k, n = 4 only
/// coupling = [ { pairs = ["1-2", "1-4"], value = -100 } ]
/// [drop]                # optional: the whole drop (bodies may then have gap = 0.01)
/// until = "apex"        # or seconds > 0
/// max_events = 10000    # 1 .. max_drop_events
/// distant = false
/// \endcode
/// Numbers may be TOML integers or floats (read exactly as written) or
/// strings holding a fraction "1/3".  Throws InputError naming the file, the
/// place and what is wrong, on one line (control characters of the file
/// escaped, see printable()).
///
/// \p path "-" reads standard input (named stdin_origin in messages); a FIFO
/// is read the same way, as a stream (its open waits for a writer).  At most
/// max_scene_file_bytes are accepted, and a stream is refused as soon as it
/// gives one byte more: never more than that is read.  A directory, a device
/// or a socket is refused before it is opened.
Scene load_scene(const std::string& path);

/// Same as load_scene() for text already in memory; \p origin names it in
/// messages.  A leading UTF-8 byte-order mark is skipped; text nesting deeper
/// than max_scene_nesting is refused (naming the line) before it is parsed.
Scene parse_scene(const std::string& text, const std::string& origin);

/// A scene as a structured value, as a front builds it from its own data
/// (Python's dicts and keywords) rather than as text: the tree of tables,
/// arrays and values of a scene file (docs/SCENES.md: `title`, `body` an
/// array of tables, `dissipation.K`, …).  Numbers are strings spelled as a
/// scene file reads them ("0.001", "1/3", "5e6", "inf"), read exactly.
struct SceneValue {
  /// What a value is: a table of named members, an array of items, a string (numbers too) or a boolean.
  enum class Kind { Table, Array, String, Boolean };
  Kind kind = Kind::Table;  ///< which of the fields below holds the value
  std::string text;                                         ///< Kind::String
  bool flag = false;                                        ///< Kind::Boolean
  std::vector<std::pair<std::string, SceneValue>> members;  ///< Kind::Table, in order
  std::vector<SceneValue> items;                            ///< Kind::Array
};

/// The scene of \p root, with every check of parse_scene() by the same
/// reader: the messages are a file's without its line and column
/// ("ORIGIN: body[2].mass: must be > 0 (got -1)").  A value nesting deeper
/// than max_scene_nesting is refused (naming the field) before it is read.
/// Throws InputError; \p origin names the scene in messages and in
/// Scene::origin.
Scene scene_from_value(const SceneValue& root, const std::string& origin);

/// The TOML text of \p scene, in the format load_scene() reads: numbers as
/// the user spelled them when that spelling is a TOML number, else as an exact
/// fraction string "p/q"; couplings of n = 4 by their α names; \p comment
/// (may be empty, may hold several lines) as leading '#' lines.  Reading the
/// text back gives the same scene (same exact values, same entries).
std::string write_scene(const Scene& scene, const std::string& comment = "");

}  // namespace superball

SUPERBALL_CASES_API_END
