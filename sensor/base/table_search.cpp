#include "sensor/base/table_search.h"

#include "sensor/base/file_status.h"

namespace camsim {

void TableSearch::noteRead(const std::filesystem::path& file) const {
  if (!filesRead) return;
  std::filesystem::path normal = file.lexically_normal();
  std::error_code ec;
  if (normal != file && !std::filesystem::equivalent(normal, file, ec)) normal = file;
  filesRead->push_back(std::move(normal));
}

std::optional<std::filesystem::path> TableSearch::locate(const std::string& name) const {
  if (name.empty()) return std::nullopt;
  const std::filesystem::path p(name);
  std::optional<std::filesystem::path> found;
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
  if (found) noteRead(*found);
  return found;
}

std::filesystem::path TableSearch::find(const YamlValue& where, const std::string& name,
                                        const std::string& what) const {
  if (name.empty()) where.fail("empty file name");
  if (std::optional<std::filesystem::path> found = locate(name)) return *found;
  std::string searched;
  for (const auto& dir : directories) searched += (searched.empty() ? "" : ", ") + dir.string();
  where.fail(what + " '" + name + "' not found" +
             (std::filesystem::path(name).is_absolute() ? std::string()
                                                        : " (searched: " + searched + ")"));
}

}  // namespace camsim
