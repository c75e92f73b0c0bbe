// graph_manager: a nodelet manager that loads the graph's stages into itself. `~stages` names
// them (image_projection feature_association map_optimization transform_fusion, or a part), each
// loaded as /<stage> with the manager's remappings, as `nodelet load` would, but without a loader
// process per stage. It is a full nodelet manager: a driver's nodelet can be loaded into it too.

#include <nodelet/loader.h>
#include <ros/ros.h>

#include <array>
#include <cstddef>
#include <exception>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

constexpr std::array<std::pair<const char*, const char*>, 4> kStageClasses{{
    {"image_projection", "adaptive_lego_loam/ImageProjection"},
    {"feature_association", "adaptive_lego_loam/FeatureAssociation"},
    {"map_optimization", "adaptive_lego_loam/MapOptimization"},
    {"transform_fusion", "adaptive_lego_loam/TransformFusion"},
}};

const char* nodelet_class(const std::string& stage) {
  for (const auto& [name, nodelet_type] : kStageClasses)
    if (stage == name) return nodelet_type;
  return nullptr;
}

std::vector<std::string> split_words(const std::string& text) {
  std::istringstream stream(text);
  std::vector<std::string> words;
  for (std::string word; stream >> word;)
    words.push_back(word);
  return words;
}

// "a, b, c or d": the stage names of kStageClasses, for error messages.
std::string stage_names() {
  std::string names;
  for (std::size_t i = 0; i < kStageClasses.size(); ++i) {
    if (i > 0) names += i + 1 < kStageClasses.size() ? ", " : " or ";
    names += kStageClasses[i].first;
  }
  return names;
}

bool known_stages(const std::vector<std::string>& stages) {
  for (const std::string& stage : stages) {
    if (nodelet_class(stage) != nullptr) continue;
    ROS_FATAL("%s: ~stages: unknown stage '%s' (expected %s)", ros::this_node::getName().c_str(),
              stage.c_str(), stage_names().c_str());
    return false;
  }
  return true;
}

bool load_stage(nodelet::Loader& loader, const std::string& stage) {
  const char* type = nodelet_class(stage);
  try {
    if (loader.load(ros::names::resolve(stage), type, ros::names::getRemappings(), {})) return true;
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s: %s", ros::this_node::getName().c_str(), stage.c_str(), e.what());
  }
  ROS_FATAL("%s: could not load %s (%s)", ros::this_node::getName().c_str(), stage.c_str(), type);
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "graph_manager");
  nodelet::Loader loader;  // with the manager's services, like `nodelet manager`
  const std::vector<std::string> stages = split_words(ros::param::param("~stages", std::string()));
  if (stages.empty()) {
    ROS_FATAL(
        "%s: ~stages is empty: name the stages to load (e.g. \"image_projection "
        "feature_association\")",
        ros::this_node::getName().c_str());
    return 1;
  }
  if (!known_stages(stages)) return 1;
  for (const std::string& stage : stages)
    if (!load_stage(loader, stage)) return 1;
  ros::spin();
  return 0;
}
