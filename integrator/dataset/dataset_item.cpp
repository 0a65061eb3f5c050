#include "integrator/dataset/dataset_item.h"

#include <fstream>
#include <map>
#include <sstream>

#include "integrator/scene/scene_loader.h"
#include "sensor/base/fnv1a.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"

namespace camsim {
namespace {

// Whether loader key `key` lies at or below the canonical path `path`.
bool under(const std::string& key, const std::string& path) {
  if (path.empty() || key.compare(0, path.size(), path) != 0) return false;
  return key.size() == path.size() || key[path.size()] == '.' || key[path.size()] == '[';
}

std::string fileContentHash(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return fnv1aHex(text.str());
}

// An item's own files (item.json, params.json) lie beside the render's NAME.json: a scene
// named after one of them overwrote it, and item.json then listed a hash of the other.
// Refused where the name comes from: an edit of the item, the base scene's `name`, or the
// base scene's file name (the manifest's `scene:`).
void checkItemName(const Manifest& manifest, const DatasetItem& item, const std::string& name) {
  if (name != "item" && name != "params") return;
  const std::string taken = "is taken by the item's own " + name + ".json: choose another";
  for (std::size_t k = item.edits.size(); k-- > 0;)
    if (item.edits[k].path == "name")
      throw InputError(item.edits[k].where, item.edits[k].key,
                       "item " + std::to_string(item.index) + ": name = " + item.edits[k].value +
                           ": the name '" + name + "' " + taken);
  const YamlValue base = parseYaml(manifest.sceneText, manifest.scene.string());
  if (const auto n = YamlMap(base).find("name"))
    n->fail("the name '" + name + "' of a dataset's base scene " + taken);
  throw InputError(manifest.sceneWhere, "scene",
                   "the base scene's file name gives it the name '" + name + "', which " + taken +
                       " (give the scene a name:)");
}

}  // namespace

std::string itemFolderName(std::size_t index) {
  return formatSixDigits(static_cast<long long>(index));
}

void checkBaseScene(const Manifest& manifest) {
  (void)loadSceneFromText(manifest.sceneText, manifest.scene.string(),
                          sceneBaseDir(manifest.scene));
}

ResolvedItem resolveItem(const Manifest& manifest, const DatasetItem& item,
                         const std::string& outputKey) {
  ResolvedItem r;
  r.index = item.index;
  std::vector<YamlEdit> edits = item.edits;
  // The scene's name stays its own (the loader would take it from the display name).
  const YamlValue base = parseYaml(manifest.sceneText, manifest.scene.string());
  if (!YamlMap(base).has("name"))
    edits.insert(edits.begin(), {"name", manifest.scene.stem().string(), item.where, "scene"});
  const EditedYaml edited = applyYamlEdits(manifest.sceneText, manifest.scene.string(), edits);
  r.sceneText = edited.text;
  r.edits = edits;
  r.editPaths = edited.canonicalPaths;
  r.where = item.where;
  // Stable across runs, shards and machines (it is written into the outputs).
  r.displayName = manifest.scene.filename().string() + " (dataset " +
                  manifest.file.filename().string() + ", item " + std::to_string(item.index) + ")";
  try {
    r.description = loadSceneFromText(r.sceneText, r.displayName, sceneBaseDir(manifest.scene));
  } catch (const InputError& e) {
    throw r.manifestError(e);
  }
  checkItemName(manifest, item, r.description.name);
  std::map<std::string, std::string> last;
  for (std::size_t k = 0; k < edits.size(); ++k) {
    if (edited.canonicalPaths[k].empty() || edits[k].path == "name") continue;
    if (!last.count(edits[k].path)) r.parameters.emplace_back(edits[k].path, "");
    last[edits[k].path] = edits[k].value;
  }
  for (auto& [path, value] : r.parameters) value = last[path];
  std::string key = std::string(CAMSIM_VERSION) + "\n" + outputKey + "\n" + r.sceneText;
  for (const auto& f : r.description.inputFiles)
    key += "\n" + f.string() + " " + fileContentHash(f);
  r.hash = fnv1aHex(key);
  return r;
}

InputError ResolvedItem::manifestError(const InputError& e) const {
  const std::string itemName = "item " + std::to_string(index);
  if (!e.where().file.empty() && e.where().file != displayName)
    return InputError(e.where(), e.key(), itemName + ": " + e.message());
  for (std::size_t k = edits.size(); k-- > 0;)
    if (under(e.key(), editPaths[k]))
      return InputError(edits[k].where, edits[k].key,
                        itemName + ": " + e.key() + " = " + edits[k].value + ": " + e.message());
  return InputError(where, e.key(),
                    itemName + " (the base scene with this item's values): " + e.message());
}

}  // namespace camsim
