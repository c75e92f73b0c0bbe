#pragma once
// Ray casting against a World with Embree 3. Static tiles are built once when the sensor first
// comes near them. A top-level scene holds an instance of each object in reach; each frame moves
// them (plants to their wind state of the frame, moving objects to where they are then) and
// rebuilds only that top level.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/sim/world.h"

namespace adaptive_lego_loam::sim {

struct Ray {
  Eigen::Vector3f origin;
  Eigen::Vector3f direction;  // unit
  float max_distance = 0.0f;
};

struct Hit {
  float distance = -1.0f;                            // along the ray; negative: nothing hit
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit, world frame, facing the ray
  uint32_t label = 0;                                // SemanticKITTI packing
  float reflectivity = 0.0f;
  bool valid() const { return distance >= 0.0f; }
};

class RayCaster {
 public:
  // Objects farther than `reach` from the sensor are left out of a frame's scene. Uses one
  // thread (Embree's builders included).
  RayCaster(std::shared_ptr<const World> world, float reach);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // Sets up the scene of frame `frame` at `time`: wind state, moving objects, tiles in reach.
  void prepare(int frame, double time, const Eigen::Vector3d& sensor_position);
  // Closest hit of each ray in the prepared scene.
  void cast(const std::vector<Ray>& rays, std::vector<Hit>& hits) const;
  // The same for `count` rays into `hits` (room for `count`).
  void cast(const Ray* rays, std::size_t count, Hit* hits) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptive_lego_loam::sim
