#include "sensor/base/yaml_edit.h"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

#include "sensor/base/yaml_reader.h"

namespace camsim {
namespace {

bool keyChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

[[noreturn]] void fail(const YamlEdit& e, const std::string& message) {
  throw InputError(e.where, e.key, message);
}

// Names of a sequence's map elements, for "no element named …" messages.
std::string elementNames(const YAML::Node& seq) {
  std::string names;
  for (const YAML::Node& item : seq)
    if (item.IsMap() && item["name"] && item["name"].IsScalar())
      names += (names.empty() ? "" : ", ") + item["name"].Scalar();
  return names.empty() ? "none has a name" : "names: " + names;
}

}  // namespace

std::vector<KeyPathSegment> parseKeyPath(const std::string& path, const SourceLocation& where,
                                         const std::string& key) {
  auto bad = [&](const std::string& why) {
    throw InputError(where, key,
                     "malformed key path '" + path + "': " + why +
                         " (expected e.g. camera.f_number, shapes[2].radius, shapes[ball].motion)");
  };
  std::vector<KeyPathSegment> out;
  std::size_t i = 0;
  if (path.empty()) bad("it is empty");
  while (i < path.size()) {
    if (!out.empty()) {
      if (path[i] == '.') {
        ++i;
      } else if (path[i] != '[') {
        bad("expected '.' or '[' after '" + path.substr(0, i) + "'");
      }
    }
    if (i < path.size() && path[i] == '[') {
      if (out.empty()) bad("it starts with '['");
      const std::size_t close = path.find(']', i);
      if (close == std::string::npos) bad("'[' is never closed");
      const std::string inner = path.substr(i + 1, close - i - 1);
      if (inner.empty()) bad("empty []");
      KeyPathSegment s;
      if (std::isdigit(static_cast<unsigned char>(inner[0]))) {
        s.kind = KeyPathSegment::Kind::kIndex;
        const auto [p, ec] = std::from_chars(inner.data(), inner.data() + inner.size(), s.index);
        if (ec != std::errc() || p != inner.data() + inner.size()) bad("bad index [" + inner + "]");
      } else {
        for (char c : inner)
          if (!keyChar(c)) bad("bad element name [" + inner + "]");
        s.kind = KeyPathSegment::Kind::kName;
      }
      s.text = inner;
      out.push_back(s);
      i = close + 1;
      continue;
    }
    const std::size_t start = i;
    while (i < path.size() && keyChar(path[i])) ++i;
    if (i == start) bad("an empty key at position " + std::to_string(start + 1));
    out.push_back({KeyPathSegment::Kind::kKey, path.substr(start, i - start), 0});
  }
  return out;
}

EditedYaml applyYamlEdits(const std::string& text, const std::string& file,
                          const std::vector<YamlEdit>& edits) {
  // parseYaml checks the syntax and names the location; then a fresh node tree to edit.
  (void)parseYaml(text, file);
  YAML::Node root = YAML::Load(text);
  EditedYaml out;
  for (const YamlEdit& e : edits) {
    const std::vector<KeyPathSegment> segments = parseKeyPath(e.path, e.where, e.key);
    YAML::Node value;
    try {
      value = YAML::Load(e.value);
    } catch (const YAML::Exception& x) {
      fail(e, "the value '" + e.value + "' is not YAML: " + x.msg);
    }
    YAML::Node node = root;
    std::string canonical, walked;
    if (e.ifParentExists) {
      YAML::Node probe = root;
      bool exists = true;
      for (std::size_t k = 0; exists && k + 1 < segments.size(); ++k) {
        const KeyPathSegment& s = segments[k];
        exists = s.kind == KeyPathSegment::Kind::kKey && probe.IsMap() && probe[s.text];
        if (exists) probe.reset(probe[s.text]);
      }
      if (!exists || !probe.IsMap()) {
        out.canonicalPaths.emplace_back();
        continue;
      }
    }
    for (std::size_t k = 0; k < segments.size(); ++k) {
      const KeyPathSegment& s = segments[k];
      const bool last = k + 1 == segments.size();
      const std::string here = walked.empty() ? "the scene's top level" : "'" + walked + "'";
      if (s.kind == KeyPathSegment::Kind::kKey) {
        if (node.IsNull()) node = YAML::Node(YAML::NodeType::Map);  // in place: a null value
        if (!node.IsMap()) fail(e, here + " is not a map, so it has no key '" + s.text + "'");
        canonical += (canonical.empty() ? "" : ".") + s.text;
        walked += (walked.empty() ? "" : ".") + s.text;
        if (last) {
          if (value.IsNull())
            node.remove(s.text);  // null: the key goes, the loader's default applies
          else
            node[s.text] = value;
        } else {
          if (!node[s.text]) node[s.text] = YAML::Node(YAML::NodeType::Map);
          node.reset(node[s.text]);  // rebinds (operator= would overwrite the value)
        }
        continue;
      }
      if (!node.IsSequence())
        fail(e, here + " is not a list, so it has no element [" + s.text + "]");
      std::size_t index = s.index;
      if (s.kind == KeyPathSegment::Kind::kName) {
        index = node.size();
        for (std::size_t j = 0; j < node.size(); ++j)
          if (node[j].IsMap() && node[j]["name"] && node[j]["name"].IsScalar() &&
              node[j]["name"].Scalar() == s.text)
            index = j;
        if (index == node.size())
          fail(e, here + " has no element named '" + s.text + "' (" + elementNames(node) + ")");
      } else if (index >= node.size()) {
        fail(e, here + " has " + std::to_string(node.size()) + " elements: [" + s.text +
                    "] is past the end");
      }
      canonical += "[" + std::to_string(index) + "]";
      walked += "[" + s.text + "]";
      if (last) {
        node[index] = value;
      } else {
        node.reset(node[index]);
      }
    }
    out.canonicalPaths.push_back(canonical);
  }
  YAML::Emitter emitter;
  emitter << root;
  out.text = std::string(emitter.c_str()) + "\n";
  return out;
}

std::string yamlFlowText(const YamlValue& value) {
  YAML::Emitter emitter;
  emitter.SetMapFormat(YAML::Flow);
  emitter.SetSeqFormat(YAML::Flow);
  emitter << value.node();
  return emitter.c_str();
}

std::string yamlNumber(double value) {
  if (!std::isfinite(value)) return value != value ? ".nan" : (value > 0 ? ".inf" : "-.inf");
  char buf[32];
  const auto [p, ec] = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, p);
}

}  // namespace camsim
