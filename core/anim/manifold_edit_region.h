#pragma once
// Which vertices a space-time edit of an animation manifold moves (Southern 2008, 4.3; issue 35):
// the region of interest, the anchors that hold it in place, and the handle the user drags.
//
// Rules (manifold vertices, 0-based, sorted):
// - Region: |xyz - center| <= radius, or |xyz - dab| <= radius for one of the dabs (a region brushed in
//   several strokes of the same radius), and the vertex's whole star (every tetrahedron around it) has its
//   times in [t0, t1]. The star rule is what keeps the motion outside the window untouched: a slice at a
//   time outside [t0, t1] only cuts tetrahedra with a vertex outside the window, which hold no region
//   vertex, so those slices are unchanged bit for bit. (On a prism manifold a layer vertex is in the
//   window when the layers before and after it are.)
// - Anchors: vertices sharing a tetrahedron edge with a region vertex but outside it (the region's
//   boundary ring, 4.2: fixed rows of the system); they keep their positions.
// - Handle: region vertices with |xyz - point| <= radius / 4 lying on the layer times that bracket
//   `time`: t == time, or t == times[i] or times[i + 1] for the slab with times[i] < time < times[i + 1].
//   So a handle at a layer's time is that layer's vertices, and between layers both neighbours, which
//   makes the frame at `time` carry the handle exactly where it is dragged.
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"

namespace dfm {

struct EditRegionSpec {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;
  double t0 = 0, t1 = 0;
  std::vector<Eigen::Vector3d> dabs;  // more ball centres of the same radius (a brushed region)
};

struct EditHandleSpec {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double time = 0;
};

struct EditRegion {
  std::vector<int> region, anchors, handle;
};

// Throws dfm::Error (nothing selected) for: a radius that is not positive and finite, t0 >= t1, a
// window outside the animation, a region with no vertex, a region without anchors (it covers a whole
// piece of the manifold, so nothing holds it), a handle time outside the window, or a handle with no
// region vertex.
EditRegion select_edit_region(const AnimationManifold& m, const EditRegionSpec& region, const EditHandleSpec& handle);

// Whether p lies in the region's balls (the centre's or a dab's), ignoring time.
bool in_region_balls(const EditRegionSpec& region, const Eigen::Vector3d& p);

// The anchors of an arbitrary vertex set (a painted selection): the rule above. `region` sorted.
std::vector<int> region_anchors(const AnimationManifold& m, const std::vector<int>& region);

}  // namespace dfm
