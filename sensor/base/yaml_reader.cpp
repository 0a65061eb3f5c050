#include "sensor/base/yaml_reader.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string_view>

#include "sensor/base/format.h"

namespace camsim {

YamlValue::YamlValue(const YAML::Node& node, std::string key, std::string file)
    : YamlValue(node, std::move(key), std::move(file), node.Mark()) {}

YamlValue::YamlValue(const YAML::Node& node, std::string key, std::string file,
                     const YAML::Mark& mark)
    : node_(std::make_shared<const YAML::Node>(node)),
      key_(std::move(key)),
      file_(std::move(file)),
      line_(mark.line),
      column_(mark.column) {}

bool YamlValue::isNull() const {
  return !*node_ || node_->IsNull();
}
bool YamlValue::isMap() const {
  return node_->IsMap();
}
bool YamlValue::isSequence() const {
  return node_->IsSequence();
}
bool YamlValue::isScalar() const {
  return node_->IsScalar();
}

SourceLocation YamlValue::where() const {
  if (line_ < 0) return {file_, 0, 0};
  return {file_, line_ + 1, column_ + 1};
}

void YamlValue::fail(const std::string& message) const {
  throw InputError(where(), key_, message);
}

void YamlValue::failInNamedFile(const InputError& inner) const {
  if (inner.where().line <= 0)
    fail(inner.where().file.empty() ? inner.message()
                                    : inner.where().file + ": " + inner.message());
  throw namedBy(inner, where(), key_);
}

std::string YamlValue::string() const {
  if (!node_->IsScalar()) fail("expected a string");
  return node_->Scalar();
}

double YamlValue::number() const {
  if (!node_->IsScalar()) fail("expected a number");
  const std::string& s = node_->Scalar();
  double value = 0.0;
  const char* begin = s.data();
  if (!s.empty() && s.front() == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, s.data() + s.size(), value);
  if (ec != std::errc() || ptr != s.data() + s.size()) {
    std::string lower = s.substr(!s.empty() && (s.front() == '+' || s.front() == '-') ? 1 : 0);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower == ".nan" || lower == ".inf") fail("'" + s + "' is not a finite number");
    fail("'" + s + "' is not a number");
  }
  if (!std::isfinite(value)) fail("'" + s + "' is not a finite number");
  return value;
}

double YamlValue::number(double lo, double hi, bool loOpen) const {
  const double v = number();
  if (v < lo || v > hi || (loOpen && v == lo)) {
    fail("value " + node_->Scalar() + " is out of range " + formatRange(lo, hi, loOpen));
  }
  return v;
}

std::int64_t YamlValue::integer(std::int64_t lo, std::int64_t hi) const {
  if (!node_->IsScalar()) fail("expected an integer");
  const std::string& s = node_->Scalar();
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec == std::errc::result_out_of_range) fail("integer " + s + " is out of range");
  if (ec != std::errc() || ptr != s.data() + s.size()) fail("'" + s + "' is not an integer");
  if (value < lo || value > hi)
    fail("value " + s + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) +
         "]");
  return value;
}

bool YamlValue::boolean() const {
  if (node_->IsScalar()) {
    const std::string& s = node_->Scalar();
    if (s == "true" || s == "True" || s == "yes") return true;
    if (s == "false" || s == "False" || s == "no") return false;
  }
  fail("expected true or false");
}

std::vector<YamlValue> YamlValue::items() const {
  if (!node_->IsSequence()) fail("expected a list");
  std::vector<YamlValue> out;
  out.reserve(node_->size());
  for (size_t i = 0; i < node_->size(); ++i)
    out.push_back(YamlValue((*node_)[i], key_ + "[" + std::to_string(i) + "]", file_));
  return out;
}

std::vector<double> YamlValue::numbers() const {
  std::vector<double> out;
  for (const YamlValue& item : items()) out.push_back(item.number());
  return out;
}

glm::dvec3 YamlValue::vec3() const {
  if (!node_->IsSequence() || node_->size() != 3) fail("expected a list of 3 numbers [x, y, z]");
  const std::vector<double> v = numbers();
  return {v[0], v[1], v[2]};
}

YamlMap::YamlMap(const YamlValue& value) : self_(value) {
  if (!value.isMap()) value.fail("expected a mapping of keys to values");
  // yaml-cpp keeps duplicate keys; lookups would silently use the first one.
  std::map<std::string, int> seen;  // key → line (1-based)
  for (auto it = self_.node().begin(); it != self_.node().end(); ++it) {
    if (!it->first.IsScalar())
      YamlValue(it->first, self_.key(), self_.file()).fail("a key must be a plain name");
    const std::string name = it->first.Scalar();
    const auto [first, inserted] = seen.emplace(name, it->first.Mark().line + 1);
    if (!inserted) {
      YamlValue(it->first, childKey(name), self_.file())
          .fail("duplicate key (first given at line " + std::to_string(first->second) + ")");
    }
  }
}

std::string YamlMap::childKey(const std::string& name) const {
  return self_.key().empty() ? name : self_.key() + "." + name;
}

bool YamlMap::has(const std::string& name) const {
  return static_cast<bool>(self_.node()[name]);
}

std::optional<YamlValue> YamlMap::find(const std::string& name) {
  for (auto it = self_.node().begin(); it != self_.node().end(); ++it) {
    if (it->first.Scalar() != name) continue;
    used_.insert(name);
    // A key given without a value ("radius:" at the end of a line) is a null node that
    // yaml-cpp places at the next token, on a later line or past the end: use the key.
    const YAML::Mark valueMark = it->second.Mark();
    const YAML::Mark keyMark = it->first.Mark();
    const bool misplaced = it->second.IsNull() && valueMark.line != keyMark.line;
    return YamlValue(it->second, childKey(name), self_.file(), misplaced ? keyMark : valueMark);
  }
  return std::nullopt;
}

namespace {

// Levenshtein distance, for "did you mean" hints on misspelt keys.
size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitute});
    }
  }
  return row[b.size()];
}

}  // namespace

YamlValue YamlMap::require(const std::string& name) {
  std::optional<YamlValue> v = find(name);
  if (v) return *v;
  // A misspelt required key ("radus") is reported where the typo is, not as a missing key.
  for (auto it = self_.node().begin(); it != self_.node().end(); ++it) {
    const std::string other = it->first.Scalar();
    if (!used_.count(other) && editDistance(other, name) <= 2 && other.size() > 2) {
      YamlValue(it->first, childKey(other), self_.file())
          .fail("unknown key (did you mean '" + name + "'? It is required here)");
    }
  }
  throw InputError(self_.where(), childKey(name), "required key is missing");
}

std::vector<std::string> YamlMap::keys() const {
  std::vector<std::string> out;
  for (auto it = self_.node().begin(); it != self_.node().end(); ++it)
    out.push_back(it->first.Scalar());
  return out;
}

void YamlMap::finish(const std::vector<std::string>& known) const {
  for (auto it = self_.node().begin(); it != self_.node().end(); ++it) {
    const std::string name = it->first.Scalar();
    if (used_.count(name)) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    const YamlValue keyNode(it->first, childKey(name), self_.file());
    bool isKnown = false;
    for (const auto& k : known) isKnown = isKnown || k == name;
    keyNode.fail(isKnown ? "key is not allowed together with the keys given here"
                         : "unknown key (allowed here: " + list + ")");
  }
}

namespace {

struct Bracket {
  char c;
  int line, column;  // 1-based
};

// The innermost '[' or '{' still open at byte `end` of `text`, skipping quoted scalars and
// comments. yaml-cpp reports an unclosed flow collection where it gave up (often the end
// of the file); the bracket that needs closing is what the user has to find.
std::optional<Bracket> unclosedBracket(const std::string& text, size_t end) {
  constexpr std::string_view kQuoteAfter = " \t\n[{,:";  // a quote here starts a scalar
  std::vector<Bracket> open;
  int line = 1, column = 0;
  char quote = 0;  // '"' or '\'' inside a quoted scalar
  bool comment = false;
  end = std::min(end, text.size());
  for (size_t i = 0; i < end; ++i) {
    const char c = text[i];
    const char prev = i > 0 ? text[i - 1] : '\n';
    ++column;
    if (c == '\n') {
      comment = false;
      ++line;
      column = 0;
    } else if (comment) {
      continue;
    } else if (quote == '"') {
      if (c == '\\' && i + 1 < end && text[i + 1] != '\n') {
        ++i;
        ++column;
      } else if (c == '"') {
        quote = 0;
      }
    } else if (quote == '\'') {
      if (c == '\'' && i + 1 < end && text[i + 1] == '\'') {
        ++i;  // '' is an escaped quote
        ++column;
      } else if (c == '\'') {
        quote = 0;
      }
    } else if (c == '#' && (prev == ' ' || prev == '\t' || prev == '\n')) {
      comment = true;
    } else if ((c == '"' || c == '\'') && kQuoteAfter.find(prev) != std::string_view::npos) {
      quote = c;
    } else if (c == '[' || c == '{') {
      open.push_back({c, line, column});
    } else if (!open.empty() &&
               ((c == ']' && open.back().c == '[') || (c == '}' && open.back().c == '{'))) {
      open.pop_back();
    }
  }
  if (open.empty()) return std::nullopt;
  return open.back();
}

// yaml-cpp 0.7 accepts a quoted scalar left open when the text ends with a line break: the
// scalar swallows the rest of the file. Check that every quoted scalar is closed.
// At least this many nodes, aliases expanded, are always allowed (a few seconds' walk).
constexpr std::size_t kMaxYamlNodes = 50000000;

// visits: the nodes seen so far, aliases expanded (an alias is its anchor's whole tree again);
// at most maxVisits. A text of n bytes holds at most about n nodes; aliases nested k deep,
// each used m times, expand to m^k (the "billion laughs": nine levels of ten took minutes,
// here and in every walk of the tree after it), so an expansion far beyond the text is
// refused before anything walks it.
void checkQuotesClosed(const YAML::Node& node, const std::string& text, const std::string& file,
                       std::size_t& visits, std::size_t maxVisits) {
  if (++visits > maxVisits)
    throw InputError({file, 1, 1}, "",
                     "the YAML aliases (*name) expand to more than " + std::to_string(maxVisits) +
                         " nodes (aliases used very many times, or nested in one another; "
                         "limit kMaxYamlNodes or 64 per byte of text): place a repeated mesh "
                         "with `instances:` instead");
  if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      checkQuotesClosed(it->first, text, file, visits, maxVisits);
      checkQuotesClosed(it->second, text, file, visits, maxVisits);
    }
  } else if (node.IsSequence()) {
    for (size_t i = 0; i < node.size(); ++i)
      checkQuotesClosed(node[i], text, file, visits, maxVisits);
  } else if (node.IsScalar()) {
    const YAML::Mark mark = node.Mark();
    if (mark.pos < 0 || static_cast<size_t>(mark.pos) >= text.size()) return;
    const char q = text[static_cast<size_t>(mark.pos)];
    if (q != '"' && q != '\'') return;  // a plain scalar
    for (size_t i = static_cast<size_t>(mark.pos) + 1; i < text.size(); ++i) {
      if (q == '"' && text[i] == '\\') {
        ++i;
      } else if (text[i] == q) {
        if (q == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
          ++i;  // '' is an escaped quote
        } else {
          return;
        }
      }
    }
    YamlValue(node, "", file)
        .fail(std::string("YAML syntax error: the quoted string (") + q + ") is never closed");
  }
}

// Records, per document, whether it has content and where that content starts.
class DocumentCounter final : public YAML::EventHandler {
 public:
  struct Document {
    bool hasContent = false;
    YAML::Mark mark;
  };
  std::vector<Document> documents;

  void OnDocumentStart(const YAML::Mark&) override { documents.emplace_back(); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { note(m, false); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override { note(m, true); }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                const std::string&) override {
    note(m, true);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    note(m, true);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    note(m, true);
  }
  void OnMapEnd() override {}

 private:
  void note(const YAML::Mark& m, bool content) {
    if (documents.empty()) documents.emplace_back();
    if (content && !documents.back().hasContent) documents.back() = {true, m};
  }
};

[[noreturn]] void throwSyntaxError(const YAML::Exception& e, const std::string& text,
                                   const std::string& file) {
  SourceLocation where{file, e.mark.line >= 0 ? e.mark.line + 1 : 0,
                       e.mark.column >= 0 ? e.mark.column + 1 : 0};
  std::string message = "YAML syntax error: " + e.msg;
  if (const auto* deep = dynamic_cast<const YAML::DeepRecursion*>(&e))  // it says "bad file"
    message = "YAML syntax error: lists or mappings nested " + std::to_string(deep->depth()) +
              " levels deep, yaml-cpp's limit";
  if (e.msg == YAML::ErrorMsg::END_OF_SEQ_FLOW || e.msg == YAML::ErrorMsg::END_OF_MAP_FLOW) {
    const size_t end = e.mark.pos >= 0 ? static_cast<size_t>(e.mark.pos) : text.size();
    if (const auto b = unclosedBracket(text, end)) {
      where.line = b->line;
      where.column = b->column;
      message += " ('" + std::string(1, b->c) + "' is never closed)";
    }
  }
  throw InputError(where, "", message);
}

}  // namespace

YamlValue parseYaml(const std::string& text, const std::string& file) {
  // yaml-cpp 0.7's LoadAll can loop forever on inputs such as "," (it keeps returning
  // empty documents without consuming input: jbeder/yaml-cpp#1319). So: the first document
  // with YAML::Load, and the document structure with the event parser, bounded — a stream
  // that yields more documents than it has bytes is not making progress.
  YAML::Node first;
  DocumentCounter counter;
  try {
    first = YAML::Load(text);
    std::istringstream in(text);
    YAML::Parser parser(in);
    const size_t maxDocuments = text.size() + 2;
    while (parser.HandleNextDocument(counter)) {
      if (counter.documents.size() > maxDocuments)
        throw InputError(
            {file, 1, 1}, "",
            "YAML syntax error: the text is not a YAML document (a stray ',' or flow indicator?)");
    }
  } catch (const YAML::Exception& e) {
    throwSyntaxError(e, text, file);
  }
  if (!first) return YamlValue(YAML::Node(), "", file);
  std::size_t visits = 0;
  checkQuotesClosed(first, text, file, visits, std::max(64 * text.size(), kMaxYamlNodes));
  // YAML::Load alone would silently drop everything after a second '---'.
  for (size_t i = 1; i < counter.documents.size(); ++i) {
    if (counter.documents[i].hasContent) {
      const YAML::Mark& m = counter.documents[i].mark;
      throw InputError({file, m.line + 1, m.column + 1}, "",
                       "a scene file holds one YAML document; this is a second");
    }
  }
  return YamlValue(first, "", file);
}

}  // namespace camsim
