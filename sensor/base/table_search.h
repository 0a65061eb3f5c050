// TableSearch: where the spectral tables (CSV) named in a description are looked for, and
// the record of the files found. Scene files and sensor descriptions both name tables this
// way: an absolute path, or a name looked up in an ordered list of folders. A scene
// searches its own folder, its spectra_path, --spectra-path, then luts/spectra
// (integrator/scene/scene_loader.cpp); a sensor description its own folder, luts/spectra, then
// luts/ (sensor/model/sensor_spec.cpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sensor/base/yaml_reader.h"

namespace camsim {

struct TableSearch {
  std::vector<std::filesystem::path> directories;           // in order
  std::vector<std::filesystem::path>* filesRead = nullptr;  // each file found is appended

  // Records a file the description made camsim read (tables and, for scenes, meshes,
  // textures and maps): the record lists a render's inputs, each path lexically normal
  // (scenes/../x.csv as x.csv; relative stays relative) unless that names another file
  // (a symbolic link before the ..): then as it was opened.
  void noteRead(const std::filesystem::path& file) const;
  // The file `name`: itself if absolute, else the first of `directories` holding it;
  // recorded. Nothing if there is no such regular file (or the name is empty).
  std::optional<std::filesystem::path> locate(const std::string& name) const;
  // locate(name) for the table written at `where`; fails there when the name is empty or
  // no such file exists, naming the folders searched and what it is ("spectral table",
  // "lens file").
  std::filesystem::path find(const YamlValue& where, const std::string& name,
                             const std::string& what = "spectral table") const;
};

}  // namespace camsim
