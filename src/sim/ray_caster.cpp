#include "adaptive_lego_loam/sim/ray_caster.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_lego_loam/sim/random.h"

namespace adaptive_lego_loam::sim {
namespace {

constexpr float kPlantGridCell = 32.0f;
constexpr int kPacketSize = 16;
constexpr unsigned kNoInstance = RTC_INVALID_GEOMETRY_ID;

// An Embree scene made from one GeometrySet: a triangle geometry per surface (the hit's geometry
// id then gives its surface) and the capped cylinders.
struct SubScene {
  RTCScene scene = nullptr;
  const GeometrySet* geometry = nullptr;
  std::vector<uint32_t> geometry_surfaces;  // by geometry id; kCylinders: look up the cylinder
  static constexpr uint32_t kCylinders = 0xFFFFFFFFu;

  uint32_t surface(unsigned geometry_id, unsigned primitive) const {
    const uint32_t surface = geometry_surfaces[geometry_id];
    return surface != kCylinders ? surface : geometry->cylinders[primitive].surface;
  }
};

// One instance of the top-level scene, found by its geometry id there.
struct InstanceRecord {
  const SubScene* sub = nullptr;
  Eigen::Matrix3f normal_matrix = Eigen::Matrix3f::Identity();
  uint16_t instance = 0;  // used for surfaces without their own
};

std::pair<int, int> plant_cell(const Eigen::Vector3f& point) {
  return {static_cast<int>(std::floor(point.x() / kPlantGridCell)),
          static_cast<int>(std::floor(point.y() / kPlantGridCell))};
}

}  // namespace

struct RayCaster::Impl {
  std::shared_ptr<const World> world;
  float reach;
  RTCDevice device = nullptr;
  std::string device_error;

  std::map<TileKey, Eigen::AlignedBox3f> tile_bounds;
  std::map<TileKey, SubScene> tile_scenes;          // built when first in reach
  std::vector<std::vector<SubScene>> plant_scenes;  // [prototype][wind state]
  std::vector<SubScene> car_scenes;
  std::map<std::pair<int, int>, std::vector<int>> plants_by_cell;

  // The top-level scene lives as long as the caster: an object keeps its instance while it is in
  // reach, and each frame only moves it (wind state, sway, traffic) and rebuilds the top level.
  RTCScene top = nullptr;
  std::vector<InstanceRecord> records;  // by geometry id in `top`
  std::map<TileKey, unsigned> tile_instances;
  std::vector<unsigned> plant_instances;  // per plant; kNoInstance when out of reach
  std::vector<unsigned> car_instances;    // per moving car
  std::vector<int> plants_in_reach, plants_in_reach_before;
  std::vector<int> cars_in_reach, cars_in_reach_before;
  std::vector<unsigned> walker_instances;  // put in anew every frame, in the gait's pose
  std::map<std::pair<uint32_t, int>, SubScene> walker_scenes;  // by (surface, pose)
  std::vector<std::unique_ptr<GeometrySet>> walker_geometry;   // what they were built from
  int frame_stamp = 0;
  bool prepared = false;
  std::vector<int> plant_seen, car_seen;  // frame_stamp when last put in this frame's scene

  void check_device(const char* what) {
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE || !device_error.empty()) {
      throw std::runtime_error(std::string("embree: ") + what + ": " + device_error);
    }
  }

  // `watertight`: no ray slips between triangles sharing an edge (ground, walls); slower.
  SubScene build(const GeometrySet& set, RTCBuildQuality quality, bool watertight = false) {
    SubScene sub;
    sub.geometry = &set;
    sub.scene = rtcNewScene(device);
    if (watertight) rtcSetSceneFlags(sub.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(sub.scene, quality);
    std::map<uint32_t, std::vector<uint32_t>> by_surface;  // surface -> its triangles
    for (std::size_t i = 0; i < set.triangles.size(); ++i)
      by_surface[set.triangle_surfaces[i]].push_back(static_cast<uint32_t>(i));
    for (const auto& [surface, triangles] : by_surface)
      note_geometry(sub, attach_triangles(sub.scene, set, triangles), surface);
    if (!set.cylinders.empty())
      note_geometry(sub, attach_cylinders(sub.scene, set), SubScene::kCylinders);
    rtcCommitScene(sub.scene);
    check_device("building a scene");
    return sub;
  }

  static void note_geometry(SubScene& sub, unsigned id, uint32_t surface) {
    if (id >= sub.geometry_surfaces.size()) sub.geometry_surfaces.resize(id + 1, 0);
    sub.geometry_surfaces[id] = surface;
  }

  // The triangles `which` of `set`, with their own copies of their vertices.
  unsigned attach_triangles(RTCScene scene, const GeometrySet& set,
                            const std::vector<uint32_t>& which) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), 3 * which.size()));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), which.size()));
    for (std::size_t i = 0; i < which.size(); ++i) {
      for (int corner = 0; corner < 3; ++corner) {
        const Eigen::Vector3f& vertex = set.vertices[set.triangles[which[i]][corner]];
        const std::size_t k = 3 * i + corner;
        for (int axis = 0; axis < 3; ++axis)
          vertices[3 * k + axis] = vertex[axis];
        indices[k] = static_cast<uint32_t>(k);
      }
    }
    return commit_and_attach(scene, geometry);
  }

  unsigned attach_cylinders(RTCScene scene, const GeometrySet& set) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE);
    const std::size_t count = set.cylinders.size();
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 2 * count));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(uint32_t), count));
    auto* flags = static_cast<uint8_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, sizeof(uint8_t), count));
    for (std::size_t i = 0; i < count; ++i) {
      const Cylinder& cylinder = set.cylinders[i];
      for (int end = 0; end < 2; ++end) {
        const Eigen::Vector3f& p = end == 0 ? cylinder.a : cylinder.b;
        float* vertex = vertices + 4 * (2 * i + end);
        vertex[0] = p.x();
        vertex[1] = p.y();
        vertex[2] = p.z();
        vertex[3] = cylinder.radius;
      }
      indices[i] = static_cast<uint32_t>(2 * i);
      flags[i] = 0;  // no neighbours: both ends capped
    }
    return commit_and_attach(scene, geometry);
  }

  static unsigned commit_and_attach(RTCScene scene, RTCGeometry geometry) {
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    return id;
  }

  // Puts `sub` at `transform` into the top-level scene: into the instance `id` when it has one
  // (kNoInstance: a new one). Returns the instance's id.
  unsigned place(unsigned id, const SubScene& sub, const Eigen::Affine3f& transform,
                 uint16_t instance) {
    RTCGeometry geometry;
    if (id == kNoInstance) {
      geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    } else {
      geometry = rtcGetGeometry(top, id);
    }
    rtcSetGeometryInstancedScene(geometry, sub.scene);
    const Eigen::Matrix<float, 3, 4> matrix = transform.matrix().topRows<3>();  // column-major
    rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, matrix.data());
    if (id == kNoInstance) {
      id = commit_and_attach(top, geometry);
    } else {
      rtcCommitGeometry(geometry);
    }
    if (id >= records.size()) records.resize(id + 1);
    records[id] = {&sub, transform.linear().inverse().transpose(), instance};
    return id;
  }

  void remove(unsigned& id) {
    if (id == kNoInstance) return;
    rtcDetachGeometry(top, id);
    records[id] = InstanceRecord();
    id = kNoInstance;
  }

  bool box_in_reach(const Eigen::AlignedBox3f& box, const Eigen::Vector3f& sensor) const {
    return box.exteriorDistance(sensor) <= reach;
  }

  void update_tiles(const Eigen::Vector3f& sensor) {
    for (const auto& [key, bounds] : tile_bounds) {
      auto built = tile_scenes.find(key);
      auto placed = tile_instances.find(key);
      if (!box_in_reach(bounds, sensor)) {
        if (placed != tile_instances.end()) {
          remove(placed->second);
          tile_instances.erase(placed);
        }
        // Far behind: free it (it is rebuilt if the path comes back).
        if (built != tile_scenes.end() &&
            bounds.exteriorDistance(sensor) > reach + 2 * world->tile_size) {
          rtcReleaseScene(built->second.scene);
          tile_scenes.erase(built);
        }
        continue;
      }
      if (placed != tile_instances.end()) continue;  // static: nothing to update
      if (built == tile_scenes.end()) {
        built = tile_scenes.emplace(key, build(world->tiles.at(key), RTC_BUILD_QUALITY_HIGH, true))
                    .first;
      }
      tile_instances[key] = place(kNoInstance, built->second, Eigen::Affine3f::Identity(), 0);
    }
  }

  void update_plants(int frame, double time, const Eigen::Vector3f& sensor) {
    const auto [cx, cy] = plant_cell(sensor);
    const int span = static_cast<int>(std::ceil(reach / kPlantGridCell)) + 1;
    const float sway_amplitude = world->wind.sway_deg * static_cast<float>(M_PI) / 180.0f;
    plants_in_reach.clear();
    for (int ix = cx - span; ix <= cx + span; ++ix) {
      for (int iy = cy - span; iy <= cy + span; ++iy) {
        const auto cell = plants_by_cell.find({ix, iy});
        if (cell == plants_by_cell.end()) continue;
        for (int index : cell->second) {
          const Plant& plant = world->plants[index];
          const PlantPrototype& prototype = world->plant_prototypes[plant.prototype];
          if ((plant.base - sensor).head<2>().norm() > reach + prototype.radius * plant.scale)
            continue;
          const uint64_t bits = derive_seed(world->seed, 0x57494E44ull /* wind */,
                                            (static_cast<uint64_t>(index) << 32) | uint32_t(frame));
          const int state = static_cast<int>(bits % prototype.wind_states.size());
          const float sway =
              sway_amplitude * std::sin(2.0f * static_cast<float>(M_PI) * world->wind.sway_hz *
                                            static_cast<float>(time) +
                                        plant.sway_phase);
          Eigen::Affine3f transform = Eigen::Affine3f::Identity();
          transform.translate(plant.base);
          transform.rotate(Eigen::AngleAxisf(sway, Eigen::Vector3f::UnitY()));
          transform.rotate(Eigen::AngleAxisf(plant.yaw, Eigen::Vector3f::UnitZ()));
          transform.scale(plant.scale);
          plant_instances[index] =
              place(plant_instances[index], plant_scene(plant.prototype, state), transform,
                    plant.instance);
          plant_seen[index] = frame_stamp;
          plants_in_reach.push_back(index);
        }
      }
    }
    for (int index : plants_in_reach_before) {
      if (plant_seen[index] != frame_stamp) remove(plant_instances[index]);
    }
    std::swap(plants_in_reach, plants_in_reach_before);
  }

  // Medium quality: as fast to trace as high quality (spatial splits) for small facets, and
  // several times faster to build.
  const SubScene& plant_scene(int prototype, int state) {
    SubScene& sub = plant_scenes[prototype][state];
    if (!sub.scene)
      sub = build(world->plant_prototypes[prototype].wind_states[state], RTC_BUILD_QUALITY_MEDIUM);
    return sub;
  }

  // Pose of a path-following object at `time`, or false when it is off the path or out of reach.
  bool mover_pose(const PathMotion& motion, double time, const Eigen::Vector3f& sensor,
                  Eigen::Affine3f& pose) const {
    const Path& path = *world->path;
    const double s = motion.start_s + motion.speed * time;
    if (!path.closed() && (s < 0.0 || s > path.length())) return false;
    pose = path_motion_pose(path, motion, time).cast<float>();
    return (pose.translation() - sensor).norm() <= reach + 5.0f;
  }

  void update_movers(double time, const Eigen::Vector3f& sensor) {
    for (unsigned& id : walker_instances)
      remove(id);
    walker_instances.clear();
    if (!world->path) return;
    Eigen::Affine3f pose;
    cars_in_reach.clear();
    for (std::size_t i = 0; i < world->moving_cars.size(); ++i) {
      const MovingCar& car = world->moving_cars[i];
      if (!mover_pose(car.motion, time, sensor, pose)) continue;
      car_instances[i] = place(car_instances[i], car_scenes[car.prototype], pose, car.instance);
      car_seen[i] = frame_stamp;
      cars_in_reach.push_back(static_cast<int>(i));
    }
    for (int index : cars_in_reach_before) {
      if (car_seen[index] != frame_stamp) remove(car_instances[index]);
    }
    std::swap(cars_in_reach, cars_in_reach_before);

    for (const Walker& walker : world->walkers) {
      if (!mover_pose(walker.motion, time, sensor, pose)) continue;
      pose.scale(walker.height / kWalkerHeight);
      walker_instances.push_back(place(kNoInstance,
                                       walker_scene(walker.surface, walker_pose(walker, time)),
                                       pose, walker.instance));
    }
  }

  const SubScene& walker_scene(uint32_t surface, int pose) {
    auto found = walker_scenes.find({surface, pose});
    if (found == walker_scenes.end()) {
      auto geometry = std::make_unique<GeometrySet>(walker_pose_geometry(pose, surface));
      const SubScene sub = build(*geometry, RTC_BUILD_QUALITY_MEDIUM);
      walker_geometry.push_back(std::move(geometry));
      found = walker_scenes.emplace(std::make_pair(surface, pose), sub).first;
    }
    return found->second;
  }

  void make_hit(unsigned instance_id, unsigned geometry_id, unsigned primitive,
                const Eigen::Vector3f& normal, float distance, const Eigen::Vector3f& direction,
                Hit& result) const {
    const InstanceRecord& record = records[instance_id];
    const Surface& surface = world->surfaces[record.sub->surface(geometry_id, primitive)];
    result.distance = distance;
    result.normal = (record.normal_matrix * normal).normalized();
    if (result.normal.dot(direction) > 0.0f) result.normal = -result.normal;
    result.label =
        pack_label(surface.semantic, surface.instance ? surface.instance : record.instance);
    result.reflectivity = surface.reflectivity;
  }
};

RayCaster::RayCaster(std::shared_ptr<const World> world, float reach) : impl_(new Impl) {
  Impl& d = *impl_;
  d.world = std::move(world);
  d.reach = reach;
  d.device = rtcNewDevice("threads=1,verbose=0");
  if (!d.device) throw std::runtime_error("embree: cannot create a device");
  rtcSetDeviceErrorFunction(
      d.device,
      [](void* user, RTCError, const char* message) {
        static_cast<Impl*>(user)->device_error = message ? message : "unknown error";
      },
      &d);
  for (const auto& [key, tile] : d.world->tiles) {
    if (!tile.empty()) d.tile_bounds[key] = tile.bounds();
  }
  for (const PlantPrototype& prototype : d.world->plant_prototypes) {
    // Built when first needed: a scene may use few of them, or none.
    d.plant_scenes.emplace_back(prototype.wind_states.size());
  }
  for (const GeometrySet& car : d.world->car_prototypes)
    d.car_scenes.push_back(d.build(car, RTC_BUILD_QUALITY_HIGH));
  for (std::size_t i = 0; i < d.world->plants.size(); ++i)
    d.plants_by_cell[plant_cell(d.world->plants[i].base)].push_back(static_cast<int>(i));
  d.plant_instances.assign(d.world->plants.size(), kNoInstance);
  d.plant_seen.assign(d.world->plants.size(), -1);
  d.car_instances.assign(d.world->moving_cars.size(), kNoInstance);
  d.car_seen.assign(d.world->moving_cars.size(), -1);
  d.top = rtcNewScene(d.device);
  rtcSetSceneFlags(d.top, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(d.top, RTC_BUILD_QUALITY_LOW);
  d.check_device("creating the top-level scene");
}

RayCaster::~RayCaster() {
  Impl& d = *impl_;
  rtcReleaseScene(d.top);
  for (auto& [key, sub] : d.walker_scenes)
    rtcReleaseScene(sub.scene);
  for (auto& [key, sub] : d.tile_scenes)
    rtcReleaseScene(sub.scene);
  for (auto& states : d.plant_scenes) {
    for (SubScene& sub : states) {
      if (sub.scene) rtcReleaseScene(sub.scene);
    }
  }
  for (SubScene& sub : d.car_scenes)
    rtcReleaseScene(sub.scene);
  rtcReleaseDevice(d.device);
}

void RayCaster::prepare(int frame, double time, const Eigen::Vector3d& sensor_position) {
  Impl& d = *impl_;
  const Eigen::Vector3f sensor = sensor_position.cast<float>();
  ++d.frame_stamp;
  d.prepared = false;
  d.update_tiles(sensor);
  d.update_plants(frame, time, sensor);
  d.update_movers(time, sensor);
  rtcCommitScene(d.top);
  d.check_device("building the frame's scene");
  d.prepared = true;
}

void RayCaster::cast(const std::vector<Ray>& rays, std::vector<Hit>& hits) const {
  hits.resize(rays.size());
  cast(rays.data(), rays.size(), hits.data());
}

void RayCaster::cast(const Ray* rays, std::size_t count, Hit* hits) const {
  const Impl& d = *impl_;
  if (!d.prepared) throw std::logic_error("RayCaster::cast before prepare");
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kPacketSize];
  for (std::size_t first = 0; first < count; first += kPacketSize) {
    const int lanes = static_cast<int>(std::min<std::size_t>(kPacketSize, count - first));
    for (int i = 0; i < kPacketSize; ++i) {
      valid[i] = i < lanes ? -1 : 0;
      const Ray& ray = rays[first + std::min(i, lanes - 1)];
      packet.ray.org_x[i] = ray.origin.x();
      packet.ray.org_y[i] = ray.origin.y();
      packet.ray.org_z[i] = ray.origin.z();
      packet.ray.dir_x[i] = ray.direction.x();
      packet.ray.dir_y[i] = ray.direction.y();
      packet.ray.dir_z[i] = ray.direction.z();
      packet.ray.tnear[i] = 0.0f;
      packet.ray.tfar[i] = ray.max_distance;
      packet.ray.time[i] = 0.0f;
      packet.ray.mask[i] = 0xFFFFFFFFu;
      packet.ray.id[i] = static_cast<unsigned>(i);
      packet.ray.flags[i] = 0;
      packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, d.top, &context, &packet);
    for (int i = 0; i < lanes; ++i) {
      Hit& hit = hits[first + i];
      if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
        hit = Hit();
        continue;
      }
      d.make_hit(packet.hit.instID[0][i], packet.hit.geomID[i], packet.hit.primID[i],
                 Eigen::Vector3f(packet.hit.Ng_x[i], packet.hit.Ng_y[i], packet.hit.Ng_z[i]),
                 packet.ray.tfar[i], rays[first + i].direction, hit);
    }
  }
}

}  // namespace adaptive_lego_loam::sim
