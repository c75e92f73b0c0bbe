#pragma once
// The generated adaptive_lego_loam/CloudInfo message, as adaptive_lego_loam::CloudInfoMsg.
//
// Message headers are generated into the package's namespace, where the core already declares
// its own struct CloudInfo (core/segmentation.h): including <adaptive_lego_loam/CloudInfo.h>
// next to the core does not compile. This header renames the message's typedef while it is
// included; the message type on the wire is still adaptive_lego_loam/CloudInfo. Include this
// header, never the generated one.

#include "adaptive_lego_loam/core/clustering/segmenter.h"

#define CloudInfo CloudInfoMsg
#include <adaptive_lego_loam/CloudInfo.h>
#undef CloudInfo
