#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/ambient/skeleton.h"
#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "core/ambient/filter_scan.h"
#include "support/scenes.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
using test::Box;
using test::Scene;

TEST(Degeneration, CorridorIsDegenerateAlongItsAxis) {
  const Config config = synthetic_config();
  const AmbientFilterResult result = filter(config, test::render(config.sensor, corridor()));
  ASSERT_TRUE(result.degeneration.valid);
  EXPECT_GT(result.skeleton_points, 1000);
  EXPECT_GT(result.degeneration.normals, 100);
  EXPECT_GE(result.mu, 0.8);
  EXPECT_GE(std::fabs(result.degeneration.weak_direction.x()), std::cos(10.0 * M_PI / 180.0))
      << result.degeneration.weak_direction.transpose();
  // A degenerate scene gets the lenient end of the threshold range.
  EXPECT_LT(result.beta0_deg, 20.0);
}

TEST(Degeneration, BoxRoomAndCrossroadsAreWellConstrained) {
  const Config config = synthetic_config();
  for (const auto& [name, scene] :
       {std::pair<const char*, Scene>{"box room", box_room()}, {"crossroads", crossroads()}}) {
    SCOPED_TRACE(name);
    const AmbientFilterResult result = filter(config, test::render(config.sensor, scene));
    ASSERT_TRUE(result.degeneration.valid);
    EXPECT_GT(result.degeneration.normals, 100);
    EXPECT_LE(result.mu, 0.3);
    EXPECT_GT(result.beta0_deg, 45.0);
  }
}

TEST(Degeneration, HandMadeNormals) {
  auto normal = [](float x, float y, float z, float weight) {
    NormalFeature n;
    n.normal = Eigen::Vector3f(x, y, z).normalized();
    n.weight = weight;
    return n;
  };
  // All normals along +-y: k infinite, mu = 1, weak direction x.
  Degeneration d = degeneration_from_normals({normal(0, 1, 0, 2), normal(0, -1, 0, 1)});
  EXPECT_TRUE(d.valid);
  EXPECT_DOUBLE_EQ(d.mu, 1.0);
  EXPECT_NEAR(std::fabs(d.weak_direction.x()), 1.0, 1e-12);
  // Equal weight along x and y: k = 1, mu = 0.
  d = degeneration_from_normals({normal(1, 0, 0, 1), normal(0, 1, 0, 1)});
  EXPECT_NEAR(d.mu, 0.0, 1e-12);
  // Three along y, one along x (equal weights): k = 3, mu = 2/3.
  d = degeneration_from_normals(
      {normal(0, 1, 0, 1), normal(0, -1, 0, 1), normal(0, 1, 0, 1), normal(1, 0, 0, 1)});
  EXPECT_NEAR(d.mu, 2.0 / 3.0, 1e-12);
  // Only vertical normals (a flat ceiling): nothing horizontal, mu unknown.
  EXPECT_FALSE(degeneration_from_normals({normal(0, 0, 1, 1)}).valid);
  EXPECT_FALSE(degeneration_from_normals({}).valid);
  EXPECT_DOUBLE_EQ(beta0_from_mu(1.0, 10, 60), 10.0);
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.0, 10, 60), 60.0);
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.5, 10, 60), 35.0);
}

// Strict below the first knot, lenient above the second, linear between.
TEST(Degeneration, Beta0MapHoldsEachEndBeyondItsKnot) {
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.1, 10, 60, 0.3, 0.5), 60.0);
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.3, 10, 60, 0.3, 0.5), 60.0);
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.4, 10, 60, 0.3, 0.5), 35.0);
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.5, 10, 60, 0.3, 0.5), 10.0);
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.9, 10, 60, 0.3, 0.5), 10.0);
}

TEST(Degeneration, FewNormalsPullMuTowardDegenerate) {
  EXPECT_DOUBLE_EQ(mu_with_evidence(0.2, 50, 200), 0.8);  // a quarter of the evidence
  EXPECT_DOUBLE_EQ(mu_with_evidence(0.2, 0, 200), 1.0);
  EXPECT_DOUBLE_EQ(mu_with_evidence(0.2, 200, 200), 0.2);
  EXPECT_DOUBLE_EQ(mu_with_evidence(0.2, 5000, 200), 0.2);
  EXPECT_DOUBLE_EQ(mu_with_evidence(0.2, 50, 0), 0.2);  // off
}

TEST(Degeneration, TheStructureShareOfTheSceneShiftsMu) {
  EXPECT_DOUBLE_EQ(mu_with_structure(0.5, 0.10, 1.0, 0.25), 0.35);  // foliage: toward strict
  EXPECT_DOUBLE_EQ(mu_with_structure(0.5, 0.45, 1.0, 0.25), 0.70);  // walls: toward lenient
  EXPECT_DOUBLE_EQ(mu_with_structure(0.5, 0.25, 1.0, 0.25), 0.50);
  EXPECT_DOUBLE_EQ(mu_with_structure(0.1, 0.0, 1.0, 0.25), 0.0);  // clamped
  EXPECT_DOUBLE_EQ(mu_with_structure(0.9, 1.0, 1.0, 0.25), 1.0);
  EXPECT_DOUBLE_EQ(mu_with_structure(0.5, 0.0, 0.0, 0.25), 0.5);  // off
}

TEST(Degeneration, SmoothFragmentsCountAsStructureAndRoughOnesDoNot) {
  // 100 skeleton points of 1000 clustered: 900 fragments.
  EXPECT_DOUBLE_EQ(structure_share(100, 1000, 0.65, 0.45), (100 + 900 * 0.2 / 0.55) / 1000);
  EXPECT_DOUBLE_EQ(structure_share(100, 1000, 0.43, 0.45), 0.1);  // leaves: the skeleton alone
  EXPECT_DOUBLE_EQ(structure_share(100, 1000, 1.0, 0.45), 1.0);   // every fragment smooth
  EXPECT_DOUBLE_EQ(structure_share(100, 1000, 0.65, 1.0), 0.1);   // floor 1: off
  EXPECT_DOUBLE_EQ(structure_share(0, 0, 0.65, 0.45), 0.0);       // nothing clustered
}

// A well-constrained room seen through fewer normals than the evidence asks for keeps more
// points: its mu comes from too little structure to trust.
TEST(Degeneration, AWellConstrainedSceneWithLittleEvidenceGetsTheLenientEnd) {
  Config config = synthetic_config();
  const auto scan = test::render(config.sensor, box_room());
  const AmbientFilterResult trusted = filter(config, scan);
  ASSERT_TRUE(trusted.degeneration.valid);
  ASSERT_LE(trusted.mu, 0.3);

  config.ambient.mu_evidence_normals = 4 * trusted.degeneration.normals;
  const AmbientFilterResult doubted = filter(config, scan);
  EXPECT_EQ(doubted.degeneration.normals, trusted.degeneration.normals);
  EXPECT_NEAR(doubted.mu, 1.0 - (1.0 - trusted.mu) / 4.0, 1e-12);
  EXPECT_LT(doubted.beta0_deg, trusted.beta0_deg - 20.0);
}
