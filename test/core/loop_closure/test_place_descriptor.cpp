// The place descriptor: the same place turned on the spot is the same place at a sector shift
// that gives the turn; another place is far; a few metres away is a little farther.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/core/loop_closure/place_descriptor.h"
#include "core/loop_closure/keyframe_scenes.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

// The scene sampled about as densely as a scan sees it nearby (keyframe_scenes.h samples sparsely,
// which is enough for ICP but leaves a descriptor's cells empty at random).
std::vector<Patch> dense(std::vector<Patch> patches) {
  for (Patch& patch : patches)
    patch.density *= 10.0;
  return patches;
}

PlaceDescriptor place_of(const std::vector<Patch>& scene, const Eigen::Isometry3d& pose,
                         unsigned samples_seed) {
  PlaceRecognitionParams params;
  params.max_radius = 20.0;  // what observe() sees
  PlaceDescriptor descriptor(params);
  descriptor.add(*observe(dense(scene), pose, samples_seed), Eigen::Matrix3f::Identity());
  descriptor.finish();
  return descriptor;
}

}  // namespace

TEST(PlaceDescriptor, TheSamePlaceTurnedGivesItsTurn) {
  const std::vector<Patch> scene_patches = scene(7);
  const PlaceDescriptor here = place_of(scene_patches, planar(5, 5, 0), 1);
  for (double yaw_deg : {30.0, -90.0, 174.0}) {
    // Other samples of the same surfaces, the sensor turned.
    const PlaceDescriptor turned = place_of(scene_patches, planar(5, 5, yaw_deg), 2);
    int shift = 0;
    const double distance = turned.distance(here, &shift);
    EXPECT_LT(distance, 0.15) << yaw_deg;
    EXPECT_NEAR(turned.yaw_of_shift(shift) * 180.0 / M_PI, yaw_deg, 6.0 + 1e-9) << "one sector";
    EXPECT_LT(turned.distance(here), 0.15);
  }
  for (std::size_t ring = 0; ring < here.ring_key().size(); ++ring) {
    EXPECT_NEAR(place_of(scene_patches, planar(5, 5, 77), 3).ring_key()[ring],
                here.ring_key()[ring], 0.5)
        << "ring key " << ring << ": the turn does not change it";
  }
}

TEST(PlaceDescriptor, AnotherPlaceIsFarAndAFewMetresAwayIsFarther) {
  const PlaceDescriptor here = place_of(scene(7), planar(5, 5, 0), 1);
  const double same = place_of(scene(7), planar(5, 5, 0), 2).distance(here);
  const double near = place_of(scene(7), planar(7, 5, 0), 2).distance(here);
  const double elsewhere = place_of(scene(99), planar(5, 5, 0), 2).distance(here);
  EXPECT_LT(same, near);
  EXPECT_LT(near, elsewhere);
  EXPECT_GT(elsewhere, 0.3) << "beyond the default place_max_distance";
  EXPECT_DOUBLE_EQ(PlaceDescriptor(PlaceRecognitionParams()).distance(here), 1.0)
      << "an empty grid is like nothing";
}
