// The scene loader's `include:` part: glTF 2.0 assets placed in a camsim scene, with their
// node hierarchy, materials, lights, cameras and animation (docs/scene-format.md, "glTF
// assets"). Each (node, primitive) becomes a mesh shape:
//   static, mesh used by one node   positions baked into render space (in double)
//   static, mesh used by ≥ 2 nodes  an instance of the primitive's one stored mesh
//                                   (ShapeDescription::sharedMesh, placement)
//   under an animated node          the mesh in the deepest animated node's space,
//                                   keyframed with the animated nodes above it composed
//                                   (gltf_motion.cpp)
// Render space is world − renderOrigin; the include's placement maps asset → world.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "integrator/scene/gltf_convert.h"
#include "integrator/scene/scene_loader_parts.h"
#include "sensor/base/file_status.h"

namespace camsim {
namespace {

struct Walk {
  const GltfInclude& inc;
  SceneDescription& scene;
  std::vector<int> materials;  // glTF material → camsim index
  int defaultMaterial = -1;    // glTF's default material, added when a primitive needs it
  std::vector<bool> animated;
  std::vector<int> meshUses;  // static nodes using each mesh
  // Each glTF material's emission, worked out (and its notes written) once.
  std::map<int, std::optional<EmissionDescription>> emissions;
  // (mesh, primitive, mirrored): a mirroring node's copy has its winding reversed
  std::map<std::tuple<int, int, bool>, std::shared_ptr<const MeshData>> shared;

  // Node n under renderFromParent (rest poses). Below animated nodes, `chain` lists them
  // (outermost first), `belowParent` is the static transform from the deepest one's space
  // (its residual scale included) to n's parent, and motion that node's keyframes.
  void node(int n, const glm::dmat4& renderFromParent, const std::vector<GltfChainLink>& chain,
            const glm::dmat4& belowParent, const RigidMotion* motion) {
    const GltfNode& g = inc.doc.nodes[static_cast<size_t>(n)];
    const std::string file = inc.doc.file.string();
    const glm::dmat4 renderFromNode = renderFromParent * g.local();
    glm::dmat4 below = chain.empty() ? glm::dmat4(1.0) : belowParent * g.local();
    RigidMotion own;
    std::vector<GltfChainLink> extended;
    const std::vector<GltfChainLink>* links = &chain;
    if (animated[static_cast<size_t>(n)]) {
      extended = chain;
      extended.push_back({chain.empty() ? renderFromParent : belowParent, n});
      own = gltfChainMotion(inc, extended, below);  // below: the residual scale
      motion = &own;
      links = &extended;
    }
    const bool moving = !links->empty();
    if (g.mesh >= 0) {
      if (g.skinned)
        throw InputError({file, 0, 0}, g.path + ".skin", "skinned meshes are not supported");
      const GltfMesh& mesh = inc.doc.meshes[static_cast<size_t>(g.mesh)];
      for (size_t k = 0; k < mesh.primitives.size(); ++k)
        addPrimitive(g, mesh, k, moving ? below : renderFromNode, motion);
    }
    if (g.light >= 0 && inc.lights) {
      if (moving)
        scene.notes.push_back(inc.where + ": " + g.path +
                              ": an animated light is placed at its rest pose");
      scene.lights.push_back(
          gltfLight(inc, inc.doc.lights[static_cast<size_t>(g.light)], renderFromNode, scene));
    }
    for (int c : g.children) node(c, renderFromNode, *links, below, motion);
  }

  glm::dmat4 renderFromAsset() const {
    return glm::translate(glm::dmat4(1.0), -scene.renderOrigin) * inc.worldFromAsset;
  }

  void addPrimitive(const GltfNode& g, const GltfMesh& mesh, size_t k, const glm::dmat4& m,
                    const RigidMotion* motion) {
    const GltfPrimitive& p = mesh.primitives[k];
    if (!(std::abs(glm::determinant(glm::dmat3(m))) > 0.0)) {  // a zero scale hides a node
      scene.notes.push_back(inc.where + ": " + g.path +
                            ": its transform is singular (a zero "
                            "scale): not rendered");
      return;
    }
    ShapeDescription s;
    s.kind = ShapeDescription::Kind::kMesh;
    s.label = inc.label + ":" + (g.name.empty() ? g.path : g.name) +
              (mesh.primitives.size() > 1 ? "/" + std::to_string(k) : "");
    s.className = inc.className;
    s.classNumber = inc.classNumber;
    s.where = inc.location;
    s.key = inc.key;
    if (p.material < 0 && defaultMaterial < 0) defaultMaterial = addGltfDefaultMaterial(inc, scene);
    s.material = p.material >= 0 ? materials[static_cast<size_t>(p.material)] : defaultMaterial;
    const auto known = emissions.find(p.material);
    s.emission =
        known != emissions.end()
            ? known->second
            : emissions.emplace(p.material, gltfEmission(inc, p.material, scene)).first->second;
    if (motion) s.motion = *motion;
    if (!motion && meshUses[static_cast<size_t>(g.mesh)] > 1) {
      // glTF keeps the front under a mirroring transform (its winding turns clockwise); a
      // placement keeps the winding, so a mirrored node places a copy wound the other way
      // (found by probing: a one-sided emitter on a mirrored node went dark when its mesh
      // was shared, not when it was baked by transformed()).
      const bool mirrored = glm::determinant(glm::dmat3(m)) < 0.0;
      auto& sharedMesh = shared[{g.mesh, static_cast<int>(k), mirrored}];
      if (!sharedMesh) {
        MeshData copy = p.mesh;
        if (mirrored) reverseWinding(copy);
        sharedMesh = std::make_shared<const MeshData>(std::move(copy));
      }
      s.sharedMesh = sharedMesh;
      s.placement = m;
    } else {
      s.mesh = transformed(p.mesh, m, p.path);
      s.objectFromModel = m;  // the model: the primitive's own coordinates (object_poses.h)
    }
    if (p.colorAlpha)
      scene.notes.push_back(inc.where + ": " + p.path +
                            ".attributes.COLOR_0: its alpha is ignored (the colours multiply "
                            "the base colour; only the material's alpha cuts out)");
    scene.shapes.push_back(std::move(s));
  }

  // The mesh under an affine m (in double): normals by the inverse transpose, tangents by m,
  // and a mirroring m (det < 0) reverses the winding so the front stays the front.
  MeshData transformed(const MeshData& in, const glm::dmat4& m, const std::string& path) const {
    MeshData out = in;
    const glm::dmat3 linear(m), normalMatrix = glm::transpose(glm::inverse(linear));
    const double det = glm::determinant(linear);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
      throw InputError({inc.doc.file.string(), 0, 0}, path, "its node's transform is singular");
    for (size_t i = 0; i < in.positions.size(); ++i) {
      const glm::dvec3 q = glm::dvec3(m * glm::dvec4(glm::dvec3(in.positions[i]), 1.0));
      out.positions[i] = glm::vec3(q);
      if (!std::isfinite(out.positions[i].x) || !std::isfinite(out.positions[i].y) ||
          !std::isfinite(out.positions[i].z))
        throw InputError({inc.doc.file.string(), 0, 0}, path,
                         "a placed position leaves the float range");
    }
    for (glm::vec3& n : out.normals) n = glm::vec3(glm::normalize(normalMatrix * glm::dvec3(n)));
    for (glm::vec4& t : out.tangents) {
      const glm::vec3 d = glm::vec3(glm::normalize(linear * glm::dvec3(t)));
      t = glm::vec4(d, det < 0.0 ? -t.w : t.w);
    }
    if (det < 0.0) reverseWinding(out);
    return out;
  }

  static void reverseWinding(MeshData& mesh) {
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
      std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
  }
};

// `animation`: all (the default), none, an index or a name, or a list of indices and names.
std::vector<int> parseAnimationChoice(const std::optional<YamlValue>& v, GltfDocument& doc) {
  std::vector<int> all;
  for (size_t k = 0; k < doc.animations.size(); ++k) all.push_back(static_cast<int>(k));
  if (!v) {
    if (all.size() > 1)
      doc.notes.push_back("animations: all " + std::to_string(all.size()) +
                          " animations play together from t = 0 (choose with `animation:`)");
    return all;
  }
  if (!v->isSequence()) {
    const std::string a = v->string();
    if (a == "all") return all;
    if (a == "none") return {};
  }
  std::vector<int> chosen;
  for (const YamlValue& item : v->isSequence() ? v->items() : std::vector<YamlValue>{*v}) {
    const std::string a = item.string();
    int found = -1;
    for (size_t k = 0; k < doc.animations.size() && found < 0; ++k)
      if (doc.animations[k].name == a || std::to_string(k) == a) found = static_cast<int>(k);
    if (found < 0)
      item.fail("no animation '" + a +
                "' in the file (give its index or name, a list of them, all or none; the "
                "file has " +
                std::to_string(doc.animations.size()) + ")");
    if (std::find(chosen.begin(), chosen.end(), found) == chosen.end()) chosen.push_back(found);
  }
  return chosen;
}

}  // namespace

std::vector<GltfInclude> parseGltfIncludes(const YamlValue& list,
                                           const std::filesystem::path& baseDir,
                                           TableSearch& search) {
  std::vector<GltfInclude> out;
  const std::vector<YamlValue> items = list.items();
  for (size_t i = 0; i < items.size(); ++i) {
    YamlMap map(items[i]);
    GltfInclude inc;
    const YamlValue fileValue = map.require("gltf");
    std::filesystem::path file(fileValue.string());
    if (file.is_relative()) file = baseDir / file;
    if (!isRegularFile(file)) fileValue.fail("glTF file '" + file.string() + "' not found");
    search.noteRead(file);
    inc.doc = readGltf(file);
    for (const auto& f : inc.doc.filesRead) search.noteRead(f);
    inc.where = "include[" + std::to_string(i) + "] (" + file.filename().string() + ")";
    inc.key = "include[" + std::to_string(i) + "]";
    inc.location = map.self().where();
    inc.label = file.stem().string();
    if (auto n = map.find("name")) inc.label = n->string();
    inc.worldFromAsset = parsePlacement(map);  // matrix, or T · R · S
    // A file without scenes places nothing (glTF lets a library of meshes omit them; found
    // by probing: such an include added nothing, without a word).
    if (inc.doc.scenes.empty())
      fileValue.fail("the file has no scenes (glTF's \"scenes\"): it places no node to import");
    inc.scene = inc.doc.defaultScene;
    if (auto v = map.find("scene")) {
      inc.scene =
          static_cast<int>(v->integer(0, static_cast<std::int64_t>(inc.doc.scenes.size()) - 1));
    }
    if (inc.scene >= static_cast<int>(inc.doc.scenes.size()))
      fileValue.fail("the file's default scene " + std::to_string(inc.scene) + " does not exist");
    if (inc.doc.scenes[static_cast<size_t>(inc.scene)].empty())
      inc.doc.notes.push_back("scenes[" + std::to_string(inc.scene) +
                              "] has no nodes: nothing is imported");
    inc.animations = parseAnimationChoice(map.find("animation"), inc.doc);
    if (auto v = map.find("lights")) inc.lights = v->boolean();
    if (auto v = map.find("emissive_luminance")) inc.emissiveLuminance = v->number(0.0, 1e12);
    if (auto c = map.find("class")) {  // the rule of a shape's class:
      ShapeDescription classOf;
      parseShapeClass(*c, classOf);
      inc.className = classOf.className;
      inc.classNumber = classOf.classNumber;
    }
    map.finish({"gltf", "name", "matrix", "translate", "rotate", "scale", "scene", "animation",
                "lights", "emissive_luminance", "class"});
    out.push_back(std::move(inc));
  }
  return out;
}

double applyGltfCamera(const YamlValue& spec, const std::vector<GltfInclude>& includes,
                       PhysicalCameraParams& camera, std::vector<std::string>& notes) {
  YamlMap map(spec);
  size_t which = 0;
  if (auto v = map.find("include")) {
    if (includes.empty()) v->fail("the scene has no include: entries");
    which = static_cast<size_t>(v->integer(0, static_cast<std::int64_t>(includes.size()) - 1));
  } else if (includes.empty()) {
    spec.fail("camera.gltf needs an include: entry with a glTF camera");
  }
  const GltfInclude& inc = includes[which];
  const GltfDocument& doc = inc.doc;
  int cam = doc.cameras.empty() ? -1 : 0;
  const auto name = map.find("camera");
  if (name) {
    const std::string c = name->string();
    cam = -1;
    for (size_t k = 0; k < doc.cameras.size(); ++k)
      if (doc.cameras[k].name == c || std::to_string(k) == c) cam = static_cast<int>(k);
  }
  map.finish({"include", "camera"});
  if (cam < 0) (name ? *name : spec).fail("no such camera in " + doc.file.string());
  const GltfCamera& gc = doc.cameras[static_cast<size_t>(cam)];
  if (!gc.perspective)
    (name ? *name : spec)
        .fail(gc.path +
              " is orthographic: camsim's cameras are perspective (thin lens or pinhole)");
  // The first node of the chosen scene's hierarchy that holds the camera.
  std::function<bool(int, const glm::dmat4&)> find = [&](int n, const glm::dmat4& parent) {
    const glm::dmat4 m = parent * doc.nodes[static_cast<size_t>(n)].local();
    if (doc.nodes[static_cast<size_t>(n)].camera == cam) {
      if (gltfAnimatedNodes(inc)[static_cast<size_t>(n)])
        notes.push_back(inc.where + ": " + doc.nodes[static_cast<size_t>(n)].path +
                        ": the camera's animation is not used; it stays at its rest pose");
      // glTF cameras look down −z with +y up; camsim's columns are right, up, forward. A
      // uniform or per-axis scale is dropped; a zero scale, a shear or a mirror is refused
      // (found by probing: a zero scale gave a NaN pose and a black image, exit 0; a
      // mirroring scale rendered the image mirrored).
      const std::string node = doc.nodes[static_cast<size_t>(n)].path;
      glm::dvec3 axes[3];
      for (int c = 0; c < 3; ++c) {
        const double length = glm::length(glm::dvec3(m[c]));
        if (!(length > 0.0 && std::isfinite(length)))
          spec.fail(node + ": the camera's transform is singular (a zero scale)");
        axes[c] = glm::dvec3(m[c]) / length;
      }
      // The include's placement is part of m: when it mirrors or scales unevenly, it is
      // named rather than the node (found in review).
      const glm::dmat3 placed(inc.worldFromAsset);
      const double sx = glm::length(placed[0]), sy = glm::length(placed[1]),
                   sz = glm::length(placed[2]);
      const bool uneven = std::abs(sx - sy) > 1e-6 * sx || std::abs(sx - sz) > 1e-6 * sx;
      const std::string culprit =
          glm::determinant(placed) < 0.0 || uneven ? inc.key + "'s placement (its scale)" : node;
      if (std::abs(glm::dot(axes[0], axes[1])) > 1e-4 ||
          std::abs(glm::dot(axes[1], axes[2])) > 1e-4 ||
          std::abs(glm::dot(axes[0], axes[2])) > 1e-4)
        spec.fail(culprit + ": the camera's transform shears (its axes are not perpendicular)");
      if (glm::dot(glm::cross(axes[0], axes[1]), axes[2]) < 0.0)
        spec.fail(culprit +
                  ": the camera's transform mirrors (a negative scale): the image "
                  "would be mirrored");
      camera.worldFromCamera = glm::dmat4(glm::dvec4(axes[0], 0.0), glm::dvec4(axes[1], 0.0),
                                          glm::dvec4(-axes[2], 0.0), m[3]);
      return true;
    }
    for (int c : doc.nodes[static_cast<size_t>(n)].children)
      if (find(c, m)) return true;
    return false;
  };
  bool placed = false;
  for (int r : doc.scenes[static_cast<size_t>(inc.scene)])
    placed = placed || find(r, inc.worldFromAsset);
  if (!placed) spec.fail(gc.path + " is not used by any node of the included scene");
  if (gc.aspectRatio > 0.0)
    notes.push_back(inc.where + ": " + gc.path + ": aspectRatio " + std::to_string(gc.aspectRatio) +
                    " is not used: the vertical field of view is kept on the camera's sensor (" +
                    "its own aspect ratio)");
  if (gc.znear > 0.0 || gc.zfar > 0.0)
    notes.push_back(inc.where + ": " + gc.path +
                    ": znear/zfar are ignored (a camera sees all depths)");
  return gc.yfov;
}

void addGltfIncludes(std::vector<GltfInclude>& includes, SceneDescription& scene) {
  for (GltfInclude& inc : includes) {
    for (const std::string& n : gltfAnimationNotes(inc)) inc.doc.notes.push_back(n);
    Walk w{inc, scene, addGltfMaterials(inc, scene), -1, gltfAnimatedNodes(inc), {}, {}, {}};
    w.meshUses.assign(inc.doc.meshes.size(), 0);
    // Count static uses of each mesh (nodes outside animated chains).
    std::function<void(int, bool)> count = [&](int n, bool moving) {
      const GltfNode& g = inc.doc.nodes[static_cast<size_t>(n)];
      moving = moving || w.animated[static_cast<size_t>(n)];
      if (g.mesh >= 0 && !moving) ++w.meshUses[static_cast<size_t>(g.mesh)];
      for (int c : g.children) count(c, moving);
    };
    const std::vector<int>& roots = inc.doc.scenes[static_cast<size_t>(inc.scene)];
    for (int r : roots) count(r, false);
    const size_t shapesBefore = scene.shapes.size();
    for (int r : roots) w.node(r, w.renderFromAsset(), {}, glm::dmat4(1.0), nullptr);
    bool emits = false;
    for (size_t i = shapesBefore; i < scene.shapes.size(); ++i)
      emits = emits || scene.shapes[i].emission;
    if (emits)
      scene.notes.push_back(inc.where + ": glTF emission is relative: emissive (1, 1, 1) is " +
                            std::to_string(inc.emissiveLuminance) + " cd/m² (emissive_luminance)");
    for (const std::string& n : inc.doc.notes) scene.notes.push_back(inc.where + ": " + n);
  }
}

}  // namespace camsim
