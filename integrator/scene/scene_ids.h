// SceneIds: the ids the ID mattes and dominant-id channels give what a camera ray hits
// (aovs instance_id, class_id, material_id; docs/output.md#id-mattes). For each kind a
// table of names — entry 0 is "nothing": a miss, an unlabelled shape, a shape without a
// material — and, per shape, its entry. The names are what Cryptomatte hashes; the numbers
// are what the dominant-id channel holds:
//
// | kind      | entry of a shape                  | name              | number |
// |-----------|-----------------------------------|-------------------|--------|
// | instance  | one per shape, in scene order     | its `name:` (or "shapes[i]") | i + 1 |
// | class     | one per distinct `class:`         | the class text    | an integer class: itself; a named one: after the largest integer, in order of first use |
// | material  | one per material the scenes names | its key under `materials:` | its index + 1 |
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "integrator/scene/scene_description.h"

namespace camsim {

// The largest class number: the dominant-id channels are float, exact to 2^24 (the scene
// loader refuses an integer class above it, or names numbered past it).
inline constexpr std::uint32_t kMaxClassNumber = 1u << 24;

enum class IdKind : std::uint8_t { kInstance, kClass, kMaterial };
inline constexpr int kIdKindCount = 3;
inline const char* idKindName(IdKind k) {
  constexpr const char* names[kIdKindCount] = {"instance", "class", "material"};
  return names[static_cast<int>(k)];
}
// The Cryptomatte type name of each kind (the EXR layer prefix; Blender's for two of them).
inline const char* cryptomatteTypeName(IdKind k) {
  constexpr const char* names[kIdKindCount] = {"CryptoObject", "CryptoClass", "CryptoMaterial"};
  return names[static_cast<int>(k)];
}
// The id kind an AOV asks for (none: not an id AOV).
inline std::optional<IdKind> idKindOf(Aov a) {
  switch (a) {
    case Aov::kInstanceId:
      return IdKind::kInstance;
    case Aov::kClassId:
      return IdKind::kClass;
    case Aov::kMaterialId:
      return IdKind::kMaterial;
    default:
      return std::nullopt;
  }
}
// The id kinds `aovs` asks for, in their order.
inline std::vector<IdKind> idKindsOf(const std::vector<Aov>& aovs) {
  std::vector<IdKind> kinds;
  for (Aov a : aovs)
    if (const std::optional<IdKind> k = idKindOf(a)) kinds.push_back(*k);
  return kinds;
}

struct IdTable {
  std::vector<std::string> names;      // entry 0: "" (nothing)
  std::vector<std::uint32_t> numbers;  // the dominant-id value of each entry; entry 0: 0
  std::vector<std::uint32_t> ofShape;  // per shape: its entry
};

struct SceneIds {
  std::array<IdTable, kIdKindCount> tables;
  const IdTable& operator[](IdKind k) const { return tables[static_cast<std::size_t>(k)]; }
};

SceneIds sceneIds(const SceneDescription& description);

}  // namespace camsim
