// TableSearch: where the spectral tables (CSV) named in a description are looked for, and
// the record of the files found. Scene files and sensor descriptions both name tables this
// way: an absolute path, or a name looked up in an ordered list of folders (the
// description's own folder first, then luts/spectra and luts/).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sensor/yaml_reader.h"

namespace camsim {

struct TableSearch {
  std::vector<std::filesystem::path> directories;           // in order
  std::vector<std::filesystem::path>* filesRead = nullptr;  // each file found is appended

  // Records a file the description made camsim read (tables and, for scenes, meshes,
  // textures and maps): the record lists a render's inputs.
  void noteRead(const std::filesystem::path& file) const {
    if (filesRead) filesRead->push_back(file);
  }
  // The table `name` (as written at `where`): itself if absolute, else the first of
  // `directories` holding it. Records it. Fails at `where` when the name is empty or no
  // such file exists, naming the folders searched.
  std::filesystem::path find(const YamlValue& where, const std::string& name) const;
};

}  // namespace camsim
