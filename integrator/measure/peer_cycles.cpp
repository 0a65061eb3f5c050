#include "integrator/measure/peer_cycles.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "integrator/camera/physical_camera.h"
#include "sensor/base/input_error.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"

namespace camsim {
namespace {

// Shortest text that reads back as the same float ("%.9g"): the script is deterministic.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string tuple3(const glm::dvec3& v) {
  return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")";
}

[[noreturn]] void untranslatable(const SceneDescription& scene, const std::string& what) {
  throw InputError({scene.sourceFile, 0, 0}, "",
                   what +
                       ": not translatable to Cycles by camsim bench --peer (it covers "
                       "diffuse and mirror materials of constant reflectance, emitting "
                       "shapes, pinhole and thin-lens cameras and static scenes)");
}

// A triangle soup in render space (m): positions and triangle indices.
struct SoupMesh {
  std::vector<glm::dvec3> positions;
  std::vector<std::uint32_t> indices;
  bool smooth = false;
};

// A UV sphere: rings of kSphereSegments vertices between the poles; every triangle wound so
// that its geometric normal points outwards (Cycles' back face is then the inside).
SoupMesh tessellateSphere(const glm::dvec3& centre, double radius) {
  SoupMesh m;
  m.smooth = true;
  const double pi = std::numbers::pi;
  m.positions.push_back(centre + glm::dvec3(0.0, radius, 0.0));
  for (int r = 1; r < kSphereRings; ++r) {
    const double theta = pi * r / kSphereRings;
    for (int s = 0; s < kSphereSegments; ++s) {
      const double phi = 2.0 * pi * s / kSphereSegments;
      m.positions.push_back(centre + radius * glm::dvec3(std::sin(theta) * std::cos(phi),
                                                         std::cos(theta),
                                                         std::sin(theta) * std::sin(phi)));
    }
  }
  m.positions.push_back(centre - glm::dvec3(0.0, radius, 0.0));
  const auto ring = [](int r, int s) {
    return static_cast<std::uint32_t>(1 + (r - 1) * kSphereSegments + s % kSphereSegments);
  };
  const auto last = static_cast<std::uint32_t>(m.positions.size() - 1);
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const glm::dvec3 n =
        glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
    const glm::dvec3 mid = (m.positions[a] + m.positions[b] + m.positions[c]) / 3.0;
    if (glm::dot(n, mid - centre) < 0.0) std::swap(b, c);
    m.indices.insert(m.indices.end(), {a, b, c});
  };
  for (int s = 0; s < kSphereSegments; ++s) {
    add(0, ring(1, s), ring(1, s + 1));
    add(last, ring(kSphereRings - 1, s), ring(kSphereRings - 1, s + 1));
    for (int r = 1; r + 1 < kSphereRings; ++r) {
      add(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      add(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  }
  return m;
}

// The shape in render space at the shutter's opening (the scene must be static).
SoupMesh shapeMesh(const SceneDescription& scene, const ShapeDescription& shape) {
  const double t0 = scene.camera.shutter.open();
  if (!shape.motion.empty() && !shape.motion.isStaticDuring(t0, scene.camera.shutter.close()))
    untranslatable(scene, "shape '" + shape.label + "' moves during the shutter");
  glm::dmat4 m = shape.motion.empty() ? glm::dmat4(1.0) : shape.motion.at(t0);
  if (shape.sharedMesh) m = m * shape.placement;
  const auto place = [&](const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); };
  if (shape.kind == ShapeDescription::Kind::kSphere) {
    SoupMesh s = tessellateSphere(glm::dvec3(shape.centre), static_cast<double>(shape.radius));
    for (glm::dvec3& p : s.positions) p = place(p);
    return s;
  }
  const MeshData& data = shape.sharedMesh ? *shape.sharedMesh : shape.mesh;
  SoupMesh s;
  for (const glm::vec3& p : data.positions) s.positions.push_back(place(glm::dvec3(p)));
  s.indices = data.indices;
  s.smooth = !data.normals.empty();
  return s;
}

glm::dvec3 constantRgb(const SceneDescription& scene, const MaterialDescription& m) {
  if (m.reflectance.kind != TextureDescription::Kind::kConstant)
    untranslatable(scene, "material '" + m.name + "' has a textured reflectance");
  return cyclesReflectanceRgb(m.reflectance.value);
}

void writeMaterials(std::ostream& py, const SceneDescription& scene) {
  py << "def material(name, kind, rgb):\n"
        "    m = bpy.data.materials.new(name)\n"
        "    m.use_nodes = True\n"
        "    nt = m.node_tree\n"
        "    nt.nodes.clear()\n"
        "    out = nt.nodes.new('ShaderNodeOutputMaterial')\n"
        "    if kind == 'mirror':\n"
        "        b = nt.nodes.new('ShaderNodeBsdfGlossy')\n"
        "        b.distribution = 'SHARP'\n"
        "    else:\n"
        "        b = nt.nodes.new('ShaderNodeBsdfDiffuse')\n"
        "        b.inputs['Roughness'].default_value = 0.0\n"
        "    b.inputs['Color'].default_value = (*rgb, 1.0)\n"
        "    nt.links.new(b.outputs[0], out.inputs['Surface'])\n"
        "    return m\n\n"
        "def emitter(name, base, rgb):\n"
        "    # One-sided: strength 1 - backfacing; plus the base material's BSDF, if any.\n"
        "    m = bpy.data.materials.new(name)\n"
        "    m.use_nodes = True\n"
        "    nt = m.node_tree\n"
        "    nt.nodes.clear()\n"
        "    out = nt.nodes.new('ShaderNodeOutputMaterial')\n"
        "    e = nt.nodes.new('ShaderNodeEmission')\n"
        "    e.inputs['Color'].default_value = (*rgb, 1.0)\n"
        "    geo = nt.nodes.new('ShaderNodeNewGeometry')\n"
        "    front = nt.nodes.new('ShaderNodeMath')\n"
        "    front.operation = 'SUBTRACT'\n"
        "    front.inputs[0].default_value = 1.0\n"
        "    nt.links.new(geo.outputs['Backfacing'], front.inputs[1])\n"
        "    nt.links.new(front.outputs[0], e.inputs['Strength'])\n"
        "    shader = e.outputs[0]\n"
        "    if base is not None:\n"
        "        add = nt.nodes.new('ShaderNodeAddShader')\n"
        "        src = [n for n in base.node_tree.nodes if n.type != 'OUTPUT_MATERIAL'][0]\n"
        "        b = nt.nodes.new(src.bl_idname)\n"
        "        if src.bl_idname == 'ShaderNodeBsdfGlossy':\n"
        "            b.distribution = 'SHARP'\n"
        "        b.inputs['Color'].default_value = src.inputs['Color'].default_value\n"
        "        nt.links.new(shader, add.inputs[0])\n"
        "        nt.links.new(b.outputs[0], add.inputs[1])\n"
        "        shader = add.outputs[0]\n"
        "    nt.links.new(shader, out.inputs['Surface'])\n"
        "    return m\n\n"
        "materials = []\n";
  for (const MaterialDescription& m : scene.materials) {
    const char* kind = nullptr;
    if (m.type == MaterialDescription::Type::kDiffuse) kind = "diffuse";
    if (m.type == MaterialDescription::Type::kMirror) kind = "mirror";
    if (!kind)
      untranslatable(scene, "material '" + m.name + "' of type " + std::string(enumName(m.type)));
    py << "materials.append(material(" << pythonString(m.name) << ", '" << kind << "', "
       << tuple3(constantRgb(scene, m)) << "))\n";
  }
  py << "black = material('black', 'diffuse', (0.0, 0.0, 0.0))\n\n";
}

void writeShapes(std::ostream& py, const SceneDescription& scene) {
  py << "def shape(name, verts, tris, smooth, mat):\n"
        "    me = bpy.data.meshes.new(name)\n"
        "    me.from_pydata(verts, [], [tris[i:i + 3] for i in range(0, len(tris), 3)])\n"
        "    for p in me.polygons:\n"
        "        p.use_smooth = smooth\n"
        "    me.materials.append(mat)\n"
        "    ob = bpy.data.objects.new(name, me)\n"
        "    scene.collection.objects.link(ob)\n\n";
  for (const ShapeDescription& shape : scene.shapes) {
    const SoupMesh mesh = shapeMesh(scene, shape);
    const std::string base =
        shape.material >= 0 ? "materials[" + std::to_string(shape.material) + "]" : "None";
    std::string mat = shape.material >= 0 ? base : "black";
    if (shape.emission) {
      if (shape.emission->twoSided)
        untranslatable(scene, "shape '" + shape.label + "' emits on both sides");
      py << "m = emitter(" << pythonString(shape.label + ".emission") << ", " << base << ", "
         << tuple3(cyclesRadianceRgb(shape.emission->radiance)) << ")\n";
      mat = "m";
    }
    py << "shape(" << pythonString(shape.label) << ", [";
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      py << (i ? ", " : "") << tuple3(mesh.positions[i]);
    py << "], [";
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) py << (i ? "," : "") << mesh.indices[i];
    py << "], " << (mesh.smooth ? "True" : "False") << ", " << mat << ")\n";
  }
  py << "\n";
}

void writeCamera(std::ostream& py, const SceneDescription& scene) {
  const PhysicalCameraParams& c = scene.camera;
  if (!c.motion.empty() && !c.motion.isStaticDuring(c.shutter.open(), c.shutter.close()))
    untranslatable(scene, "the camera moves during the shutter");
  const PhysicalCamera camera(c);
  if (!camera.idealPinhole())
    untranslatable(scene, "a camera projection other than the undistorted ideal lens");
  const glm::dmat4 w = camera.worldFromCameraAt(c.shutter.open());
  // Blender's camera looks down its −z with +y up and +x to the image's right: columns
  // right, up, −forward, position, a proper rotation (right = forward × up: the scenes'
  // "the camera looks along +z, so image right is world −x").
  const glm::dvec3 up(w[1]), forward(w[2]), pos(w[3]);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
  const double zi = camera.imageDistance();
  py << "cam = bpy.data.cameras.new('camera')\n"
     << "cam.sensor_fit = 'HORIZONTAL'\n"
     << "cam.sensor_width = " << num(c.sensorSize.x * 1e3) << "\n"
     << "cam.sensor_height = " << num(c.sensorSize.y * 1e3) << "\n"
     << "cam.lens = " << num(zi * 1e3) << "  # mm: camsim's image distance\n"
     << "cam.clip_start = 1e-4\n"
     << "cam.clip_end = 1e5\n";
  if (c.aperture && c.focusDistance > 0.0) {
    py << "cam.dof.use_dof = True\n"
       << "cam.dof.focus_distance = " << num(c.focusDistance) << "\n"
       << "cam.dof.aperture_fstop = " << num(zi / c.apertureDiameter()) << "\n"
       << "cam.dof.aperture_blades = " << (c.aperture->blades >= 3 ? c.aperture->blades : 0) << "\n"
       << "cam.dof.aperture_rotation = " << num(c.aperture->rotation) << "\n";
  } else {
    py << "cam.dof.use_dof = False\n";
  }
  py << "cam_ob = bpy.data.objects.new('camera', cam)\n"
     << "cam_ob.matrix_world = Matrix((" << tuple3({right.x, up.x, -forward.x}) << "[:] + ("
     << num(pos.x) << ",), " << tuple3({right.y, up.y, -forward.y}) << "[:] + (" << num(pos.y)
     << ",), " << tuple3({right.z, up.z, -forward.z}) << "[:] + (" << num(pos.z)
     << ",), (0.0, 0.0, 0.0, 1.0)))\n"
     << "scene.collection.objects.link(cam_ob)\n"
     << "scene.camera = cam_ob\n\n";
}

void writeRenderSettings(std::ostream& py, const SceneDescription& scene, const CyclesSettings& s) {
  const int b = s.bounces;
  py << "r = scene.render\n"
     << "r.engine = 'CYCLES'\n"
     << "r.resolution_x = " << scene.camera.resolution.x << "\n"
     << "r.resolution_y = " << scene.camera.resolution.y << "\n"
     << "r.resolution_percentage = 100\n"
     << "r.pixel_aspect_x = r.pixel_aspect_y = 1.0\n"
     << "r.threads_mode = 'FIXED'\n"
     << "r.threads = " << s.threads << "\n"
     << "r.use_persistent_data = False  # True keeps the first render's samples and seed\n"
     << "r.film_transparent = False\n"
     << "r.use_motion_blur = False\n"
     << "r.image_settings.file_format = 'OPEN_EXR'\n"
     << "r.image_settings.color_mode = 'RGB'\n"
     << "r.image_settings.color_depth = '32'\n"
     << "r.image_settings.exr_codec = 'ZIP'\n"
     << "scene.view_settings.view_transform = 'Standard'\n"
     << "scene.view_settings.look = 'None'\n"
     << "scene.view_settings.exposure = 0.0\n"
     << "scene.view_settings.gamma = 1.0\n"
     << "c = scene.cycles\n"
     << "c.device = 'CPU'\n"
     << "c.use_adaptive_sampling = False\n"
     << "c.use_denoising = False\n"
     << "c.time_limit = 0.0\n"
     << "c.max_bounces = c.diffuse_bounces = c.glossy_bounces = " << b << "\n"
     << "c.transmission_bounces = c.transparent_max_bounces = " << b << "\n"
     << "c.volume_bounces = 0\n"
     << "c.sample_clamp_direct = c.sample_clamp_indirect = 0.0\n"
     << "c.blur_glossy = 0.0\n"
     << "c.caustics_reflective = c.caustics_refractive = True\n"
     << "c.film_exposure = 1.0\n"
     << "world = bpy.data.worlds.new('black')\n"
     << "world.use_nodes = True\n"
     << "world.node_tree.nodes['Background'].inputs['Strength'].default_value = 0.0\n"
     << "scene.world = world\n\n";
}

void writeRenders(std::ostream& py, const CyclesSettings& s) {
  py << "def render(index, spp, seed, path):\n"
        "    c.samples = spp\n"
        "    c.seed = seed\n"
        "    t0 = time.perf_counter()\n"
        "    bpy.ops.render.render()\n"
        "    seconds = time.perf_counter() - t0\n"
        "    bpy.data.images['Render Result'].save_render(path)\n"
        "    print('camsim-peer: %d %.6f' % (index, seconds), flush=True)\n\n";
  if (!s.warmupFile.empty()) py << "render(-1, 1, 0, " << pythonString(s.warmupFile) << ")\n";
  for (std::size_t i = 0; i < s.renders.size(); ++i)
    py << "render(" << i << ", " << s.renders[i].spp << ", " << s.renders[i].seed << ", "
       << pythonString(s.renders[i].file) << ")\n";
}

}  // namespace

glm::dvec3 cyclesReflectanceRgb(const Spectrum& reflectance) {
  return reflectanceToRgb(reflectance, RgbColorSpace::linearRec709());
}

glm::dvec3 cyclesRadianceRgb(const Spectrum& radiance) {
  return RgbColorSpace::linearRec709().fromXyz(spectrumToXyz(radiance));
}

std::string pythonString(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '\\' || ch == '"') {
      out += '\\';
      out += ch;
    } else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(u));
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

CyclesTranslation translateToCycles(const SceneDescription& scene, const CyclesSettings& settings) {
  if (!scene.lights.empty())
    untranslatable(scene, "light '" + scene.lights.front().label + "' (not a shape)");
  if (scene.sensor) untranslatable(scene, "a sensor model");
  std::ostringstream py;
  py << "# " << scene.name << " (" << scene.sourceFile << "), translated by camsim bench --peer\n"
     << "import time\n"
     << "import bpy\n"
     << "from mathutils import Matrix\n\n"
     << "bpy.ops.wm.read_factory_settings(use_empty=True)\n"
     << "scene = bpy.context.scene\n\n";
  writeMaterials(py, scene);
  writeShapes(py, scene);
  writeCamera(py, scene);
  writeRenderSettings(py, scene, settings);
  writeRenders(py, settings);

  CyclesTranslation t;
  t.script = py.str();
  t.approximations = {
      "spectra as linear Rec.709 RGB (reflectances under D65, emission XYZ → RGB): an RGB "
      "renderer multiplies per channel what camsim integrates per wavelength",
      "Cycles' pixel filter (Blackman-Harris, 1.5 px) against camsim's",
      "bounces: Cycles max_bounces = camsim max_depth − 1"};
  for (const ShapeDescription& s : scene.shapes)
    if (s.kind == ShapeDescription::Kind::kSphere) {
      t.approximations.push_back("spheres as smooth-shaded UV spheres of " +
                                 std::to_string(kSphereSegments) + " × " +
                                 std::to_string(kSphereRings) + " quads");
      break;
    }
  if (scene.camera.aperture && scene.camera.focusDistance > 0.0)
    t.approximations.push_back(
        "thin lens: Cycles' polygonal aperture and its rotation convention as given");
  return t;
}

}  // namespace camsim
