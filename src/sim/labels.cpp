#include "adaptive_lego_loam/sim/labels.h"

namespace adaptive_lego_loam::sim {

std::string class_name(SemanticClass semantic) {
  switch (semantic) {
    case SemanticClass::kUnlabeled:
      return "unlabeled";
    case SemanticClass::kCar:
      return "car";
    case SemanticClass::kPerson:
      return "person";
    case SemanticClass::kRoad:
      return "road";
    case SemanticClass::kSidewalk:
      return "sidewalk";
    case SemanticClass::kOtherGround:
      return "other-ground";
    case SemanticClass::kBuilding:
      return "building";
    case SemanticClass::kFence:
      return "fence";
    case SemanticClass::kOtherStructure:
      return "other-structure";
    case SemanticClass::kVegetation:
      return "vegetation";
    case SemanticClass::kTrunk:
      return "trunk";
    case SemanticClass::kTerrain:
      return "terrain";
    case SemanticClass::kPole:
      return "pole";
    case SemanticClass::kTrafficSign:
      return "traffic-sign";
    case SemanticClass::kOtherObject:
      return "other-object";
    case SemanticClass::kMovingCar:
      return "moving-car";
    case SemanticClass::kMovingPerson:
      return "moving-person";
  }
  return "class-" + std::to_string(static_cast<int>(semantic));
}

}  // namespace adaptive_lego_loam::sim
