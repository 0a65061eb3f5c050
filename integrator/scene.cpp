#include "integrator/scene.h"

#include "integrator/diffuse_material.h"
#include "integrator/pinhole_camera.h"
#include "integrator/sphere.h"
#include "integrator/triangle_mesh.h"

namespace camsim {

Scene::Scene(const SceneDescription& d) : settings_(d.render) {
  const CameraDescription& c = d.camera;
  camera_ = std::make_unique<PinholeCamera>(c.worldFromCamera, c.sensorSizeM, c.resolution,
                                            c.focalLengthM);
  materials_.push_back(std::make_unique<DiffuseMaterial>(Spectrum::constant(0.0)));  // black
  for (const MaterialDescription& m : d.materials)
    materials_.push_back(std::make_unique<DiffuseMaterial>(m.reflectance));

  std::vector<double> powers;
  for (const ShapeDescription& s : d.shapes) {
    if (s.kind == ShapeDescription::Kind::kSphere)
      shapes_.push_back(std::make_unique<Sphere>(s.centre, s.radius));
    else
      shapes_.push_back(std::make_unique<TriangleMesh>(s.mesh.positions, s.mesh.normals, s.mesh.indices));
    materialOfShape_.push_back(s.material < 0 ? 0 : static_cast<size_t>(s.material) + 1);
    lightOfShape_.push_back(nullptr);
    lightIndexOfShape_.push_back(0);
    if (s.emission) {
      auto light = std::make_unique<AreaLight>(*shapes_.back(), s.emission->radiance, s.emission->twoSided);
      lightOfShape_.back() = light.get();
      lightIndexOfShape_.back() = lights_.size();
      powers.push_back(light->power());
      lights_.push_back(std::move(light));
    }
  }
  if (!powers.empty()) lightDistribution_ = DiscreteDistribution(powers);
  geometry_ = std::make_unique<EmbreeScene>(shapes_);
}

}  // namespace camsim
