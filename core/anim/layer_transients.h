#pragma once
// Short-lived topology between a transition's middle layers (issue 30). Where the blend is nearly
// flat, as when the air gap between two parts closes, the lattice reads handles that appear and
// vanish within a layer interval or two: bridges form here and there, the pockets between them fill
// a moment later. The slices around them show slits that neither key has. (Southern 2008 meets the
// same kind of spurious holes and bumps in concave regions, 8.5.3, and moves them in time: 8.6 pushes
// the skeleton's vertices to another time, so that holes close at once. Here the field's own
// short-lived features are moved to where they start.)
//
// Each lattice point's field is linear in time, so its sign changes at most once, and the layers'
// inside sets form a sweep: points join or leave one at a time, in the order of their crossing times.
// A point joining changes the inside set's Euler characteristic by 1 - chi(L), leaving by chi(L) - 1,
// L the part of its link (the faces of its star in K opposite it) on inside points (the lower-star
// formula for a full subcomplex; the region F < 0 retracts onto it). A change followed within
// `max_life` by the opposite change within `radius` is a short-lived feature. Features whose changes
// lie within `radius` of each other form one event, and the crossings near its changes (within
// `radius`) between its first and last change all move to its first change, at one rate (the
// median of theirs), so that the staircase's 4-simplices among them cross exactly there. The event
// then happens at once, where it starts.
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"

namespace dfm {

struct LayerTransientOptions {
  double radius = 0;    // how near two changes lie to belong together; the reach of a move
  double max_life = 0;  // in u: longest life of a feature that is merged
};

struct LayerTransientStats {
  int events = 0;  // merged events (each one or more short-lived features)
  int moved = 0;   // crossings moved to their event's start
};

// values[k]: the field at points X (#X x 3) at time u[k] (ascending), every value nonzero; K the
// points' tetrahedralization (its links spheres inside). A moved point's values at the layers from
// the last before its event's start to the first after its end become +-rate * (u[k] - start), kept
// `away` from zero as the transition clamps (transition_points.h); its other layers keep theirs,
// which have the same signs.
// The points (rows of X) whose crossings change the topology in the events merge_layer_transients
// would merge, ascending, each once.
std::vector<int> layer_transient_points(const Eigen::MatrixXd& X, const MatrixX4iRow& K, const std::vector<double>& u,
                                        const std::vector<Eigen::VectorXd>& values, const LayerTransientOptions& o);

LayerTransientStats merge_layer_transients(const Eigen::MatrixXd& X, const MatrixX4iRow& K, const std::vector<double>& u,
                                           std::vector<Eigen::VectorXd>& values, double away,
                                           const LayerTransientOptions& o);

}  // namespace dfm
