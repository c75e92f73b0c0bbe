// The four stages as nodelets (nodelet_plugins.xml), for one process that passes clouds between
// them by pointer: launch/nodes.launch nodelets:=true.

#include <pluginlib/class_list_macros.hpp>

#include "feature_association.h"
#include "graph_nodelet.h"
#include "image_projection.h"
#include "map_optimization.h"
#include "transform_fusion.h"

namespace adaptive_lego_loam::nodes {
using ImageProjection = GraphNodelet<ImageProjectionNode>;
using FeatureAssociation = GraphNodelet<FeatureAssociationNode>;
using MapOptimization = GraphNodelet<MapOptimizationNode>;
using TransformFusion = GraphNodelet<TransformFusionNode>;
}  // namespace adaptive_lego_loam::nodes

PLUGINLIB_EXPORT_CLASS(adaptive_lego_loam::nodes::ImageProjection, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_lego_loam::nodes::FeatureAssociation, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_lego_loam::nodes::MapOptimization, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_lego_loam::nodes::TransformFusion, nodelet::Nodelet)
