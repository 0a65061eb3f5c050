// Editing a YAML document by key paths: a dataset manifest's overrides applied to its base
// scene (integrator/dataset/manifest.h). yaml-cpp stays in the .cpp.
//
// A key path names a value the way the scene loader's messages do:
//   camera.f_number            a map key
//   shapes[2].radius           element 2 of a sequence (0-based)
//   shapes[red_ball].motion    the element of a sequence of maps whose `name` is red_ball
// Keys are letters, digits and '_'. Every key and element up to the last must exist but a
// missing map key is created (empty map) so that a path may add a block the base scene
// does not have, e.g. sensor.auto_exposure.target; the scene loader then checks the result.
// A null value (~ or null) on a map key removes the key (the loader's default applies).
// Errors (InputError at the edit's location, naming the edit's key):
//   a malformed path, an index past the end, no element of that name, a key inside a
//   scalar, a value that is not YAML.
#pragma once

#include <string>
#include <vector>

#include "sensor/base/input_error.h"

namespace camsim {

class YamlValue;

struct YamlEdit {
  std::string path;      // a key path (above)
  std::string value;     // the new value as YAML text: "2.8", "[0, 1, 2]", "{open: 0, close: 0.01}"
  SourceLocation where;  // where the edit was written (errors name it)
  std::string key;       // how errors name it, e.g. "grid.camera.f_number"
  // Applied only where everything but the last key exists (e.g. sensor.noise_seed on a
  // scene with a sensor); skipped otherwise (its canonical path is then empty).
  bool ifParentExists = false;
};

struct EditedYaml {
  std::string text;  // the edited document (block style; comments are not kept)
  // Each edit's path with names resolved to indices ("shapes[4].motion"), in edit order:
  // what the loader's error keys are matched against.
  std::vector<std::string> canonicalPaths;
};

// `text` is a YAML document (file names it in syntax errors); edits apply in order.
EditedYaml applyYamlEdits(const std::string& text, const std::string& file,
                          const std::vector<YamlEdit>& edits);

// A value as one line of flow-style YAML ("[1, 2, 3]", "{a: 1}", "2.5"), as written.
std::string yamlFlowText(const YamlValue& value);

// A number as the shortest text that reads back to the same double ("0.1", "1e-05").
std::string yamlNumber(double value);

// The checked path segments of a key path (InputError at where, naming key, if malformed):
// each is a map key, or an element "[3]" / "[name]".
struct KeyPathSegment {
  enum class Kind { kKey, kIndex, kName } kind = Kind::kKey;
  std::string text;  // the key or the element name
  std::size_t index = 0;
};
std::vector<KeyPathSegment> parseKeyPath(const std::string& path, const SourceLocation& where,
                                         const std::string& key);

}  // namespace camsim
