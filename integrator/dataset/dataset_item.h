// One dataset item resolved: the manifest's base scene with the item's edits applied and
// loaded, and the hash that says whether its outputs on disk are still its outputs.
//
// Errors name the manifest: an error the loader reports at a key an edit set (or below it)
// is reported at that edit's line in the manifest ("sweep.yaml:14:7: key
// 'grid.camera.f_number': item 3: …"); any other error of an item names the item's manifest
// entry and the scene key. The base scene alone is checked first, with its own lines. An
// error found later, while the item renders, is mapped the same way (manifestError).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "integrator/dataset/manifest.h"
#include "integrator/scene/scene_description.h"
#include "sensor/base/input_error.h"
#include "sensor/base/yaml_edit.h"

namespace camsim {

struct ResolvedItem {
  std::size_t index = 0;
  std::string sceneText;  // the resolved scene (written as the item's scene.yaml)
  SceneDescription description;
  // The key paths the item sets (seeds included), last value wins, as YAML text.
  std::vector<std::pair<std::string, std::string>> parameters;
  // FNV-1a 64 over camsim's version, `outputKey`, the resolved scene and the content of
  // every file it reads (meshes, textures, tables): a changed base scene, asset or option
  // changes it.
  std::string hash;
  // What maps a loader's or a render's error back to the manifest (above).
  std::vector<YamlEdit> edits;
  std::vector<std::string> editPaths;  // each edit's canonical path (EditedYaml)
  SourceLocation where;                // the item's manifest entry
  std::string displayName;             // the resolved scene's name in messages

  // An error the scene loader or the render raised about the resolved scene, at the line in
  // the manifest that set its key, or else at the item's entry; one located in a file of its
  // own (a sensor description, a dark frame) keeps that place, prefixed "item N: ".
  InputError manifestError(const InputError& e) const;
};

// Checks that the base scene loads on its own (InputError with its own file:line).
void checkBaseScene(const Manifest& manifest);

// outputKey: the output options that change the files (OCIO config, display, view, …).
ResolvedItem resolveItem(const Manifest& manifest, const DatasetItem& item,
                         const std::string& outputKey);

// The item's folder name: six digits (000042), more when the index needs them.
std::string itemFolderName(std::size_t index);

}  // namespace camsim
