#include "sensor/output_set.h"

#include <unistd.h>

#include <system_error>

namespace camsim {

OutputSet::OutputSet(std::filesystem::path directory) : directory_(std::move(directory)) {}

OutputSet::~OutputSet() {
  if (committed_) return;
  std::error_code ignored;
  for (const auto& [temp, final] : files_) std::filesystem::remove(temp, ignored);
}

std::filesystem::path OutputSet::add(const std::string& fileName) {
  const auto temp =
      directory_ / ("." + fileName + ".camsim-tmp-" + std::to_string(static_cast<long>(::getpid())));
  files_.emplace_back(temp, directory_ / fileName);
  return temp;
}

std::vector<std::filesystem::path> OutputSet::commit() {
  std::vector<std::filesystem::path> finals;
  for (const auto& [temp, final] : files_) {
    std::filesystem::rename(temp, final);
    finals.push_back(final);
  }
  committed_ = true;
  return finals;
}

}  // namespace camsim
