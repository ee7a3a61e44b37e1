#pragma once
// Volume preservation for a space-time edit (Southern 2008, 4.2.2; issue 35): each time layer of a
// prism manifold the edit touches is a closed surface whose enclosed volume the edit should keep, as clay
// does. Layers are found through the manifold's PrismSlab records.
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"

namespace dfm {

struct EditLayer {
  Eigen::MatrixXi F;            // the layer's triangles on manifold vertex indices
  double volume = 0;            // enclosed volume before the edit
  std::vector<int> movable;     // region vertices of this layer the correction may move
  std::vector<double> weight;   // per movable vertex, >= 0
};

// The layers holding a vertex of `movable` (weights per movable vertex, same order). Throws dfm::Error
// when a movable vertex is on no prism layer, or a layer is not closed and oriented.
std::vector<EditLayer> edit_layers(const AnimationManifold& m, const std::vector<int>& movable,
                                   const std::vector<double>& weight);

// Enclosed volume of triangles F over the x, y, z of manifold vertex rows V.
double layer_volume(const MatrixX4dRow& V, const Eigen::MatrixXi& F);

// Moves each layer's movable vertices along weight * (the volume's gradient at the start) until the
// layer's volume is its original one again (Newton on that one offset, a few steps).
void restore_layer_volumes(const std::vector<EditLayer>& layers, MatrixX4dRow& V);

}  // namespace dfm
