#include "sensor/table_search.h"

#include "sensor/file_status.h"

namespace camsim {

std::filesystem::path TableSearch::find(const YamlValue& where, const std::string& name) const {
  if (name.empty()) where.fail("empty file name");
  const std::filesystem::path p(name);
  std::filesystem::path found;
  if (p.is_absolute()) {
    if (isRegularFile(p)) found = p;
  } else {
    for (const auto& dir : directories) {
      if (isRegularFile(dir / p)) {
        found = dir / p;
        break;
      }
    }
  }
  if (found.empty()) {
    std::string searched;
    for (const auto& dir : directories) searched += (searched.empty() ? "" : ", ") + dir.string();
    where.fail("spectral table '" + name + "' not found" +
               (p.is_absolute() ? std::string() : " (searched: " + searched + ")"));
  }
  noteRead(found);
  return found;
}

}  // namespace camsim
