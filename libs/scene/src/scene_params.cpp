// The visitors over the scene's parameter description (scene_params.h): parsing with
// validation, JSON output, the schema, hashes and the Markdown tables.
#include "scene_params.h"

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "shanshui/core/error.h"

namespace shanshui::scene {

using nlohmann::json;

namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string join(const std::vector<std::string>& parts, const char* sep) {
  std::string s;
  for (const std::string& p : parts) s += (s.empty() ? "" : sep) + p;
  return s;
}

template <typename E, std::size_t N>
std::vector<std::string> names(const std::array<Named<E>, N>& options) {
  std::vector<std::string> out;
  for (const Named<E>& o : options) out.emplace_back(o.name);
  return out;
}

template <typename E, std::size_t N>
const char* nameOf(E value, const std::array<Named<E>, N>& options) {
  for (const Named<E>& o : options) {
    if (o.value == value) return o.name;
  }
  SHANSHUI_CHECK(!"an enum value without a name in its description");
  return "";
}

// ---------------------------------------------------------------------------------------
// Parser: reads one JSON object into the fields, checking kinds and ranges, and reports
// keys it did not read.
class Parser {
 public:
  Parser(const json* j, std::string path, const std::string& origin) : j_(j), path_(std::move(path)), origin_(origin) {
    if (j_ && !j_->is_object()) throw fail(path_, "expected an object, found " + describe(*j_));
  }

  void number(const Key& k, double& f, Range<double> r) {
    if (const json* v = find(k.name)) f = numberValue(*v, keyPath(k.name), r);
  }

  template <typename I>
  void integer(const Key& k, I& f, Range<long long> r) {
    const json* v = find(k.name);
    if (!v) return;
    const std::string at = keyPath(k.name);
    if (!v->is_number_integer()) throw fail(at, "expected an integer, found " + describe(*v));
    const bool huge = v->is_number_unsigned() && v->get<unsigned long long>() > static_cast<unsigned long long>(r.hi);
    if (huge || !r.contains(v->get<long long>())) {
      throw fail(at, v->dump() + " is out of range; expected " + r.text());
    }
    f = static_cast<I>(v->get<long long>());
  }

  void boolean(const Key& k, bool& f) {
    const json* v = find(k.name);
    if (!v) return;
    if (!v->is_boolean()) throw fail(keyPath(k.name), "expected true or false, found " + describe(*v));
    f = v->get<bool>();
  }

  void text(const Key& k, std::string& f, Text) {
    const json* v = find(k.name);
    if (!v) return;
    if (!v->is_string()) throw fail(keyPath(k.name), "expected a string, found " + describe(*v));
    f = v->get<std::string>();
  }

  template <typename E, std::size_t N>
  void choice(const Key& k, E& f, const std::array<Named<E>, N>& options) {
    const json* v = find(k.name);
    if (!v) return;
    if (v->is_string()) {
      for (const Named<E>& o : options) {
        if (v->get<std::string>() == o.name) {
          f = o.value;
          return;
        }
      }
    }
    throw fail(keyPath(k.name), describe(*v) + " is not one of: " + join(names(options), ", "));
  }

  void vec3(const Key& k, glm::dvec3& f, Range<double> r, Vec) {
    std::array<double, 3> a{f.x, f.y, f.z};
    numbers(k, a, r);
    f = {a[0], a[1], a[2]};
  }

  void optionalVec3(const Key& k, std::optional<glm::dvec3>& f, Range<double> r) {
    const json* v = find(k.name);
    if (!v || v->is_null()) return;
    glm::dvec3 x{0.0};
    vec3(k, x, r, Vec::Vector);
    f = x;
  }

  template <std::size_t N>
  void numbers(const Key& k, std::array<double, N>& f, Range<double> r) {
    const json* v = find(k.name);
    if (!v) return;
    const std::string at = keyPath(k.name);
    if (!v->is_array() || v->size() != N) {
      throw fail(at, "expected a list of " + std::to_string(N) + " numbers, found " + describe(*v));
    }
    for (std::size_t i = 0; i < N; ++i) f[i] = numberValue((*v)[i], at + "." + std::to_string(i), r);
  }

  template <typename T>
  void group(const char* name, T& g, Table) {
    Parser child(find(name), keyPath(name), origin_);
    shanshui::scene::describe(child, g);
    child.finish();
  }

  template <typename T, typename Make>
  void list(const Key& k, std::vector<T>& items, Range<long long> count, Make make, Table) {
    const json* v = find(k.name);
    const std::string at = keyPath(k.name);
    if (v && !v->is_array()) throw fail(at, "expected a list, found " + describe(*v));
    if (v) {
      items.clear();
      for (std::size_t i = 0; i < v->size(); ++i) {
        T item = make();
        Parser child(&(*v)[i], at + "." + std::to_string(i), origin_);
        shanshui::scene::describe(child, item);
        child.finish();
        items.push_back(std::move(item));
      }
    }
    const long long n = static_cast<long long>(items.size());
    if (n < count.lo) {
      throw fail(at, "needs at least " + std::to_string(count.lo) + (count.lo == 1 ? " entry" : " entries") +
                         ", found " + std::to_string(n));
    }
    if (n > count.hi)
      throw fail(at, std::to_string(n) + " entries; at most " + std::to_string(count.hi) + " are allowed");
  }

  template <typename F>
  void check(const char* key, F f) {
    if (const std::string e = f(); !e.empty()) throw fail(*key ? keyPath(key) : path_, e);
  }

  void finish() const {
    if (!j_) return;
    for (const auto& [key, value] : j_->items()) {
      if (!used_.count(key)) {
        throw fail(keyPath(key), "unknown key (known here: " +
                                     join(std::vector<std::string>(used_.begin(), used_.end()), ", ") + ")");
      }
    }
  }

 private:
  std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  Error fail(const std::string& key_path, const std::string& what) const {
    return makeError(origin_, ": ", key_path.empty() ? "(top level)" : key_path, ": ", what);
  }

  static std::string describe(const json& v) {
    std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
    if (s.size() > 40) s = s.substr(0, 37) + "...";
    return std::string(v.type_name()) + " " + s;
  }

  const json* find(const std::string& key) {
    used_.insert(key);
    if (!j_) return nullptr;
    const auto it = j_->find(key);
    return it == j_->end() ? nullptr : &*it;
  }

  double numberValue(const json& v, const std::string& at, Range<double> r) const {
    if (!v.is_number()) throw fail(at, "expected a number, found " + describe(v));
    const double x = v.get<double>();
    if (!std::isfinite(x) || !r.contains(x)) throw fail(at, fmt(x) + " is out of range; expected " + r.text());
    return x;
  }

  const json* j_;
  std::string path_;
  std::string origin_;
  std::set<std::string> used_;
};

// ---------------------------------------------------------------------------------------
// Writer: every field as JSON.
class Writer {
 public:
  json out = json::object();

  void number(const Key& k, double f, Range<double>) { out[k.name] = f; }
  template <typename I>
  void integer(const Key& k, I f, Range<long long>) {
    out[k.name] = f;
  }
  void boolean(const Key& k, bool f) { out[k.name] = f; }
  void text(const Key& k, const std::string& f, Text) { out[k.name] = f; }
  template <typename E, std::size_t N>
  void choice(const Key& k, E f, const std::array<Named<E>, N>& options) {
    out[k.name] = nameOf(f, options);
  }
  void vec3(const Key& k, const glm::dvec3& f, Range<double>, Vec) { out[k.name] = json::array({f.x, f.y, f.z}); }
  void optionalVec3(const Key& k, const std::optional<glm::dvec3>& f, Range<double> r) {
    if (f)
      vec3(k, *f, r, Vec::Vector);
    else
      out[k.name] = nullptr;
  }
  template <std::size_t N>
  void numbers(const Key& k, const std::array<double, N>& f, Range<double>) {
    out[k.name] = f;
  }
  template <typename T>
  void group(const char* name, T& g, Table) {
    Writer child;
    shanshui::scene::describe(child, g);
    out[name] = std::move(child.out);
  }
  template <typename T, typename Make>
  void list(const Key& k, std::vector<T>& items, Range<long long>, Make, Table) {
    json a = json::array();
    for (T& item : items) {
      Writer child;
      shanshui::scene::describe(child, item);
      a.push_back(std::move(child.out));
    }
    out[k.name] = std::move(a);
  }
  template <typename F>
  void check(const char*, F) {}
};

// ---------------------------------------------------------------------------------------
// Hasher: FNV-1a over the values (and list lengths), optionally of one effect only.
class Hasher {
 public:
  explicit Hasher(std::optional<Effect> only) : only_(only) {}
  std::uint64_t hash = 1469598103934665603ull;

  void number(const Key& k, double f, Range<double>) { add(k, f); }
  template <typename I>
  void integer(const Key& k, I f, Range<long long>) {
    add(k, static_cast<long long>(f));
  }
  void boolean(const Key& k, bool f) { add(k, f); }
  void text(const Key& k, const std::string& f, Text) {
    if (!wanted(k)) return;
    bytes(f.data(), f.size());
    bytes("\0", 1);
  }
  template <typename E, std::size_t N>
  void choice(const Key& k, E f, const std::array<Named<E>, N>&) {
    add(k, static_cast<int>(f));
  }
  void vec3(const Key& k, const glm::dvec3& f, Range<double>, Vec) { add(k, f); }
  void optionalVec3(const Key& k, const std::optional<glm::dvec3>& f, Range<double>) {
    add(k, f.has_value());
    if (f) add(k, *f);
  }
  template <std::size_t N>
  void numbers(const Key& k, const std::array<double, N>& f, Range<double>) {
    add(k, f);
  }
  template <typename T>
  void group(const char*, T& g, Table) {
    shanshui::scene::describe(*this, g);
  }
  template <typename T, typename Make>
  void list(const Key&, std::vector<T>& items, Range<long long>, Make, Table) {
    const std::size_t n = items.size();
    bytes(&n, sizeof n);
    for (T& item : items) shanshui::scene::describe(*this, item);
  }
  template <typename F>
  void check(const char*, F) {}

 private:
  bool wanted(const Key& k) const { return !only_ || k.effect == *only_; }
  template <typename T>
  void add(const Key& k, const T& v) {
    if (wanted(k)) bytes(&v, sizeof v);
  }
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) hash = (hash ^ b[i]) * 1099511628211ull;
  }
  std::optional<Effect> only_;
};

// ---------------------------------------------------------------------------------------
// Schema: one entry per key, its path with * for list indices, from a default scene.
class SchemaBuilder {
 public:
  std::vector<SchemaEntry> entries;

  void number(const Key& k, double f, Range<double> r) { add(k, "number", r.lo, r.hi, r.lo_open, fmt(f), r.text()); }
  template <typename I>
  void integer(const Key& k, I f, Range<long long> r) {
    add(k, "integer", static_cast<double>(r.lo), static_cast<double>(r.hi), r.lo_open, std::to_string(f), r.text());
  }
  void boolean(const Key& k, bool f) { add(k, "bool", 0, 1, false, f ? "true" : "false", "bool"); }
  void text(const Key& k, const std::string& f, Text t) {
    add(k, t == Text::File ? "file" : "string", 0, 0, false, "\"" + f + "\"", t == Text::File ? "file" : "string");
  }
  template <typename E, std::size_t N>
  void choice(const Key& k, E f, const std::array<Named<E>, N>& options) {
    std::vector<std::string> quoted;
    for (const std::string& n : names(options)) quoted.push_back("`" + n + "`");
    add(k, "choice", 0, 0, false, std::string("`") + nameOf(f, options) + "`", join(quoted, ", "));
    entries.back().choices = names(options);
  }
  void vec3(const Key& k, const glm::dvec3& f, Range<double> r, Vec kind) {
    add(k, kind == Vec::Color ? "color" : "vec3", r.lo, r.hi, r.lo_open, list3(f),
        kind == Vec::Color ? "RGB in " + r.text() : "each in " + r.text());
  }
  void optionalVec3(const Key& k, const std::optional<glm::dvec3>& f, Range<double> r) {
    add(k, "vec3", r.lo, r.hi, r.lo_open, f ? list3(*f) : "null", "null or each in " + r.text());
    entries.back().optional = true;
  }
  template <std::size_t N>
  void numbers(const Key& k, const std::array<double, N>& f, Range<double> r) {
    std::vector<std::string> parts;
    for (double x : f) parts.push_back(fmt(x));
    add(k, "list", r.lo, r.hi, r.lo_open, "[" + join(parts, ", ") + "]", std::to_string(N) + " values in " + r.text());
    entries.back().size = N;
  }
  template <typename T>
  void group(const char* name, T& g, Table t) {
    Scope scope(*this, name, t == Table::Own);
    shanshui::scene::describe(*this, g);
  }
  template <typename T, typename Make>
  void list(const Key& k, std::vector<T>&, Range<long long> count, Make make, Table t) {
    add(k, "entries", static_cast<double>(count.lo), static_cast<double>(count.hi), false, "[]",
        std::to_string(count.lo) + " to " + std::to_string(count.hi) + " entries");
    T item = make();
    Scope scope(*this, std::string(k.name) + ".*", t == Table::Own);
    shanshui::scene::describe(*this, item);
  }
  template <typename F>
  void check(const char*, F) {}

 private:
  struct Scope {
    Scope(SchemaBuilder& b, const std::string& name, bool own) : b_(b), prefix_(b.prefix_), table_(b.table_) {
      b.prefix_ += name + ".";
      if (own) b.table_ = b.prefix_.substr(0, b.prefix_.size() - 1);
    }
    ~Scope() {
      b_.prefix_ = prefix_;
      b_.table_ = table_;
    }
    SchemaBuilder& b_;
    std::string prefix_, table_;
  };

  static std::string list3(const glm::dvec3& v) { return "[" + fmt(v.x) + ", " + fmt(v.y) + ", " + fmt(v.z) + "]"; }

  void add(const Key& k, const char* kind, double lo, double hi, bool lo_open, std::string def, std::string range) {
    SchemaEntry e;
    e.path = prefix_ + k.name;
    e.kind = kind;
    e.min = lo;
    e.max = hi;
    e.lo_open = lo_open;
    e.doc = k.doc;
    e.unit = k.unit;
    e.effect = k.effect;
    e.default_text = std::move(def);
    e.range_text = std::move(range);
    e.table = table_;
    entries.push_back(std::move(e));
  }

  std::string prefix_;
  std::string table_;
};

}  // namespace

Scene parseScene(const json& j, const std::string& origin, const std::filesystem::path& base_dir) {
  Scene s;
  Parser p(&j, "", origin);
  describe(p, s);
  p.finish();
  s.base_dir = base_dir;
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    if (s.objects[i].name.empty()) s.objects[i].name = "objects." + std::to_string(i);
  }
  return s;
}

json toJson(const Scene& s) {
  Writer w;
  describe(w, const_cast<Scene&>(s));  // the writer only reads
  return std::move(w.out);
}

std::uint64_t parameterHash(const Scene& s, std::optional<Effect> only) {
  Hasher h(only);
  describe(h, const_cast<Scene&>(s));  // the hasher only reads
  return h.hash;
}

const std::vector<SchemaEntry>& sceneSchema() {
  static const std::vector<SchemaEntry> schema = [] {
    SchemaBuilder b;
    Scene defaults;
    describe(b, defaults);
    return std::move(b.entries);
  }();
  return schema;
}

namespace {

// "objects.*.lines" -> "objects.N.lines", as docs/scene.md writes list indices.
std::string docPath(std::string p) {
  for (std::size_t at; (at = p.find('*')) != std::string::npos;) p.replace(at, 1, "N");
  return p;
}

std::string tableBody(const std::string& table) {
  std::ostringstream out;
  out << "| key | default | range | unit | on change | meaning |\n|---|---|---|---|---|---|\n";
  const std::string prefix = table.empty() ? "" : table + ".";
  for (const SchemaEntry& e : sceneSchema()) {
    if (e.table != table) continue;
    out << "| `" << docPath(e.path.substr(prefix.size())) << "` | " << e.default_text << " | " << e.range_text << " | "
        << e.unit << " | " << (e.effect == Effect::Rebuild ? "rebuild" : "live") << " | " << e.doc << " |\n";
  }
  return out.str();
}

std::vector<std::string> tables() {
  std::vector<std::string> out;
  for (const SchemaEntry& e : sceneSchema()) {
    if (std::find(out.begin(), out.end(), e.table) == out.end()) out.push_back(e.table);
  }
  return out;
}

std::string beginMarker(const std::string& table) {
  return "<!-- keys: " + (table.empty() ? std::string("(top level)") : docPath(table)) + " -->\n";
}
constexpr const char* kEndMarker = "<!-- /keys -->";

}  // namespace

std::string describeMarkdown() {
  std::ostringstream out;
  out << "# Scene keys\n\nRanges: `[a, b]` includes both ends, `(a, b]` excludes a. *live*: a change takes effect "
         "on the next frame; *rebuild*: it needs new shader variants, GPU resources or files.\n";
  for (const std::string& t : tables()) {
    out << "\n## `" << (t.empty() ? std::string("(top level)") : docPath(t)) << "`\n\n" << tableBody(t);
  }
  return out.str();
}

std::string spliceDescription(const std::string& doc, const std::string& origin) {
  std::string out = doc;
  for (const std::string& t : tables()) {
    const std::string begin = beginMarker(t);
    const std::size_t at = out.find(begin);
    if (at == std::string::npos)
      throw makeError(origin, ": has no table for ", t.empty() ? "(top level)" : docPath(t), " (a line '",
                      begin.substr(0, begin.size() - 1), "')");
    const std::size_t body = at + begin.size();
    const std::size_t end = out.find(kEndMarker, body);
    if (end == std::string::npos)
      throw makeError(origin, ": the table after '", begin.substr(0, begin.size() - 1), "' has no '", kEndMarker, "'");
    out.replace(body, end - body, tableBody(t));
  }
  return out;
}

}  // namespace shanshui::scene
