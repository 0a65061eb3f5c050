#include "integrator/scene/scene_ids.h"

#include <algorithm>
#include <map>

namespace camsim {

SceneIds sceneIds(const SceneDescription& d) {
  SceneIds ids;
  for (IdTable& t : ids.tables) {
    t.names = {""};
    t.numbers = {0};
  }
  IdTable& instances = ids.tables[static_cast<std::size_t>(IdKind::kInstance)];
  IdTable& classes = ids.tables[static_cast<std::size_t>(IdKind::kClass)];
  IdTable& materials = ids.tables[static_cast<std::size_t>(IdKind::kMaterial)];

  for (const MaterialDescription& m : d.materials) {
    materials.names.push_back(m.name);
    materials.numbers.push_back(static_cast<std::uint32_t>(materials.numbers.size()));
  }
  std::uint32_t largest = 0;  // of the integer classes: named ones are numbered after it
  for (const ShapeDescription& s : d.shapes)
    if (s.classNumber) largest = std::max(largest, *s.classNumber);
  std::map<std::string, std::uint32_t> classEntry;
  for (std::size_t i = 0; i < d.shapes.size(); ++i) {
    const ShapeDescription& s = d.shapes[i];
    instances.names.push_back(s.label);
    instances.numbers.push_back(static_cast<std::uint32_t>(i + 1));
    instances.ofShape.push_back(static_cast<std::uint32_t>(i + 1));
    materials.ofShape.push_back(s.material < 0 ? 0 : static_cast<std::uint32_t>(s.material) + 1);
    if (s.className.empty()) {
      classes.ofShape.push_back(0);
      continue;
    }
    auto [it, added] =
        classEntry.emplace(s.className, static_cast<std::uint32_t>(classes.names.size()));
    if (added) {
      classes.names.push_back(s.className);
      classes.numbers.push_back(s.classNumber ? *s.classNumber : ++largest);
    }
    classes.ofShape.push_back(it->second);
  }
  return ids;
}

}  // namespace camsim
