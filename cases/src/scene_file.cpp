#include "superball/cases/scene_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <memory>
#include <set>
#include <sstream>
#include <vector>

#include "superball/cases/vocabulary.hpp"

namespace superball {
namespace {

/// Reads one TOML document and turns it into a Scene, with every message
/// prefixed by "origin:line:col: field: ".
class SceneReader {
 public:
  SceneReader(const std::string& text, std::string origin) : origin_(std::move(origin)) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines_.push_back(line);
  }

  Scene read(const toml::table& root) {
    Scene scene;
    scene.origin = origin_;
    check_keys(root, "", {"title", "drop_height", "g", "fall_speed", "body", "dissipation", "flight", "drop"});
    if (auto t = root.get("title")) {
      if (!t->is_string()) fail(*t, "title", "must be a string");
      scene.title = t->value<std::string>().value_or("");
    }
    if (auto n = root.get("drop_height")) {
      scene.drop_height = number(*n, "drop_height");
      if (scene.drop_height->is_negative()) fail(*n, "drop_height", "must be >= 0 (got " + scene.drop_height->text + ")");
    }
    if (auto n = root.get("g")) {
      scene.g = number(*n, "g");
      if (scene.g.is_negative() || scene.g.is_zero()) fail(*n, "g", "must be > 0 (got " + scene.g.text + ")");
    }
    if (auto n = root.get("fall_speed")) {
      if (scene.drop_height) fail(*n, "fall_speed", "give drop_height or fall_speed, not both");
      scene.fall_speed = number(*n, "fall_speed");
      if (scene.fall_speed->is_negative()) fail(*n, "fall_speed", "must be >= 0 (a speed; bodies fall at -fall_speed)");
    }
    read_bodies(root, scene);
    if (auto d = root.get("dissipation")) read_dissipation(*d, scene);
    if (auto f = root.get("flight")) {
      if (!f->is_table()) fail(*f, "flight", "must be a table");
      check_keys(*f->as_table(), "flight.", {"duration"});
      scene.flight.requested = true;
      if (const toml::node* d = f->as_table()->get("duration")) {
        scene.flight.duration = number(*d, "flight.duration");
        if (scene.flight.duration->is_negative() || scene.flight.duration->is_zero())
          fail(*d, "flight.duration", "must be > 0 seconds (got " + scene.flight.duration->text + ")");
      }
    }
    if (auto d = root.get("drop")) read_drop(*d, scene);
    return scene;
  }

 private:
  /// The [drop] table and the release positions it needs (drop_height > 0 over a fixed obstacle).
  void read_drop(const toml::node& node, Scene& scene) const {
    if (!node.is_table()) fail(node, "drop", "must be a table");
    const toml::table& t = *node.as_table();
    check_keys(t, "drop.", {"until", "max_events", "distant"});
    scene.drop.requested = true;
    if (const toml::node* u = t.get("until")) {
      const std::string bad = "must be \"apex\" or a time in seconds > 0";
      const bool apex = u->is_string() && *u->value<std::string>() == "apex";
      if (!apex) {
        if (u->is_string() && u->value<std::string>()->find_first_of("0123456789") == std::string::npos)
          fail(*u, "drop.until", bad + " (got \"" + *u->value<std::string>() + "\")");
        scene.drop.until = number(*u, "drop.until");
        if (scene.drop.until->is_negative() || scene.drop.until->is_zero()) fail(*u, "drop.until", bad + " (got " + scene.drop.until->text + ")");
      }
    }
    if (const toml::node* m = t.get("max_events")) {
      if (!m->is_integer()) fail(*m, "drop.max_events", std::string("must be a whole number from 1 to ") + std::to_string(max_drop_events) + " (got a " + type_name(*m) + ")");
      const long long v = *m->value<long long>();
      if (v < 1 || v > max_drop_events)
        fail(*m, "drop.max_events", "must be a whole number from 1 to " + std::to_string(max_drop_events) + " (got " + std::to_string(v) + ")");
      scene.drop.max_events = v;
    }
    if (const toml::node* d = t.get("distant")) {
      if (!d->is_boolean()) fail(*d, "drop.distant", std::string("must be true or false (got a ") + type_name(*d) + ")");
      scene.drop.distant = *d->value<bool>();
    }
    const bool fixed = !scene.bodies.empty() && scene.bodies.back().infinite;
    if (fixed && (!scene.drop_height || scene.drop_height->is_zero()))
      fail(t, "drop_height", "a drop onto a fixed obstacle needs drop_height > 0 (the lowest free body's height above it, m)");
  }

  [[noreturn]] void fail(const toml::node& at, const std::string& field, const std::string& what) const {
    fail_at(at.source(), field, what);
  }
  [[noreturn]] void fail_at(const toml::source_region& at, const std::string& field, const std::string& what) const {
    std::ostringstream os;
    os << origin_;
    if (at.begin.line > 0) os << ':' << at.begin.line << ':' << at.begin.column;
    os << ": " << field << ": " << what;
    throw InputError(printable(os.str()));
  }

  void check_keys(const toml::table& t, const std::string& prefix, std::set<std::string> allowed) const {
    for (const auto& [key, node] : t)
      if (!allowed.count(std::string(key.str()))) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail_at(key.source(), prefix + std::string(key.str()),
                "unknown key" + (list.empty() ? std::string(" (this table takes no keys)") : " (expected one of: " + list + ")"));
      }
  }

  /// The byte offset in \p line of toml++'s \p column, which counts code
  /// points from 1 (a tab is one, 'é' is one); npos past the end.
  static std::size_t byte_offset(const std::string& line, std::size_t column) {
    std::size_t at = 0;
    for (std::size_t c = 1; c < column; ++c) {
      if (at >= line.size()) return std::string::npos;
      ++at;
      while (at < line.size() && (static_cast<unsigned char>(line[at]) & 0xc0) == 0x80) ++at;  // continuation bytes
    }
    return at;
  }

  /// The exact spelling of a TOML number as it stands in the file (the text
  /// has no byte-order mark: parse_scene() removes it before toml++ and this
  /// reader see the text, so that both count from the same first byte).
  std::string spelling(const toml::node& node) const {
    const auto& src = node.source();
    if (src.begin.line == 0 || src.begin.line != src.end.line || src.begin.line > lines_.size())
      return "";
    const std::string& line = lines_[src.begin.line - 1];
    const std::size_t b = byte_offset(line, src.begin.column), e = byte_offset(line, src.end.column);
    return e <= line.size() && b < e ? line.substr(b, e - b) : "";
  }

  /// A number: TOML integer/float (exact as written) or a string "p/q".
  Number number(const toml::node& node, const std::string& field) const {
    std::string text;
    if (node.is_integer()) {
      text = std::to_string(*node.value<long long>());  // exact whatever the base it was written in (0x10, 0o20, 0b10000)
    } else if (node.is_floating_point()) {
      const double v = *node.value<double>();
      if (v != v || v - v != 0) fail(node, field, "must be a finite number (got " + spelling(node) + ")");
      text = spelling(node);  // the decimal digits as written, read exactly below
      if (text.empty()) text = std::to_string(v);
    } else if (node.is_string()) {
      text = *node.value<std::string>();
    } else {
      fail(node, field, std::string("must be a number or a fraction string like \"1/3\" (got a ") + type_name(node) + ")");
    }
    try {
      return Number::parse(text);
    } catch (const std::invalid_argument& e) {
      fail(node, field, without_function_prefix(e.what()));
    }
  }

  static const char* type_name(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::table: return "table";
      case toml::node_type::array: return "array";
      case toml::node_type::string: return "string";
      case toml::node_type::integer: return "integer";
      case toml::node_type::floating_point: return "float";
      case toml::node_type::boolean: return "boolean";
      default: return "date/time";
    }
  }

  void read_bodies(const toml::table& root, Scene& scene) const {
    const toml::node* bodies = root.get("body");
    if (!bodies) fail_at(root.source(), "body", "no [[body]] tables: a scene needs at least 2 bodies, top to bottom");
    const toml::array* list = bodies->as_array();
    if (!list || !list->is_array_of_tables()) fail(*bodies, "body", "must be an array of tables ([[body]])");
    if (list->size() < 2) fail(*bodies, "body", "a scene needs at least 2 bodies (got " + std::to_string(list->size()) + ")");
    if (list->size() > static_cast<std::size_t>(max_scene_bodies))
      fail(*bodies, "body", "at most " + std::to_string(max_scene_bodies) + " bodies (got " + std::to_string(list->size()) + ")");
    const bool falls = scene.drop_height || scene.fall_speed;
    for (std::size_t k = 0; k < list->size(); ++k) {
      const toml::table& t = *(*list)[k].as_table();
      const std::string field = "body[" + std::to_string(k + 1) + "]";
      check_keys(t, field + ".", {"mass", "velocity", "gap"});
      Body body;
      const toml::node* mass = t.get("mass");
      if (!mass) fail(t, field + ".mass", "missing: every body needs a mass (kg), or \"inf\" for a fixed obstacle");
      const std::string inf_text = mass->is_string() ? *mass->value<std::string>() : mass->is_floating_point() ? spelling(*mass) : "";
      const bool inf_spelled = inf_text == "inf" || inf_text == "+inf";
      if (inf_spelled) {
        if (k + 1 != list->size()) fail(*mass, field + ".mass", "only the bottom body may have infinite mass (a fixed obstacle)");
        body.infinite = true;
      } else {
        body.mass = number(*mass, field + ".mass");
        if (body.mass.is_negative() || body.mass.is_zero())
          fail(*mass, field + ".mass", "must be > 0 (got " + body.mass.text + ")");
      }
      if (const toml::node* v = t.get("velocity")) body.velocity = number(*v, field + ".velocity");
      if (const toml::node* g = t.get("gap")) {
        body.gap = number(*g, field + ".gap");
        if (body.gap->is_negative()) fail(*g, field + ".gap", "must be >= 0 m (got " + body.gap->text + ")");
        if (k + 1 == list->size()) fail(*g, field + ".gap", "the bottom body has no body below it (drop_height is the lowest free body's height)");
        if (k + 2 == list->size())
          fail(*g, field + ".gap", "body " + std::to_string(k + 1) + "'s distance to the bottom body is drop_height, not a gap (give drop_height)");
      }
      if (!body.velocity && !falls && !body.infinite)
        fail(t, field, "no velocity before the collision: give velocity, or drop_height / fall_speed for the scene");
      scene.bodies.push_back(body);
    }
  }

  Pair pair_in_range(const toml::node& at, const std::string& field, std::string_view text, int n) const {
    Pair p;
    try {
      p = Pair::parse(text);
    } catch (const std::invalid_argument& e) {
      fail(at, field, without_function_prefix(e.what()));
    }
    if (p.j > n) fail(at, field, "pair " + p.name() + " is outside bodies 1.." + std::to_string(n));
    return p;
  }

  void add_entry(Scene& scene, const toml::node& at, const std::string& field, MatrixEntry e) {
    if (e.second < e.first) std::swap(e.first, e.second);
    if (!declared_.emplace(e.first, e.second).second)
      fail(at, field, "the entry of M for (" + e.first.name() + ", " + e.second.name() + ") is given twice");
    scene.entries.push_back(std::move(e));
  }

  void read_dissipation(const toml::node& node, Scene& scene) {
    const toml::table* d = node.as_table();
    if (!d) fail(node, "dissipation", "must be a table");
    check_keys(*d, "dissipation.", {"K", "alpha", "coupling"});
    const int n = scene.size();
    if (const toml::node* k = d->get("K")) {
      if (!k->is_table()) fail(*k, "dissipation.K", "must be a table of \"i-j\" = value");
      for (const auto& [key, value] : *k->as_table()) {
        const std::string field = "dissipation.K." + std::string(key.str());
        const Pair p = pair_in_range(value, field, key.str(), n);
        add_entry(scene, value, field, {p, p, number(value, field)});
      }
    }
    if (const toml::node* a = d->get("alpha")) {
      if (!a->is_table()) fail(*a, "dissipation.alpha", "must be a table of \"k\" = value (the paper's alpha_k)");
      const Vocabulary& vocab = Vocabulary::paper();
      for (const auto& [key, value] : *a->as_table()) {
        const std::string field = "dissipation.alpha." + std::string(key.str());
        if (n != vocab.bodies())
          fail(value, field, "the paper's alpha_k name couplings of 4 bodies (this scene has " + std::to_string(n) +
                                 "); use dissipation.coupling");
        int k = 0;
        const std::string ks(key.str());
        if (ks.size() == 1 && ks[0] >= '1' && ks[0] <= '0' + static_cast<int>(vocab.alphas().size())) k = ks[0] - '0';
        if (k == 0) fail(value, field, "unknown alpha: expected \"1\" .. \"" + std::to_string(vocab.alphas().size()) + "\"");
        const NamedCoupling& c = vocab.alpha(k);
        add_entry(scene, value, field, {c.first, c.second, number(value, field)});
      }
    }
    if (const toml::node* c = d->get("coupling")) {
      const toml::array* list = c->as_array();
      if (!list || (!list->empty() && !list->is_array_of_tables()))
        fail(*c, "dissipation.coupling", "must be an array of tables { pairs = [\"1-2\", \"1-4\"], value = -100 }");
      for (std::size_t k = 0; k < list->size(); ++k) {
        const toml::table& t = *(*list)[k].as_table();
        const std::string field = "dissipation.coupling[" + std::to_string(k + 1) + "]";
        check_keys(t, field + ".", {"pairs", "value"});
        const toml::array* pairs = t.get_as<toml::array>("pairs");
        if (!pairs || pairs->size() != 2 || !(*pairs)[0].is_string() || !(*pairs)[1].is_string())
          fail(t, field + ".pairs", "must be two pairs like [\"1-2\", \"1-4\"]");
        const Pair p = pair_in_range((*pairs)[0], field + ".pairs", *(*pairs)[0].value<std::string>(), n);
        const Pair q = pair_in_range((*pairs)[1], field + ".pairs", *(*pairs)[1].value<std::string>(), n);
        if (p == q) fail(*pairs, field + ".pairs", "a coupling joins two different pairs (use K for the diagonal)");
        const toml::node* value = t.get("value");
        if (!value) fail(t, field + ".value", "missing");
        add_entry(scene, *value, field, {p, q, number(*value, field + ".value")});
      }
    }
  }

  std::string origin_;
  std::vector<std::string> lines_;
  std::set<std::pair<Pair, Pair>> declared_;  ///< the entries of M read so far, (first, second) with first <= second
};

/// The nesting pre-scan: the line where \p text first nests tables, arrays
/// and dotted keys deeper than max_scene_nesting, or 0.
///
/// A key `a.b.c` is 3 levels below the table it is written in, a `[a.b]`
/// header puts the keys after it 2 levels down, an array's elements and an
/// inline table's keys are one level below it.  The scan follows TOML's
/// grammar far enough to tell keys from values (strings, comments, the
/// scalars between them) in one pass over the text, and recurses at most
/// max_scene_nesting deep.  It validates nothing: where the text is not TOML
/// it goes on reading brackets as nesting, and toml++ reports the error.
class NestingScan {
 public:
  explicit NestingScan(std::string_view text) : s_(text) {}

  std::size_t too_deep_line() {
    while (i_ < s_.size()) {
      skip_blank(true);
      if (i_ >= s_.size()) break;
      if (s_[i_] == '[') {  // [table] or [[array.of.tables]]
        ++i_;
        if (i_ < s_.size() && s_[i_] == '[') ++i_;
        if (!key(0)) return line_;
        table_level_ = level_;
      } else if (key(table_level_)) {
        skip_blank(false);
        if (i_ < s_.size() && s_[i_] == '=') {
          ++i_;
          if (!value(level_)) return line_;
        }
      } else {
        return line_;
      }
      while (i_ < s_.size() && s_[i_] != '\n') ++i_;  // the rest of the line (a comment, or not TOML)
    }
    return 0;
  }

 private:
  static bool ends_bare(char c) { return std::strchr(" \t\r\n.=[]{},#\"'", c) != nullptr; }

  /// Spaces and tabs; with \p newlines also line ends and comments.
  void skip_blank(bool newlines) {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == ' ' || c == '\t' || c == '\r') {
        ++i_;
      } else if (newlines && c == '\n') {
        ++line_, ++i_;
      } else if (newlines && c == '#') {
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
      } else {
        break;
      }
    }
  }

  /// A basic, literal or multi-line string, from its opening quote.
  void skip_string() {
    const char q = s_[i_];
    const bool multi = s_.compare(i_, 3, std::string(3, q)) == 0;
    i_ += multi ? 3 : 1;
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\\' && q == '"') {
        if (i_ + 1 < s_.size() && s_[i_ + 1] == '\n') ++line_;
        i_ += 2;
        continue;
      }
      if (c == '\n') {
        ++line_;
        if (!multi) return;
      }
      if (c == q && (!multi || s_.compare(i_, 3, std::string(3, q)) == 0)) {
        i_ += multi ? 3 : 1;
        while (multi && i_ < s_.size() && s_[i_] == q) ++i_;  // up to two quotes may end the content
        return;
      }
      ++i_;
    }
  }

  /// A key `a."b".c`, \p base levels deep: sets level_ to base + its parts;
  /// false when that is deeper than allowed.
  bool key(int base) {
    level_ = base;
    for (;;) {
      skip_blank(false);
      if (i_ < s_.size() && (s_[i_] == '"' || s_[i_] == '\'')) {
        skip_string();
      } else {
        while (i_ < s_.size() && !ends_bare(s_[i_])) ++i_;
      }
      if (++level_ > max_scene_nesting) return false;
      skip_blank(false);
      if (i_ >= s_.size() || s_[i_] != '.') return true;
      ++i_;
    }
  }

  /// A value of a key \p level deep; false when it nests deeper than allowed.
  bool value(int level) {
    skip_blank(false);
    if (i_ >= s_.size()) return true;
    const char c = s_[i_];
    if (c == '"' || c == '\'') {
      skip_string();
    } else if (c == '[') {
      if (level + 1 > max_scene_nesting) return false;
      for (++i_;;) {
        skip_blank(true);
        if (i_ >= s_.size()) return true;
        if (s_[i_] == ']') break;
        if (s_[i_] == ',') {
          ++i_;
          continue;
        }
        if (!value(level + 1)) return false;
      }
      ++i_;
    } else if (c == '{') {
      for (++i_;;) {
        skip_blank(false);
        if (i_ >= s_.size() || s_[i_] == '\n') return true;
        if (s_[i_] == '}') break;
        if (s_[i_] == ',') {
          ++i_;
          continue;
        }
        if (!key(level)) return false;
        skip_blank(false);
        if (i_ < s_.size() && s_[i_] == '=') ++i_;
        if (!value(level_)) return false;
      }
      ++i_;
    } else {
      // A scalar (number, boolean, date): up to the next separator; anything
      // else is not TOML here and is stepped over.
      const std::size_t from = i_;
      while (i_ < s_.size() && !std::strchr(" \t\r\n,]}#", s_[i_])) ++i_;
      if (i_ == from && s_[i_] != '\n') ++i_;
    }
    return true;
  }

  std::string_view s_;
  std::size_t i_ = 0, line_ = 1;
  int table_level_ = 0;  ///< levels of the last [table] header
  int level_ = 0;        ///< levels of the last key read
};

constexpr std::string_view utf8_byte_order_mark = "\xEF\xBB\xBF";

}  // namespace

Scene parse_scene(const std::string& file_text, const std::string& origin) {
  // A UTF-8 byte-order mark is no part of the text: drop it before anything
  // counts lines and columns.
  const std::string text = file_text.compare(0, utf8_byte_order_mark.size(), utf8_byte_order_mark) == 0
                               ? file_text.substr(utf8_byte_order_mark.size())
                               : file_text;
  if (const std::size_t line = NestingScan(text).too_deep_line())
    throw InputError(printable(origin + ":" + std::to_string(line) + ": tables, arrays and dotted keys nest deeper than " +
                               std::to_string(max_scene_nesting) + " levels (a scene needs a few)"));
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << origin << ':' << e.source().begin.line << ':' << e.source().begin.column << ": not valid TOML: " << e.description();
    throw InputError(printable(os.str()));
  }
  return SceneReader(text, origin).read(root);
}

namespace {

/// \p v as a TOML node of the same shape (no source position: messages name
/// the field only); \p field names it in the message of a value too deep.
std::unique_ptr<toml::node> toml_node(const SceneValue& v, const std::string& origin, const std::string& field, int depth) {
  if (depth > max_scene_nesting)
    throw InputError(printable(origin + ": " + field + ": tables and arrays nest deeper than " + std::to_string(max_scene_nesting) +
                               " levels (a scene needs a few)"));
  switch (v.kind) {
    case SceneValue::Kind::String: return std::make_unique<toml::value<std::string>>(v.text);
    case SceneValue::Kind::Boolean: return std::make_unique<toml::value<bool>>(v.flag);
    case SceneValue::Kind::Array: {
      auto a = std::make_unique<toml::array>();
      for (std::size_t k = 0; k < v.items.size(); ++k)
        a->push_back(std::move(*toml_node(v.items[k], origin, field + "[" + std::to_string(k + 1) + "]", depth + 1)));
      return a;
    }
    case SceneValue::Kind::Table: break;
  }
  auto t = std::make_unique<toml::table>();
  for (const auto& [key, value] : v.members) {
    if (t->contains(key)) throw InputError(printable(origin + ": " + (field.empty() ? "" : field + ".") + key + ": given twice"));
    t->insert(key, std::move(*toml_node(value, origin, field.empty() ? key : field + "." + key, depth + 1)));
  }
  return t;
}

}  // namespace

Scene scene_from_value(const SceneValue& root, const std::string& origin) {
  if (root.kind != SceneValue::Kind::Table) throw InputError(printable(origin + ": a scene is a table of keys (title, body, ...)"));
  const std::unique_ptr<toml::node> tree = toml_node(root, origin, "", 0);
  return SceneReader("", origin).read(*tree->as_table());
}

namespace {

/// A Number as a TOML value: the user's spelling when TOML reads it as this
/// number, else the integer when TOML holds it (64 bits), else the string
/// "p" or "p/q" (a scene accepts every exact number as a string).
std::string toml_number(const Number& x) {
  const std::string& t = x.text;
  const bool plain = !t.empty() && t.find_first_not_of("+-0123456789.eE") == std::string::npos && t.find('/') == std::string::npos &&
                     std::isdigit(static_cast<unsigned char>(t.back())) && (std::isdigit(static_cast<unsigned char>(t[0])) || t[0] == '-');
  if (plain) {
    try {
      (void)toml::parse("x = " + t);
      if (Number::parse(t).fraction() == x.fraction()) return t;
    } catch (const std::exception&) {
    }
  }
  if (x.denominator == "1") {
    try {
      (void)toml::parse("x = " + x.numerator);
      return x.numerator;
    } catch (const std::exception&) {  // past 64 bits
    }
  }
  return "\"" + (x.denominator == "1" ? x.numerator : x.fraction()) + "\"";
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string write_scene(const Scene& scene, const std::string& comment) {
  std::ostringstream os;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) os << "# " << line << '\n';
  if (!scene.title.empty()) os << "title = " << quoted(scene.title) << '\n';
  if (scene.fall_speed) os << "fall_speed = " << toml_number(*scene.fall_speed) << '\n';
  if (scene.drop_height) os << "drop_height = " << toml_number(*scene.drop_height) << '\n';
  if (scene.g.fraction() != Number::parse("9.81").fraction()) os << "g = " << toml_number(scene.g) << '\n';
  for (const Body& b : scene.bodies) {
    os << "\n[[body]]\nmass = " << (b.infinite ? std::string("\"inf\"") : toml_number(b.mass)) << '\n';
    if (b.velocity) os << "velocity = " << toml_number(*b.velocity) << '\n';
    if (b.gap) os << "gap = " << toml_number(*b.gap) << '\n';
  }
  std::string diagonal, alphas, couplings;
  const Vocabulary& v = Vocabulary::paper();
  for (const MatrixEntry& e : scene.entries) {
    if (e.diagonal()) {
      diagonal += (diagonal.empty() ? "" : ", ") + quoted(e.first.name()) + " = " + toml_number(e.value);
    } else if (const auto k = scene.size() == v.bodies() ? v.alpha_index(e.first, e.second) : std::nullopt) {
      alphas += (alphas.empty() ? "" : ", ") + quoted(std::to_string(*k)) + " = " + toml_number(e.value);
    } else {
      couplings += (couplings.empty() ? "" : ",\n  ") + std::string("{ pairs = [") + quoted(e.first.name()) + ", " + quoted(e.second.name()) +
                   "], value = " + toml_number(e.value) + " }";
    }
  }
  if (!scene.entries.empty()) {
    os << "\n[dissipation]\n";
    if (!diagonal.empty()) os << "K = { " << diagonal << " }\n";
    if (!alphas.empty()) os << "alpha = { " << alphas << " }\n";
    if (!couplings.empty()) os << "coupling = [\n  " << couplings << "\n]\n";
  }
  if (scene.flight.requested) {
    os << "\n[flight]\n";
    if (scene.flight.duration) os << "duration = " << toml_number(*scene.flight.duration) << '\n';
  }
  if (scene.drop.requested) {
    os << "\n[drop]\n";
    if (scene.drop.until) os << "until = " << toml_number(*scene.drop.until) << '\n';
    if (scene.drop.max_events != Drop{}.max_events) os << "max_events = " << scene.drop.max_events << '\n';
    if (scene.drop.distant) os << "distant = true\n";
  }
  return os.str();
}

namespace {

[[noreturn]] void fail_reading(const std::string& origin, const std::string& what) { throw InputError(printable(origin + ": " + what)); }

/// Refuses what is not a regular file or a pipe, before anything opens it
/// (opening a device may act on it: a tape rewinds, a terminal is taken).
void check_kind(const struct stat& st, const std::string& origin) {
  if (S_ISDIR(st.st_mode)) fail_reading(origin, "is a directory, not a scene file");
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) fail_reading(origin, "is a device, not a scene file");
  if (S_ISSOCK(st.st_mode)) fail_reading(origin, "is a socket, not a scene file");
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) fail_reading(origin, "is not a regular file");
}

/// Everything \p fd holds, never reading more than max_scene_file_bytes + 1
/// bytes (a pipe that never ends is refused once it has said too much).
std::string read_capped(int fd, const std::string& origin) {
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const std::size_t want = std::min(sizeof buffer, max_scene_file_bytes + 1 - text.size());
    const ssize_t got = ::read(fd, buffer, want);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail_reading(origin, std::string("cannot read the scene file: ") + std::strerror(errno));
    if (got == 0) return text;
    text.append(buffer, static_cast<std::size_t>(got));
    if (text.size() > max_scene_file_bytes)
      fail_reading(origin, "more than " + std::to_string(max_scene_file_bytes) + " bytes; a scene file has at most " +
                               std::to_string(max_scene_file_bytes));
  }
}

/// Closes a file descriptor on every way out.
struct FileDescriptor {
  int fd;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

Scene load_scene(const std::string& path) {
  const bool from_stdin = path == "-";
  const std::string origin = from_stdin ? std::string(stdin_origin) : path;
  std::string text;
  if (from_stdin) {
    text = read_capped(STDIN_FILENO, origin);
  } else {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) fail_reading(origin, std::string("cannot open the scene file: ") + std::strerror(errno));
    check_kind(st, origin);
    // A FIFO is read like standard input (open waits for a writer); O_NOCTTY
    // and the second check keep a path swapped in between from being used.
    const FileDescriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY)};
    if (file.fd < 0) fail_reading(origin, std::string("cannot open the scene file: ") + std::strerror(errno));
    if (::fstat(file.fd, &st) != 0) fail_reading(origin, std::string("cannot read the scene file: ") + std::strerror(errno));
    check_kind(st, origin);
    if (S_ISREG(st.st_mode) && static_cast<unsigned long long>(st.st_size) > max_scene_file_bytes)
      fail_reading(origin, "the file has " + std::to_string(static_cast<long long>(st.st_size)) + " bytes; a scene file has at most " +
                               std::to_string(max_scene_file_bytes));
    text = read_capped(file.fd, origin);
  }
  if (text.find('\0') != std::string::npos) fail_reading(origin, "not a text file (it holds a NUL byte)");
  return parse_scene(text, origin);
}

}  // namespace superball
