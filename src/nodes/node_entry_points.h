#pragma once
// main() of each stage's node, defined next to its class: the generated node mains include only
// this, not the classes' ROS and PCL headers.

namespace adaptive_lego_loam::nodes {

int run_image_projection(int argc, char** argv);
int run_feature_association(int argc, char** argv);
int run_map_optimization(int argc, char** argv);
int run_transform_fusion(int argc, char** argv);

}  // namespace adaptive_lego_loam::nodes
