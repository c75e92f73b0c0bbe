#pragma once
// Point labels as SemanticKITTI packs them: semantic class in the lower 16 bits, instance id in
// the upper 16 bits. Class ids are SemanticKITTI's.

#include <cstdint>
#include <string>

namespace adaptive_lego_loam::sim {

enum class SemanticClass : uint16_t {
  kUnlabeled = 0,
  kCar = 10,
  kPerson = 30,
  kRoad = 40,
  kSidewalk = 48,
  kOtherGround = 49,
  kBuilding = 50,
  kFence = 51,
  kOtherStructure = 52,
  kVegetation = 70,
  kTrunk = 71,
  kTerrain = 72,
  kPole = 80,
  kTrafficSign = 81,
  kOtherObject = 99,
  kMovingCar = 252,
  kMovingPerson = 254,
};

inline uint32_t pack_label(SemanticClass semantic, uint16_t instance) {
  return (static_cast<uint32_t>(instance) << 16) | static_cast<uint16_t>(semantic);
}
inline SemanticClass label_class(uint32_t label) {
  return static_cast<SemanticClass>(label & 0xFFFFu);
}
inline uint16_t label_instance(uint32_t label) {
  return static_cast<uint16_t>(label >> 16);
}

// Road, sidewalk, terrain and other ground (a floor): the classes a ground segmentation should
// find.
inline bool is_ground_class(SemanticClass semantic) {
  return semantic == SemanticClass::kRoad || semantic == SemanticClass::kSidewalk ||
         semantic == SemanticClass::kTerrain || semantic == SemanticClass::kOtherGround;
}

// Things that move during a drive: they do not constrain the sensor's own motion.
inline bool is_moving_class(SemanticClass semantic) {
  return semantic == SemanticClass::kMovingCar || semantic == SemanticClass::kMovingPerson;
}

// SemanticKITTI's name of the class, e.g. "moving-car".
std::string class_name(SemanticClass semantic);

}  // namespace adaptive_lego_loam::sim
