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

// An Embree scene made from one GeometrySet: triangles and capped cylinders.
struct SubScene {
  RTCScene scene = nullptr;
  const GeometrySet* geometry = nullptr;
  unsigned triangle_geometry = RTC_INVALID_GEOMETRY_ID;
  unsigned cylinder_geometry = RTC_INVALID_GEOMETRY_ID;

  uint32_t surface(unsigned geometry_id, unsigned primitive) const {
    return geometry_id == triangle_geometry ? geometry->triangle_surfaces[primitive]
                                            : geometry->cylinders[primitive].surface;
  }
};

// One instance of the top-level scene; its index is the instance's geometry id there.
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

  // The prepared frame.
  RTCScene top = nullptr;
  std::vector<InstanceRecord> records;
  std::vector<GeometrySet> walker_geometry_now;
  std::vector<SubScene> walker_scenes_now;

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
    if (!set.triangles.empty()) sub.triangle_geometry = attach_triangles(sub.scene, set);
    if (!set.cylinders.empty()) sub.cylinder_geometry = attach_cylinders(sub.scene, set);
    rtcCommitScene(sub.scene);
    check_device("building a scene");
    return sub;
  }

  unsigned attach_triangles(RTCScene scene, const GeometrySet& set) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), set.vertices.size()));
    for (std::size_t i = 0; i < set.vertices.size(); ++i) {
      for (int k = 0; k < 3; ++k)
        vertices[3 * i + k] = set.vertices[i][k];
    }
    auto* indices = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(uint32_t), set.triangles.size()));
    for (std::size_t i = 0; i < set.triangles.size(); ++i) {
      for (int k = 0; k < 3; ++k)
        indices[3 * i + k] = set.triangles[i][k];
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

  void add_instance(const SubScene& sub, const Eigen::Affine3f& transform, uint16_t instance) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geometry, sub.scene);
    Eigen::Matrix<float, 3, 4> matrix = transform.matrix().topRows<3>();  // column-major storage
    rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, matrix.data());
    const unsigned id = commit_and_attach(top, geometry);
    if (id != records.size()) throw std::logic_error("embree: unexpected instance id");
    records.push_back({&sub, transform.linear().inverse().transpose(), instance});
  }

  bool box_in_reach(const Eigen::AlignedBox3f& box, const Eigen::Vector3f& sensor) const {
    return box.exteriorDistance(sensor) <= reach;
  }

  void add_tiles(const Eigen::Vector3f& sensor) {
    for (const auto& [key, bounds] : tile_bounds) {
      auto built = tile_scenes.find(key);
      if (!box_in_reach(bounds, sensor)) {
        // Far behind: free it (it is rebuilt if the path comes back).
        if (built != tile_scenes.end() &&
            bounds.exteriorDistance(sensor) > reach + 2 * world->tile_size) {
          rtcReleaseScene(built->second.scene);
          tile_scenes.erase(built);
        }
        continue;
      }
      if (built == tile_scenes.end()) {
        built = tile_scenes.emplace(key, build(world->tiles.at(key), RTC_BUILD_QUALITY_HIGH, true))
                    .first;
      }
      add_instance(built->second, Eigen::Affine3f::Identity(), 0);
    }
  }

  void add_plants(int frame, double time, const Eigen::Vector3f& sensor) {
    const auto [cx, cy] = plant_cell(sensor);
    const int span = static_cast<int>(std::ceil(reach / kPlantGridCell)) + 1;
    const float sway_amplitude = world->wind.sway_deg * static_cast<float>(M_PI) / 180.0f;
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
          add_instance(plant_scene(plant.prototype, state), transform, plant.instance);
        }
      }
    }
  }

  const SubScene& plant_scene(int prototype, int state) {
    SubScene& sub = plant_scenes[prototype][state];
    if (!sub.scene)
      sub = build(world->plant_prototypes[prototype].wind_states[state], RTC_BUILD_QUALITY_HIGH);
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

  void add_movers(double time, const Eigen::Vector3f& sensor) {
    if (!world->path) return;
    Eigen::Affine3f pose;
    for (const MovingCar& car : world->moving_cars) {
      if (!mover_pose(car.motion, time, sensor, pose)) continue;
      add_instance(car_scenes[car.prototype], pose, car.instance);
    }
    std::vector<std::pair<const Walker*, Eigen::Affine3f>> active;
    for (const Walker& walker : world->walkers) {
      if (mover_pose(walker.motion, time, sensor, pose)) active.emplace_back(&walker, pose);
    }
    walker_geometry_now.reserve(active.size());  // SubScenes point into it: no reallocation
    for (const auto& [walker, walker_pose] : active) {
      walker_geometry_now.push_back(walker_geometry(*walker, time));
      walker_scenes_now.push_back(build(walker_geometry_now.back(), RTC_BUILD_QUALITY_LOW));
    }
    for (std::size_t i = 0; i < active.size(); ++i)
      add_instance(walker_scenes_now[i], active[i].second, active[i].first->instance);
  }

  void release_frame() {
    if (top) rtcReleaseScene(top);
    top = nullptr;
    for (SubScene& sub : walker_scenes_now)
      rtcReleaseScene(sub.scene);
    walker_scenes_now.clear();
    walker_geometry_now.clear();
    records.clear();
  }

  Hit make_hit(const RTCHit& hit, float distance, const Eigen::Vector3f& direction) const {
    Hit result;
    const InstanceRecord& record = records[hit.instID[0]];
    const Surface& surface = world->surfaces[record.sub->surface(hit.geomID, hit.primID)];
    result.distance = distance;
    result.normal =
        (record.normal_matrix * Eigen::Vector3f(hit.Ng_x, hit.Ng_y, hit.Ng_z)).normalized();
    if (result.normal.dot(direction) > 0.0f) result.normal = -result.normal;
    result.label =
        pack_label(surface.semantic, surface.instance ? surface.instance : record.instance);
    result.reflectivity = surface.reflectivity;
    return result;
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
}

RayCaster::~RayCaster() {
  Impl& d = *impl_;
  d.release_frame();
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
  d.release_frame();
  const Eigen::Vector3f sensor = sensor_position.cast<float>();
  d.top = rtcNewScene(d.device);
  rtcSetSceneBuildQuality(d.top, RTC_BUILD_QUALITY_LOW);
  d.add_tiles(sensor);
  d.add_plants(frame, time, sensor);
  d.add_movers(time, sensor);
  rtcCommitScene(d.top);
  d.check_device("building the frame's scene");
}

void RayCaster::cast(const std::vector<Ray>& rays, std::vector<Hit>& hits) const {
  const Impl& d = *impl_;
  if (!d.top) throw std::logic_error("RayCaster::cast before prepare");
  hits.assign(rays.size(), Hit());
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kPacketSize];
  for (std::size_t first = 0; first < rays.size(); first += kPacketSize) {
    const int count = static_cast<int>(std::min<std::size_t>(kPacketSize, rays.size() - first));
    for (int i = 0; i < kPacketSize; ++i) {
      valid[i] = i < count ? -1 : 0;
      const Ray& ray = rays[first + std::min(i, count - 1)];
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
    for (int i = 0; i < count; ++i) {
      if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
      RTCHit hit;
      hit.Ng_x = packet.hit.Ng_x[i];
      hit.Ng_y = packet.hit.Ng_y[i];
      hit.Ng_z = packet.hit.Ng_z[i];
      hit.primID = packet.hit.primID[i];
      hit.geomID = packet.hit.geomID[i];
      hit.instID[0] = packet.hit.instID[0][i];
      hits[first + i] = d.make_hit(hit, packet.ray.tfar[i], rays[first + i].direction);
    }
  }
}

}  // namespace adaptive_lego_loam::sim
