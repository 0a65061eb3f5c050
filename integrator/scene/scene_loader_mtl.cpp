// A mesh file's own materials (OBJ `mtllib` + `usemtl`, .mtl files: mtl_reader.h) → camsim
// materials, and the split of such a mesh into one shape per material it uses. Used only for
// mesh shapes without a `material:` (docs/scene-format.md, "Materials of OBJ files").
//
// | .mtl                          | camsim                                                  |
// |-------------------------------|---------------------------------------------------------|
// | d < 1, or illum 4, 6, 7       | dielectric, η = Ni (none: 1.5), smooth; Kd, Ks, Ns unused |
// | otherwise Ks > 0, illum ≠ 0, 1 | plastic: ks = mean(Ks) (≤ 1), α = √(2 / (Ns + 2)) (Ns: 0), Beckmann |
// | otherwise                     | diffuse                                                 |
// | Kd r g b                      | reflectance ρ = Jakob–Hanika uplift of linear Rec.709 (r, g, b) clamped to [0, 1], as {rgb: …}; none: 0.5 |
// | map_Kd [-s u v] [-o u v] FILE | reflectance = that image (relative to the .mtl; PNG sRGB, EXR linear), uv' = uv·s + o |
//
// α = √(2/(Ns + 2)) is the Blinn–Phong exponent ↔ Beckmann width equivalence of Walter,
// Marschner, Li and Torrance, "Microfacet Models for Refraction through Rough Surfaces"
// (EGSR 2007), §5.2: α_p = 2 α_b⁻² − 2. Every statement that is not used, and every value
// changed, is one note in SceneDescription::notes (grouped per .mtl file and reason).
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "integrator/geometry/mtl_reader.h"
#include "integrator/scene/scene_loader_parts.h"
#include "integrator/textures/image_texture.h"
#include "sensor/base/file_status.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"

namespace camsim {
namespace {

// Notes with the same file, key and text are merged: the first line is named, the others
// counted.
class Notes {
 public:
  void add(const std::string& file, int line, const std::string& key, const std::string& text) {
    const std::string id = file + '\n' + key + '\n' + text;
    auto [it, added] = index_.try_emplace(id, entries_.size());
    if (added)
      entries_.push_back({file, line, key, text, 0});
    else
      ++entries_[it->second].more;
  }
  void addIgnored(const std::string& file, const MtlIgnored& i) {
    add(file, i.line, i.key, "ignored: " + i.reason);
  }
  void appendTo(std::vector<std::string>& out) const {
    for (const Entry& e : entries_) {
      std::string s = e.file + " line " + std::to_string(e.line) + ": '" + e.key + "' " + e.text;
      if (e.more > 0)
        s += " (and " + std::to_string(e.more) + " more line" + (e.more > 1 ? "s" : "") + ")";
      s += ".";
      if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);  // other shapes'
    }
  }

 private:
  struct Entry {
    std::string file;
    int line;
    std::string key, text;
    int more;
  };
  std::vector<Entry> entries_;
  std::map<std::string, std::size_t> index_;
};

struct Library {
  std::filesystem::path path;
  MtlLibrary mtl;
};

// The .mtl files of the mtllib lines: each line's text as one file name (names may contain
// spaces), else as several separated by spaces.
std::vector<Library> readLibraries(const MeshData& mesh, const std::filesystem::path& objPath,
                                   const TableSearch& search) {
  std::vector<Library> libs;
  const std::filesystem::path dir = objPath.parent_path();
  for (const MeshMaterialLibrary& ref : mesh.materialLibraries) {
    std::vector<std::string> names = {ref.files};
    if (!isRegularFile(dir / ref.files)) {
      names.clear();
      std::size_t i = 0;
      while (i < ref.files.size()) {
        const std::size_t start = ref.files.find_first_not_of(" \t", i);
        if (start == std::string::npos) break;
        i = std::min(ref.files.find_first_of(" \t", start), ref.files.size());
        names.push_back(ref.files.substr(start, i - start));
      }
    }
    for (const std::string& name : names) {
      const std::filesystem::path p = dir / name;
      if (!isRegularFile(p))
        throw InputError(
            {objPath.string(), ref.line, 0}, "",
            "mtllib: material library '" + name + "' not found (looked for " + p.string() + ")");
      search.noteRead(p);
      libs.push_back({p, readMtl(p)});
    }
  }
  return libs;
}

// Every material of the libraries by name, with its library: the first library defining a
// name wins.
std::map<std::string, std::pair<const Library*, const MtlMaterial*>> byName(
    const std::vector<Library>& libs) {
  std::map<std::string, std::pair<const Library*, const MtlMaterial*>> out;
  for (const Library& lib : libs)
    for (const MtlMaterial& m : lib.mtl.materials) out.try_emplace(m.name, &lib, &m);
  return out;
}

TextureDescription textureOf(const MtlMaterial::TextureMap& map, const Library& lib,
                             ImportedMaterials& imported, const TableSearch& search) {
  const std::string src = lib.path.string();
  TextureDescription t;
  t.kind = TextureDescription::Kind::kImage;
  t.file = lib.path.parent_path() / map.file;
  try {
    t.encoding = defaultTextureEncoding(t.file);  // checks the file type
  } catch (const InputError& e) {
    throw InputError({src, map.line, 0}, "", "map_Kd: " + e.message());
  }
  if (!isRegularFile(t.file))
    throw InputError(
        {src, map.line, 0}, "",
        "map_Kd: texture file '" + map.file + "' not found (looked for " + t.file.string() + ")");
  std::shared_ptr<const TextureImage>& image = imported.images[t.file];
  if (!image) {
    try {
      image = std::make_shared<const TextureImage>(loadTextureImage(t.file, t.encoding));
    } catch (const InputError& e) {
      throw InputError({src, map.line, 0}, "",
                       "map_Kd: texture file '" + t.file.string() + "': " + e.message());
    }
    search.noteRead(t.file);
  }
  t.image = image;
  t.uvScale = glm::vec2(map.scale);
  t.uvOffset = glm::vec2(map.offset);
  return t;
}

MaterialDescription mapMaterial(const MtlMaterial& m, const Library& lib, const std::string& name,
                                ImportedMaterials& imported, const TableSearch& search,
                                Notes& notes) {
  using Type = MaterialDescription::Type;
  const std::string src = lib.path.string();
  auto note = [&](int line, const std::string& key, const std::string& text) {
    notes.add(src, line, key, text);
  };
  for (const MtlIgnored& i : m.ignored) notes.addIgnored(src, i);
  MaterialDescription d;
  d.name = name;
  const int illum = m.illum ? m.illum->value : 2;
  const bool transparent =
      (m.dissolve && m.dissolve->value < 1.0) || illum == 4 || illum == 6 || illum == 7;
  const double ks = m.ks ? (m.ks->value.x + m.ks->value.y + m.ks->value.z) / 3.0 : 0.0;
  if (m.illum && (illum == 3 || illum == 5 || illum >= 8))
    note(
        m.illum->line, "illum",
        "read as illum 2 (mirror and ray-trace switches of illum 3, 5, 8, 9, 10 are not modelled)");
  if (m.illum && illum == 0)
    note(m.illum->line, "illum", "approximated: illum 0 (colour without lighting) is lit diffuse");

  if (transparent) {
    d.type = Type::kDielectric;
    d.eta = Spectrum::constant(m.ni ? m.ni->value : 1.5);
    if (!m.ni) note(m.line, "Ni", "missing: a transparent material gets η = 1.5");
    if (m.dissolve && m.dissolve->value < 1.0)
      note(m.dissolve->line, "d",
           "approximated: partial opacity (d < 1) is not modelled, the material is a clear "
           "dielectric");
    const char* clear = "ignored: camsim's dielectric from an .mtl is clear and smooth";
    if (m.kd) note(m.kd->line, "Kd", clear);
    if (m.ks) note(m.ks->line, "Ks", clear);
    if (m.ns) note(m.ns->line, "Ns", clear);
    if (m.mapKd) note(m.mapKd->line, "map_Kd", clear);
    return d;
  }
  const char* opaqueNi =
      "ignored: only transparent materials (d < 1, illum 4, 6, 7) become dielectrics";
  if (m.ni) note(m.ni->line, "Ni", opaqueNi);
  if (ks > 0.0 && illum >= 2) {
    d.type = Type::kPlastic;
    d.specularWeight = static_cast<float>(std::min(ks, 1.0));
    const glm::dvec3 c = m.ks->value;
    if (ks > 1.0) note(m.ks->line, "Ks", "approximated: a mean above 1 is clamped to ks = 1");
    if (std::max({c.x, c.y, c.z}) - std::min({c.x, c.y, c.z}) > 1e-6)
      note(m.ks->line, "Ks",
           "approximated: a coloured Ks is averaged (camsim's plastic specular is colourless)");
    const double ns = m.ns ? m.ns->value : 0.0;
    d.roughness = TextureDescription::constant(std::sqrt(2.0 / (ns + 2.0)));
    d.distribution = MicrofacetDistribution::kBeckmann;
    if (!m.ns) note(m.line, "Ns", "missing: Ns = 0 assumed (roughness α = 1)");
  } else {
    d.type = Type::kDiffuse;
    if (ks > 0.0) note(m.ks->line, "Ks", "ignored: illum 0 and 1 have no highlight");
    if (m.ns) note(m.ns->line, "Ns", "ignored: the material has no highlight (diffuse)");
  }
  if (m.mapKd) {
    d.reflectance = textureOf(*m.mapKd, lib, imported, search);
    if (m.kd && m.kd->value != glm::dvec3(1.0))
      note(m.kd->line, "Kd", "ignored where map_Kd is given (a texture is not tinted)");
  } else if (m.kd) {
    const glm::dvec3 rgb = glm::clamp(m.kd->value, 0.0, 1.0);
    if (rgb != m.kd->value) note(m.kd->line, "Kd", "approximated: components above 1 clamped to 1");
    d.reflectance.value = rgbToReflectance(rgb, RgbColorSpace::linearRec709());
  } else {
    note(m.line, "Kd", "missing: the diffuse reflectance is camsim's default 0.5");
  }
  return d;
}

// The triangles `tris` of `mesh` with only the vertices they use. `remap` (one entry per
// position, all UINT32_MAX) is scratch space, left as it was found: the work is linear in
// the triangles, however many pieces a mesh has.
MeshData subMesh(const MeshData& mesh, const std::vector<std::uint32_t>& tris,
                 std::vector<std::uint32_t>& remap) {
  MeshData out;
  for (std::uint32_t t : tris) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[3 * std::size_t{t} + k];
      if (remap[v] == UINT32_MAX) {
        remap[v] = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(mesh.positions[v]);
        if (!mesh.normals.empty()) out.normals.push_back(mesh.normals[v]);
        if (!mesh.uvs.empty()) out.uvs.push_back(mesh.uvs[v]);
        if (!mesh.tangents.empty()) out.tangents.push_back(mesh.tangents[v]);
      }
      out.indices.push_back(remap[v]);
    }
  }
  for (std::uint32_t t : tris)
    for (int k = 0; k < 3; ++k) remap[mesh.indices[3 * std::size_t{t} + k]] = UINT32_MAX;
  return out;
}

}  // namespace

std::vector<ShapeDescription> splitByFileMaterials(
    ShapeDescription shape, const std::filesystem::path& objPath, const YamlValue& file,
    ImportedMaterials& imported, const std::map<std::string, int>& sceneMaterials,
    const TableSearch& search, SceneDescription& scene) {
  const std::vector<Library> libs = readLibraries(shape.mesh, objPath, search);
  const auto materials = byName(libs);
  const std::string obj = objPath.string();
  Notes notes;
  for (const Library& lib : libs)
    for (const MtlIgnored& i : lib.mtl.ignored) notes.addIgnored(lib.path.string(), i);

  // Material index per group, and the triangles of each index in first-use order.
  std::vector<int> order;
  std::map<int, std::vector<std::uint32_t>> trianglesOf;
  std::map<int, std::string> nameOf;  // the file's name of each used index
  std::map<int, int> lineOf;          // its first usemtl line
  const std::vector<MeshMaterialGroup>& groups = shape.mesh.materialGroups;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const MeshMaterialGroup& g = groups[k];
    int index = -1;
    if (g.name.empty()) {  // line 0: the triangles before the first usemtl (the next group's)
      const int line = g.line > 0 || k + 1 == groups.size() ? g.line : groups[k + 1].line;
      if (!shape.emission)
        throw InputError({obj, line, 0}, "",
                         std::to_string(g.triangleCount) + " triangles have no material (" +
                             (g.line > 0 ? "a bare usemtl" : "they come before this usemtl") +
                             "): give the shape a 'material:' or name one");
    } else {
      const auto found = materials.find(g.name);
      if (found == materials.end())
        throw InputError({obj, g.line, 0}, "",
                         "usemtl '" + g.name + "': " +
                             (libs.empty() ? std::string("the file has no mtllib")
                                           : "no such material in its mtllib files"));
      const std::string sceneName = file.string() + ":" + g.name;
      if (sceneMaterials.count(sceneName) > 0)
        file.fail("the imported material '" + sceneName +
                  "' has the name of a material of the scene: rename that one");
      auto [it, added] = imported.index.try_emplace(sceneName, int(scene.materials.size()));
      if (added)
        scene.materials.push_back(mapMaterial(*found->second.second, *found->second.first,
                                              sceneName, imported, search, notes));
      index = it->second;
    }
    if (trianglesOf.count(index) == 0) {
      order.push_back(index);
      nameOf[index] = g.name;
      lineOf[index] = g.line;
    }
    std::vector<std::uint32_t>& tris = trianglesOf[index];
    for (std::uint32_t t = 0; t < g.triangleCount; ++t) tris.push_back(g.firstTriangle + t);
  }

  std::vector<ShapeDescription> pieces;
  std::vector<std::uint32_t> remap(shape.mesh.positions.size(), UINT32_MAX);
  for (int index : order) {
    ShapeDescription piece;
    piece.kind = shape.kind;
    piece.label = order.size() == 1 ? shape.label
                                    : shape.label + "/" + (index < 0 ? "(none)" : nameOf[index]);
    piece.className = shape.className;
    piece.classNumber = shape.classNumber;
    piece.material = index;
    piece.emission = shape.emission;
    piece.motion = shape.motion;
    piece.objectFromModel = shape.objectFromModel;
    piece.mesh = subMesh(shape.mesh, trianglesOf[index], remap);
    if (!(meshArea2(piece.mesh) > 0.0)) {
      notes.add(obj, lineOf[index], "usemtl " + nameOf[index],
                "dropped: its triangles have zero area (shape " + shape.label + ")");
      continue;
    }
    pieces.push_back(std::move(piece));
  }
  notes.appendTo(scene.notes);
  return pieces;
}

}  // namespace camsim
