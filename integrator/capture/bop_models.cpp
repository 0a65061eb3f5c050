// The pose exports' models (bop_writer.h): a run's PoseModels table — BOP's one model per
// obj_id and every labelled shape's box — its PLY in mm with vertex normals, and
// models_info.json's diameter and box.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

#include <glm/geometric.hpp>

#include "integrator/capture/bop_writer.h"
#include "integrator/scene/scene_ids.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/io/output_set.h"

namespace camsim {
namespace {

constexpr double kSameModel = 1e-4;  // relative to the model's box diagonal

// Whether b is a's model: the same triangles, each vertex within kSameModel of a's size.
bool sameModel(const ObjectModel& a, const ObjectModel& b) {
  if (a.vertices.size() != b.vertices.size() || a.indices != b.indices) return false;
  const double tolerance =
      kSameModel * glm::length(a.boxMax - a.boxMin) + 4.0 * std::max(a.rounding, b.rounding) + 1e-9;
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    if (!(glm::length(a.vertices[i] - b.vertices[i]) <= tolerance)) return false;
  return true;
}

// ASCII PLY in mm: positions, angle-weighted vertex normals (each corner's face normal
// weighted by its angle there), triangles.
std::string plyText(const ObjectModel& m) {
  std::vector<glm::dvec3> normals(m.vertices.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t v[3] = {m.indices[t], m.indices[t + 1], m.indices[t + 2]};
    const glm::dvec3 n =
        glm::cross(m.vertices[v[1]] - m.vertices[v[0]], m.vertices[v[2]] - m.vertices[v[0]]);
    const double length = glm::length(n);
    if (!(length > 0.0)) continue;
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 e1 = m.vertices[v[(c + 1) % 3]] - m.vertices[v[c]];
      const glm::dvec3 e2 = m.vertices[v[(c + 2) % 3]] - m.vertices[v[c]];
      const double l1 = glm::length(e1), l2 = glm::length(e2);
      if (!(l1 > 0.0 && l2 > 0.0)) continue;
      const double angle = std::acos(std::clamp(glm::dot(e1, e2) / (l1 * l2), -1.0, 1.0));
      normals[v[c]] += angle * n / length;
    }
  }
  std::string s = "ply\nformat ascii 1.0\ncomment camsim BOP model, mm\nelement vertex " +
                  std::to_string(m.vertices.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
                  "property float ny\nproperty float nz\nelement face " +
                  std::to_string(m.indices.size() / 3) +
                  "\nproperty list uchar int vertex_indices\nend_header\n";
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const glm::dvec3 p = m.vertices[i] * kMmPerM;
    const double l = glm::length(normals[i]);
    const glm::dvec3 n = l > 0.0 ? normals[i] / l : glm::dvec3(0.0);
    for (const double v : {p.x, p.y, p.z, n.x, n.y, n.z}) s += formatNumber(v, 9) + " ";
    s.back() = '\n';
  }
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
    s += "3 " + std::to_string(m.indices[t]) + " " + std::to_string(m.indices[t + 1]) + " " +
         std::to_string(m.indices[t + 2]) + "\n";
  return s;
}

}  // namespace

PoseModels::PoseModels(const SceneDescription& d) {
  const bool bop = d.exportsTo(ExportFormat::kBop);
  if (!bop && !d.exportsTo(ExportFormat::kKitti)) return;
  const SceneIds ids = sceneIds(d);
  const IdTable& classes = ids[IdKind::kClass];
  std::map<std::uint32_t, BopModel> byId;
  boxes_.resize(d.shapes.size());
  ownOfShape_.assign(d.shapes.size(), nullptr);
  for (std::size_t s = 0; s < d.shapes.size(); ++s) {
    if (classes.ofShape[s] == 0) continue;
    ObjectModel model = objectModel(d, s);
    boxes_[s].boxMin = model.boxMin;
    boxes_[s].boxMax = model.boxMax;
    boxes_[s].rounding = model.rounding;
    ownOfShape_[s] = &boxes_[s];
    if (!bop) continue;
    const std::uint32_t objId = classes.numbers[classes.ofShape[s]];
    const auto [it, added] = byId.try_emplace(objId, BopModel{objId, s, {}});
    if (added) {
      it->second.model = std::move(model);
      continue;
    }
    if (!sameModel(it->second.model, model))
      throw InputError(exportsPlace(d), "exports",
                       "bop: shapes '" + d.shapes[it->second.shape].label + "' and '" +
                           d.shapes[s].label + "' have class " + std::to_string(objId) +
                           " (BOP's obj_id) but different models: give them different classes, "
                           "or place one mesh with `instances:`; a labelled OBJ split by its "
                           "`usemtl` groups, or a glTF asset of several primitives, is several "
                           "shapes of one class: give the OBJ one `material:`, or the pieces "
                           "classes of their own (docs/output.md, \"BOP layout\")");
  }
  if (!bop) return;
  for (auto& [id, m] : byId) bop_.push_back(std::move(m));
  bopOfShape_ = bopShapeModels(d, bop_);
}

std::vector<const ObjectModel*> bopShapeModels(const SceneDescription& d,
                                               const std::vector<BopModel>& models) {
  const SceneIds ids = sceneIds(d);
  const IdTable& classes = ids[IdKind::kClass];
  std::vector<const ObjectModel*> out(d.shapes.size(), nullptr);
  for (std::size_t s = 0; s < d.shapes.size(); ++s)
    for (const BopModel& m : models)
      if (classes.ofShape[s] != 0 && m.objId == classes.numbers[classes.ofShape[s]])
        out[s] = &m.model;
  return out;
}

DifferentBopModels firstDifferentBopModels(const std::vector<BopModel>& reference,
                                           const std::vector<BopModel>& other) {
  for (const BopModel& a : reference)  // both in obj_id order (PoseModels' map)
    for (const BopModel& b : other)
      if (a.objId == b.objId && !sameModel(a.model, b.model)) return {&a, &b};
  return {};
}

BopModelInfo bopModelInfo(const ObjectModel& m) {
  BopModelInfo info;
  info.min = m.boxMin * kMmPerM;
  info.size = (m.boxMax - m.boxMin) * kMmPerM;
  // The diameter, exactly: the largest distance between two vertices, pairs pruned by
  // |p_i − p_j| ≤ r_i + r_j (r: distance from the box centre), vertices by falling r.
  const glm::dvec3 centre = 0.5 * (m.boxMin + m.boxMax);
  std::vector<double> r(m.vertices.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = glm::length(m.vertices[i] - centre);
  std::vector<std::size_t> order(r.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return r[a] > r[b]; });
  double best = 0.0;
  for (std::size_t a = 0; a < order.size(); ++a) {
    if (a + 1 < order.size() && r[order[a]] + r[order[a + 1]] <= best) break;
    for (std::size_t b = a + 1; b < order.size(); ++b) {
      if (r[order[a]] + r[order[b]] <= best) break;
      best = std::max(best, glm::length(m.vertices[order[a]] - m.vertices[order[b]]));
    }
  }
  info.diameter = best * kMmPerM;
  return info;
}

std::vector<std::filesystem::path> writeBopModels(const std::vector<BopModel>& models,
                                                  const std::filesystem::path& directory) {
  std::filesystem::create_directories(directory);
  OutputSet outputs(directory);
  JsonObject info;
  for (const BopModel& m : models) {
    outputs.addText("obj_" + formatSixDigits(m.objId) + ".ply", plyText(m.model));
    const BopModelInfo i = bopModelInfo(m.model);
    info.set(std::to_string(m.objId), JsonObject()
                                          .set("diameter", i.diameter)
                                          .set("min_x", i.min.x)
                                          .set("min_y", i.min.y)
                                          .set("min_z", i.min.z)
                                          .set("size_x", i.size.x)
                                          .set("size_y", i.size.y)
                                          .set("size_z", i.size.z));
  }
  outputs.addText("models_info.json", info.str() + "\n");
  return outputs.commit();
}

void checkPoseExports(const SceneDescription& d) {
  (void)PoseModels(d);
}

}  // namespace camsim
