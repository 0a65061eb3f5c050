// SceneCache: a built Scene (Embree BVH, shapes, materials, lights) kept by the caller of
// capture() between captures of one scene, so that a capture which changes only the camera
// (pose, shutter, f-number, sensor size), render.spp, render.seed, the sensor or the ISP
// renders on the Scene built before instead of building it again. The result is the same,
// bit for bit, as a capture that builds its own Scene (tests/integrator/capture/
// scene_cache_test.cpp): Scene::retarget sets exactly what Scene(description) would. A new
// exposure window of a scene with keyframed motion rebuilds only the shapes and the BVH
// over it (Scene::setCamera), keeping materials, textures and lights: no file is read.
//
// The caller vouches that between captures through one cache the shapes, materials,
// lights and textures are unchanged (comparing meshes would cost what the cache saves);
// anything else changed: clear() first. Scene::canRetarget checks what can be checked
// cheaply (render origin, other render settings, frames, counts) and a capture it rejects
// builds a new Scene, which the cache then keeps. The cache is the caller's object, never
// shared: no global state, and one cache must not serve two captures at once (retarget
// and a capture's re-renders change the Scene in place).
#pragma once

#include <memory>
#include <string>

#include "integrator/scene/scene.h"
#include "integrator/scene/scene_description.h"

namespace camsim {

class SceneCache {
 public:
  // The Scene to render `d` with: the kept one retargeted to d when it can render d
  // (reused() is then true), else a new one built from d and kept. The caller may move it
  // to another shutter of d's capture (Scene::setCamera; capture()'s step 4 does); the next
  // sceneFor retargets it again. A retarget that throws clears the cache.
  Scene& sceneFor(const SceneDescription& d);
  // Whether the last sceneFor() reused the kept Scene (false before any).
  bool reused() const { return reused_; }
  bool empty() const { return !scene_; }
  void clear() {
    scene_.reset();
    reused_ = false;
  }

 private:
  std::unique_ptr<Scene> scene_;
  std::string sourceFnv1a_;  // of the description it was built from: another scene is rebuilt
  bool reused_ = false;
};

}  // namespace camsim
