// A mesh shape's `instances:` list (docs/scene-format.md, "Instances"): the mesh (its file or
// inline vertices, with the shape's own `scale`/`translate`) is read once into a shared
// MeshData, its object space, and each item becomes a ShapeDescription that places it.
//
// | key         | type                          | unit | default | meaning |
// |-------------|-------------------------------|------|---------|---------|
// | `translate` | [x, y, z]                     | m    | 0       | world position of the object's origin |
// | `rotate`    | {axis: [x, y, z], angle_deg}  | °    | none    | rotation about the object's origin |
// | `scale`     | number or [sx, sy, sz], ≠ 0   | —    | 1       | about the object's origin; negative mirrors |
// | `matrix`    | 16 numbers, row by row        | m    | —       | instead of the three above: any invertible affine map, last row [0, 0, 0, 1] |
// | `motion`    | keyframes (as a shape's)      | —    | static  | applied after the placement |
// | `name`      | string                        | —    | NAME[j] | the instance's name (ID mattes); NAME = the shape's name or shapes[i] |
// | `class`     | as a shape's                  | —    | the shape's | |
// | `material`  | a material name               | —    | the shape's | |
//
//   placement P = T(translate) · R(rotate) · S(scale)  (or `matrix`),  pose(t) = motion(t) · P
// Translations are world positions: the render origin is subtracted in double (from the
// placement, or from the motion's keyframes when the instance moves).
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "integrator/scene/scene_loader_parts.h"

namespace camsim {
namespace {

constexpr double kMaxScale = 1e12;

// A non-zero scale factor within ±kMaxScale.
double scaleFactor(const YamlValue& where, double s) {
  if (s == 0.0 || std::abs(s) > kMaxScale)
    where.fail("a scale factor must be non-zero and within ±1e12");
  return s;
}

// `matrix`: 16 numbers row by row, an affine map with an invertible linear part.
glm::dmat4 parseInvertibleAffine(const YamlValue& m) {
  const glm::dmat4 out = parseAffineMatrix(m);
  // Singular relative to the size of the columns (a float placement would be degenerate).
  const glm::dmat3 a(out);
  const double size = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  if (!(std::abs(glm::determinant(a)) > 1e-12 * size))
    m.fail("the matrix is singular: its 3×3 part must be invertible");
  return out;
}

}  // namespace

glm::dmat4 parsePlacement(YamlMap& map) {
  const auto matrix = map.find("matrix");
  const auto translate = map.find("translate");
  const auto rotate = map.find("rotate");
  const auto scale = map.find("scale");
  if (matrix && (translate || rotate || scale))
    matrix->fail("give either 'matrix' or translate/rotate/scale, not both");
  if (matrix) return parseInvertibleAffine(*matrix);
  glm::dvec3 factors(1.0);
  if (scale && scale->isScalar()) {
    factors = glm::dvec3(scaleFactor(*scale, scale->number()));
  } else if (scale) {
    factors = scale->vec3();
    for (int axis = 0; axis < 3; ++axis) scaleFactor(*scale, factors[axis]);
  }
  const glm::dquat q = rotate ? parseRotation(*rotate) : glm::dquat(1.0, 0.0, 0.0, 0.0);
  glm::dmat4 placement = glm::mat4_cast(q) * glm::scale(glm::dmat4(1.0), factors);
  if (translate) placement[3] = glm::dvec4(translate->vec3(), 1.0);
  toPoint(translate ? *translate : map.self(), glm::dvec3(placement[3]));
  return placement;
}

namespace {

ShapeDescription parseInstance(YamlMap map, size_t j, const ShapeDescription& shape,
                               const std::map<std::string, int>& materials,
                               const glm::dvec3& origin) {
  ShapeDescription s = shape;  // kind, mesh, material, emission, class
  s.label = shape.label + "[" + std::to_string(j) + "]";
  s.key = shape.key + ".instances[" + std::to_string(j) + "]";
  s.where = map.self().where();
  if (auto n = map.find("name")) s.label = n->string();
  if (auto c = map.find("class")) parseShapeClass(*c, s);
  if (auto m = map.find("material")) {
    const auto it = materials.find(m->string());
    if (it == materials.end()) m->fail("no material named '" + m->string() + "'");
    s.material = it->second;
  }
  glm::dmat4 placement = parsePlacement(map);
  const auto matrix = map.find("matrix");
  const auto translate = map.find("translate");
  if (auto m = map.find("motion")) {
    s.motion = parseMotion(*m, false, origin);
  } else {
    placement[3] -= glm::dvec4(origin, 0.0);  // render space, in double
    toPoint(matrix ? *matrix : translate ? *translate : map.self(), glm::dvec3(placement[3]));
  }
  s.placement = placement;
  map.finish({"translate", "rotate", "scale", "matrix", "motion", "name", "class", "material"});
  return s;
}

}  // namespace

void parseInstances(const YamlValue& list, ShapeDescription shape,
                    const std::map<std::string, int>& materials, const glm::dvec3& origin,
                    std::vector<ShapeDescription>& out) {
  const std::vector<YamlValue> items = list.items();
  if (items.empty()) list.fail("instances needs at least one item");
  shape.sharedMesh = std::make_shared<const MeshData>(std::move(shape.mesh));
  shape.mesh = MeshData{};
  for (size_t j = 0; j < items.size(); ++j)
    out.push_back(parseInstance(YamlMap(items[j]), j, shape, materials, origin));
}

}  // namespace camsim
