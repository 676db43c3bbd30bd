#include "cspace/scenario/yaml_reader.hpp"

#include <sys/stat.h>
#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <regex>
#include <sstream>

#include "cspace/scenario/scenario.hpp"

namespace svmp::cspace::scenario_yaml {
namespace {

using Limits = ScenarioLimits;

// from_chars of a double at the start of [begin, end), with an optional leading '+' (which from_chars
// does not take). Returns the end of the number, or nullptr when there is none.
const char* readDouble(const char* begin, const char* end, double& v) {
  const char* p = begin;
  if (p != end && *p == '+' && p + 1 != end && *(p + 1) != '-' && *(p + 1) != '+') ++p;
  const auto [ptr, ec] = std::from_chars(p, end, v);
  if (ptr == p) return nullptr;
  if (ec == std::errc::result_out_of_range) v = std::numeric_limits<double>::infinity();  // reported as not finite
  return ptr;
}

std::string mib(std::uintmax_t bytes) {
  return num(static_cast<double>(bytes) / (1 << 20)) + " MiB";
}

std::string tooLarge(const std::string& source, std::uintmax_t size) {
  return source + ": " + std::to_string(size) + " bytes (" + mib(size) + ") is larger than the limit of " +
         std::to_string(Limits::kMaxFileBytes) + " bytes (" + mib(Limits::kMaxFileBytes) + ")";
}

std::string shorten(std::string s, size_t max) {
  if (s.size() > max) s = s.substr(0, max) + "... (" + std::to_string(s.size()) + " characters)";
  return s;
}

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = up;
    }
  }
  return row[b.size()];
}

struct TooManyNodes {};

// Streaming pass over the events: counts nodes and documents, remembers the last scalar.
// An alias counts as the nodes of what it names: ten thousand aliases of one large list would
// otherwise pass as ten thousand nodes and the scenario reader would copy the list into each.
class Survey : public YAML::EventHandler {
 public:
  long nodes = 0;
  int documents = 0;
  YAML::Mark second_document;
  bool have_scalar = false;
  YAML::Mark last_scalar;

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents == 2) second_document = mark;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t anchor) override { leaf(anchor); }
  void OnAlias(const YAML::Mark&, YAML::anchor_t anchor) override {
    const auto it = anchored_.find(anchor);
    count(it != anchored_.end() ? it->second : 1);
  }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string&) override {
    leaf(anchor);
    have_scalar = true;
    last_scalar = mark;
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
    open(anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  std::map<YAML::anchor_t, long> anchored_;                // anchor -> nodes it names, aliases expanded
  std::vector<std::pair<YAML::anchor_t, long>> open_;      // open collections: anchor, nodes before them

  void count(long n) {
    nodes += n;
    if (nodes > Limits::kMaxYamlNodes) throw TooManyNodes{};
  }
  void leaf(YAML::anchor_t anchor) {
    count(1);
    if (anchor != YAML::NullAnchor) anchored_[anchor] = 1;
  }
  void open(YAML::anchor_t anchor) {
    open_.emplace_back(anchor, nodes);
    count(1);
  }
  void close() {
    const auto [anchor, before] = open_.back();
    open_.pop_back();
    if (anchor != YAML::NullAnchor) anchored_[anchor] = nodes - before;
  }
};

// The byte where `text` stops being UTF-8 (overlong forms, surrogates and code points past U+10FFFF
// included), or npos. Names are copied into the JSON outputs, which must stay valid JSON.
size_t invalidUtf8(const std::string& text) {
  const auto* t = reinterpret_cast<const unsigned char*>(text.data());
  for (size_t i = 0; i < text.size();) {
    const unsigned c = t[i];
    size_t n = 0;
    unsigned lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
    if (c < 0x80) n = 0;
    else if (c >= 0xC2 && c <= 0xDF) n = 1;
    else if (c >= 0xE0 && c <= 0xEF) n = 2, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    else if (c >= 0xF0 && c <= 0xF4) n = 3, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    else return i;
    if (i + n >= text.size() && n > 0) return i;  // the sequence runs past the end
    for (size_t k = 1; k <= n; ++k) {
      const unsigned b = t[i + k];
      if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return i;
    }
    i += n + 1;
  }
  return std::string::npos;
}

std::string lineColumn(const std::string& text, size_t pos) {
  pos = std::min(pos, text.size());
  const size_t line = static_cast<size_t>(std::count(text.begin(), text.begin() + pos, '\n')) + 1;
  const size_t start = text.rfind('\n', pos == 0 ? 0 : pos - 1);
  const size_t column = start == std::string::npos || pos == 0 ? pos + 1 : pos - start;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// yaml-cpp ends a quoted scalar that is never closed at the end of the text, swallowing the rest of
// the file without an error. Such a scalar is the last one of the text: find its opening quote (after
// any tag or anchor) and look for the closing one.
void checkLastQuoteClosed(const std::string& text, const std::string& source, size_t pos) {
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (pos < text.size() && (text[pos] == '!' || text[pos] == '&')) {
    while (pos < text.size() && !blank(text[pos])) ++pos;
    while (pos < text.size() && blank(text[pos])) ++pos;
  }
  if (pos >= text.size() || (text[pos] != '"' && text[pos] != '\'')) return;
  const char quote = text[pos];
  for (size_t i = pos + 1; i < text.size(); ++i) {
    if (quote == '"' && text[i] == '\\') {
      ++i;
    } else if (text[i] == quote) {
      if (quote == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
        ++i;
      } else {
        return;
      }
    }
  }
  throw ScenarioError(source + ": YAML syntax error at " + lineColumn(text, pos) + ": the " +
                      (quote == '"' ? "double" : "single") + "-quoted string starting here is never closed");
}

[[noreturn]] void syntaxError(const std::string& source, const YAML::Exception& e) {
  throw ScenarioError(source + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) + ", column " +
                      std::to_string(e.mark.column + 1) + ": " + e.msg);
}

}  // namespace

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

bool parseNumber(const std::string& s, double& v) {
  if (s.empty()) return false;
  const char* begin = s.data();
  const char* end = s.data() + s.size();
  const char* p = readDouble(begin, end, v);
  if (p == end) return true;
  double coefficient = v;
  if (p == nullptr) {  // no number before "pi", at most a sign
    coefficient = s[0] == '-' ? -1 : 1;
    p = begin + (s[0] == '-' || s[0] == '+' ? 1 : 0);
  }
  if (end - p < 2 || p[0] != 'p' || p[1] != 'i') return false;
  v = coefficient * std::numbers::pi;
  p += 2;
  if (p == end) return true;
  if (*p != '/') return false;
  double d = 0;
  const char* q = readDouble(p + 1, end, d);
  // pi/inf or pi/1e400 must not read as 0 (readDouble gives inf out of range); pi/0 is no number either.
  if (q != end || !std::isfinite(d) || d == 0) return false;
  v /= d;
  return true;
}

std::string readScenarioFile(const std::string& path) {
  if (path.empty()) throw ScenarioError("scenario path is empty");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw ScenarioError(path + ": cannot open the file: " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw ScenarioError(path + ": is a directory, not a scenario file");
  if (S_ISREG(st.st_mode) && static_cast<std::uintmax_t>(st.st_size) > Limits::kMaxFileBytes)
    throw ScenarioError(tooLarge(path, static_cast<std::uintmax_t>(st.st_size)));
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw ScenarioError(path + ": cannot open the file: " + std::strerror(errno));
  // Read at most one byte past the limit: a pipe or device (or a file growing meanwhile) is bounded too.
  std::string text;
  char buffer[1 << 16];
  while (true) {
    const size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
    text.append(buffer, n);
    if (text.size() > Limits::kMaxFileBytes) throw ScenarioError(tooLarge(path, text.size()) + " (stopped reading)");
    if (n < sizeof buffer) break;
  }
  if (std::ferror(file.get())) throw ScenarioError(path + ": cannot read the file: " + std::strerror(errno));
  return text;
}

YAML::Node loadSingleDocument(const std::string& text, const std::string& source) {
  if (text.size() > Limits::kMaxFileBytes) throw ScenarioError(tooLarge(source, text.size()));
  if (const size_t nul = text.find('\0'); nul != std::string::npos)
    throw ScenarioError(source + ": a NUL byte at byte " + std::to_string(nul) +
                        " (" + lineColumn(text, nul) + "): not UTF-8 YAML text");
  if (const size_t bad = invalidUtf8(text); bad != std::string::npos)
    throw ScenarioError(source + ": a byte that is not UTF-8 at byte " + std::to_string(bad) + " (" +
                        lineColumn(text, bad) + "): scenario files are UTF-8 text");
  Survey survey;
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    while (parser.HandleNextDocument(survey)) {
    }
  } catch (const TooManyNodes&) {
    throw ScenarioError(source + ": more than " + std::to_string(Limits::kMaxYamlNodes) +
                        " YAML nodes (values, lists and mappings, each alias counting as what it names): "
                        "the scenario limit");
  } catch (const YAML::Exception& e) {
    syntaxError(source, e);
  }
  if (survey.documents > 1)
    throw ScenarioError(source + ": a second YAML document starts at line " +
                        std::to_string(survey.second_document.line + 1) +
                        " (after a '---' or '...' line): a scenario file holds one document");
  if (survey.have_scalar && survey.last_scalar.pos >= 0) {
    const size_t bom = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;  // yaml-cpp's positions start after it
    checkLastQuoteClosed(text, source, static_cast<size_t>(survey.last_scalar.pos) + bom);
  }
  try {
    return survey.documents == 0 ? YAML::Node(YAML::NodeType::Null) : YAML::Load(text);
  } catch (const YAML::Exception& e) {
    syntaxError(source, e);
  }
}

void Reader::fail(const std::string& field, const std::string& what) const {
  throw ScenarioError(source_ + ": field '" + field + "': " + what);
}

std::string Reader::text(const YAML::Node& n) {
  if (!n.IsDefined()) return "(missing)";
  if (n.IsNull()) return "null (an empty value)";
  if (n.IsScalar()) return "'" + shorten(n.Scalar(), 100) + "'";
  YAML::Emitter e;
  e << YAML::Flow << n;
  return shorten(e.c_str(), 160);
}

std::string Reader::join(const KeyList& keys) {
  std::string s;
  for (const auto& k : keys) s += (s.empty() ? "" : ", ") + k;
  return s;
}

void Reader::requireMap(const YAML::Node& n, const std::string& field) const {
  if (!n.IsMap()) fail(field, "expected a mapping {key: value}, got " + text(n));
}

YAML::Node Reader::require(const YAML::Node& parent, const std::string& key, const std::string& field) const {
  const std::string suffix = "." + key;
  const bool nested = field.size() > suffix.size() &&
                      field.compare(field.size() - suffix.size(), suffix.size(), suffix) == 0;
  requireMap(parent, nested ? field.substr(0, field.size() - suffix.size()) : field);
  YAML::Node n = parent[key];
  if (!n.IsDefined()) fail(field, "is required");
  if (n.IsNull()) fail(field, "is required, got an empty value");
  return n;
}

void Reader::checkKeys(const YAML::Node& n, const std::string& field, const KeyList& known,
                       const std::string& what, const KeyList& elsewhere) const {
  requireMap(n, field.empty() ? "(top level)" : field);
  std::map<std::string, std::pair<YAML::Node, YAML::Node>> seen;
  for (const auto& kv : n) {
    if (!kv.first.IsScalar())
      fail(field.empty() ? "(top level)" : field, "keys must be plain names, got the key " + text(kv.first));
    const std::string key = kv.first.Scalar();
    const std::string child = field.empty() ? key : field + "." + key;
    const auto [it, fresh] = seen.emplace(key, std::make_pair(kv.first, kv.second));
    if (!fresh)
      fail(child, "key given twice: " + text(it->second.second) + " (line " +
                      std::to_string(it->second.first.Mark().line + 1) + ") and " + text(kv.second) +
                      " (line " + std::to_string(kv.first.Mark().line + 1) + ")");
    if (known.empty() || std::find(known.begin(), known.end(), key) != known.end()) continue;
    if (std::find(elsewhere.begin(), elsewhere.end(), key) != elsewhere.end())
      fail(child, what + " does not take '" + key + "' (it takes: " + join(known) + ")");
    std::string suggestion;
    size_t best = 3;
    for (const auto& k : known) {
      const size_t d = editDistance(key, k);
      if (d < best && d < key.size()) best = d, suggestion = "; did you mean '" + k + "'?";
    }
    fail(child, "unknown field '" + shorten(key, 60) + "' (known: " + join(known) + ")" + suggestion);
  }
}

void Reader::requireList(const YAML::Node& n, const std::string& field, size_t max_size,
                         const std::string& what) const {
  if (!n.IsSequence()) fail(field, "expected a list of " + what + ", got " + text(n));
  if (n.size() > max_size)
    fail(field, "has " + std::to_string(n.size()) + " entries, at most " + std::to_string(max_size) + " allowed");
}

double Reader::number(const YAML::Node& n, const std::string& field) const {
  if (!n.IsScalar()) fail(field, "expected a number, got " + text(n));
  double v = 0;
  // YAML's own spellings of infinity and NaN (.inf, -.Inf, .nan, ...) get the message inf and nan get.
  static const std::regex yaml_special(R"([-+]?\.(inf|Inf|INF)|\.(nan|NaN|NAN))");
  const bool special = std::regex_match(n.Scalar(), yaml_special);
  if (!special && !parseNumber(n.Scalar(), v)) fail(field, "expected a number, got " + text(n));
  if (special || !std::isfinite(v))
    fail(field, "expected a finite number (in the range of a double), got " + text(n));
  return v;
}

double Reader::inRange(const YAML::Node& n, const std::string& field, double lo, double hi,
                       const std::string& unit) const {
  const double v = number(n, field);
  if (!(v >= lo && v <= hi))
    fail(field, "must lie in [" + num(lo) + ", " + num(hi) + "]" + (unit.empty() ? "" : " " + unit) +
                    ", got " + text(n));
  return v;
}

double Reader::positiveAtMost(const YAML::Node& n, const std::string& field, double hi) const {
  const double v = number(n, field);
  if (!(v > 0 && v <= hi)) fail(field, "must lie in (0, " + num(hi) + "], got " + text(n));
  return v;
}

long Reader::integer(const YAML::Node& n, const std::string& field, long lo, long hi) const {
  if (!n.IsScalar()) fail(field, "expected an integer, got " + text(n));
  const std::string& s = n.Scalar();
  const char* begin = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
  long v = 0;
  const auto [ptr, ec] = std::from_chars(begin, s.data() + s.size(), v);
  if (s.empty() || ptr != s.data() + s.size() || ec != std::errc() || v < lo || v > hi)
    fail(field, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + text(n));
  return v;
}

Eigen::VectorXd Reader::vector(const YAML::Node& n, const std::string& field, int size, double lo, double hi,
                               const std::string& unit, size_t max_size) const {
  if (!n.IsSequence()) fail(field, "expected a list of numbers, got " + text(n));
  if (size >= 0 && n.size() != static_cast<size_t>(size))
    fail(field, "expected " + std::to_string(size) + " numbers, got " + std::to_string(n.size()) + ": " + text(n));
  if (size < 0 && (n.size() == 0 || n.size() > max_size))
    fail(field, "expected 1 to " + std::to_string(max_size) + " numbers, got " + std::to_string(n.size()) +
                    ": " + text(n));
  Eigen::VectorXd v(n.size());
  for (size_t i = 0; i < n.size(); ++i) v[i] = inRange(n[i], field + "[" + std::to_string(i) + "]", lo, hi, unit);
  return v;
}

bool Reader::boolean(const YAML::Node& n, const std::string& field) const {
  if (n.IsScalar() && (n.Scalar() == "true" || n.Scalar() == "false")) return n.Scalar() == "true";
  fail(field, "expected true or false, got " + text(n));
}

std::string Reader::string(const YAML::Node& n, const std::string& field) const {
  if (!n.IsScalar()) fail(field, "expected text, got " + text(n));
  return n.Scalar();
}

}  // namespace svmp::cspace::scenario_yaml
