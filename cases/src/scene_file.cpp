#include "superball/cases/scene_file.hpp"

#include <toml++/toml.h>

#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

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
    check_keys(root, "", {"title", "drop_height", "g", "fall_speed", "body", "dissipation", "flight"});
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
    return scene;
  }

 private:
  [[noreturn]] void fail(const toml::node& at, const std::string& field, const std::string& what) const {
    fail_at(at.source(), field, what);
  }
  [[noreturn]] void fail_at(const toml::source_region& at, const std::string& field, const std::string& what) const {
    std::ostringstream os;
    os << origin_;
    if (at.begin.line > 0) os << ':' << at.begin.line << ':' << at.begin.column;
    os << ": " << field << ": " << what;
    throw InputError(os.str());
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

  /// The exact spelling of a TOML number as it stands in the file.
  std::string spelling(const toml::node& node) const {
    const auto& src = node.source();
    if (src.begin.line == 0 || src.begin.line != src.end.line || src.begin.line > lines_.size())
      return "";
    const std::string& line = lines_[src.begin.line - 1];
    const std::size_t b = src.begin.column - 1, e = src.end.column - 1;
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
      check_keys(t, field + ".", {"mass", "velocity"});
      Body body;
      const toml::node* mass = t.get("mass");
      if (!mass) fail(t, field + ".mass", "missing: every body needs a mass (kg), or \"inf\" for a fixed obstacle");
      const bool inf_spelled = (mass->is_string() && *mass->value<std::string>() == "inf") ||
                               (mass->is_floating_point() && spelling(*mass) == "inf");
      if (inf_spelled) {
        if (k + 1 != list->size()) fail(*mass, field + ".mass", "only the bottom body may have infinite mass (a fixed obstacle)");
        body.infinite = true;
      } else {
        body.mass = number(*mass, field + ".mass");
        if (body.mass.is_negative() || body.mass.is_zero())
          fail(*mass, field + ".mass", "must be > 0 (got " + body.mass.text + ")");
      }
      if (const toml::node* v = t.get("velocity")) body.velocity = number(*v, field + ".velocity");
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

}  // namespace

Scene parse_scene(const std::string& text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << origin << ':' << e.source().begin.line << ':' << e.source().begin.column << ": not valid TOML: " << e.description();
    throw InputError(os.str());
  }
  return SceneReader(text, origin).read(root);
}

namespace {

/// A Number as a TOML value: the user's spelling when TOML reads it as a number, else "p/q".
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
  return x.denominator == "1" ? x.numerator : "\"" + x.fraction() + "\"";
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
  return os.str();
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the scene file");
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size < 0) throw InputError(path + ": cannot read the scene file (is it a directory?)");
  if (static_cast<std::size_t>(size) > max_scene_file_bytes)
    throw InputError(path + ": the file has " + std::to_string(static_cast<long long>(size)) + " bytes; a scene file has at most " +
                     std::to_string(max_scene_file_bytes));
  in.seekg(0);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in.read(text.data(), size)) throw InputError(path + ": cannot read the scene file");
  if (text.find('\0') != std::string::npos) throw InputError(path + ": not a text file (it holds a NUL byte)");
  return parse_scene(text, path);
}

}  // namespace superball
