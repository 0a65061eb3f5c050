// Wavefront material library (.mtl) files, the materials an OBJ names with `mtllib` and
// `usemtl`. This reader only parses; the scene loader maps the values to camsim materials
// (integrator/scene/scene_loader_mtl.cpp, docs/scene-format.md "Materials of OBJ files").
//
// | statement                | field    | unit / range                | default |
// |--------------------------|----------|-----------------------------|---------|
// | newmtl NAME              | name     | the rest of the line        | —       |
// | Kd r [g b]               | kd       | linear RGB, each ≥ 0        | none    |
// | Ks r [g b]               | ks       | linear RGB, each ≥ 0        | none    |
// | Ns e                     | ns       | Blinn–Phong exponent ≥ 0    | none    |
// | Ni η                     | ni       | index of refraction > 0     | none    |
// | d a / Tr t               | dissolve | opacity in [0, 1]; d = 1 − Tr | none  |
// | illum n                  | illum    | integer 0 … 10              | none    |
// | map_Kd [-s u v] [-o u v] FILE | mapKd | uv scale and offset; FILE relative to the .mtl | none |
//
// Single values: `Kd 0.5` is grey (g = b = r, as the format allows). Keywords are matched
// without regard to case (writers spell map_Kd, map_kd, MAP_KD). Everything else — other
// statements (Ka, Ke, Tf, map_Bump, bump, disp, the PBR extension's Pr, Pm, …), the
// `Kd spectral`/`Kd xyz` forms, map options other than -s and -o (-bm, -clamp, -mm, …),
// statements before the first newmtl — is kept in `ignored` with its line and a reason,
// for the loader's notes. Trailing `# comments` end numeric statements; in names and file
// names a '#' is kept.
//
// Errors (malformed or out-of-range numbers, a statement without its values, a duplicate
// newmtl name, an unreadable file) throw InputError with the file and line.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace camsim {

// A statement the reader keeps but camsim does not use (or not all of).
struct MtlIgnored {
  std::string key;  // as spelt in the file (map options: "map_Kd -bm")
  int line = 0;
  std::string reason;  // why it is ignored, a phrase ("camsim has no bump maps")
};

// A value of a statement and its line (the last of repeated statements wins).
template <class T>
struct MtlField {
  T value{};
  int line = 0;
};

// map_Kd: the file as written (relative to the .mtl's folder), its -s and -o, its line.
struct MtlTextureMap {
  std::string file;
  glm::dvec2 scale{1.0}, offset{0.0};
  int line = 0;
};

// (Field and TextureMap are defined outside MtlMaterial: Clang 14 crashes on a nested
// template with a default member initializer used inside the enclosing class.)
struct MtlMaterial {
  template <class T>
  using Field = MtlField<T>;
  using TextureMap = MtlTextureMap;

  std::string name;
  int line = 0;  // its newmtl line
  std::optional<Field<glm::dvec3>> kd, ks;
  std::optional<Field<double>> ns, ni, dissolve;
  std::optional<Field<int>> illum;
  std::optional<TextureMap> mapKd;
  std::vector<MtlIgnored> ignored;  // in file order
};

struct MtlLibrary {
  std::string sourceName;  // for messages
  std::vector<MtlMaterial> materials;
  std::vector<MtlIgnored> ignored;  // statements before the first newmtl
};

MtlLibrary parseMtl(std::string_view text, const std::string& sourceName);
MtlLibrary readMtl(const std::filesystem::path& path);

}  // namespace camsim
