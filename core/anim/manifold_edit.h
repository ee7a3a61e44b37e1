#pragma once
// Laplacian editing of an animation manifold (Southern 2008, 4.3; issue 35): drag a handle and the
// region of interest follows, smoothly in space and in time, while the anchors (the region's boundary
// ring, core/anim/manifold_edit_region.h) and everything outside the region stay put.
//
// Unknowns are displacements d of the free region vertices (region minus handle); the anchors' d = 0 and
// the handle's d is the drag, both hard constraints. Over the rows of every region vertex, d minimises
//   sum_i | (L d)_i - (R_i - I) delta_i |^2                                        (4.2, in x, y, z)
// with L the manifold Laplacian of manifold_laplacian.h (4D one-rings, 4.6.1's reciprocal-length
// weights) and delta_i the original differential coordinates. By default vertices keep their t (edits
// move shape, not timing), so only x, y, z are solved: L t' = delta^t holds already. A drag's retime
// moves the handle in t as well: t is solved like x, y, z with its details unchanged, which is the reach
// field s times the retime (core/anim/manifold_retime.h says which retimes are refused).
//
// With LaplacianWeights::Dual the rows are the dual graph Laplacian's (Au et al. 2006), one per
// tetrahedron with a region vertex, with 4.4.2's ghost boundary condition (core/anim/dual_laplacian.h);
// everything else is the same least-squares system.
//
// Transformation invariance (4.2.1): R_i rotates vertex i's detail. A drag's rotation about the handle
// point spreads over the region by the reach field s (the same least-squares system with the handle at 1
// and the anchors at 0): R_i turns by s_i times the handle's angle about its axis, so details turn with
// the drag instead of shearing. (4.6.1's iterative restore() of the details after a translation-only
// drag, Au et al. 2006, is not built: a translation leaves the details unturned.)
//
// Volume (4.2.2): with preserve_volume, each layer of the region (a prism manifold's time layer, a closed
// surface) gets its enclosed volume back by moving its free vertices along the volume gradient, weighted
// by 4 s (1 - s) so the anchors and the handle stay where they are.
//
// 4.6.1's structure: the constructor is initialise (one factorisation of L_F^T L_F per region), drag is
// a back substitution (three right-hand sides, x, y, z). A drag without a turn or volume preservation
// needs none: its details are unchanged (b = 0) and every handle vertex moves by the translation, so
// the solve is linear in it, d_F = reach_F translation^T (the reach's system, solved at initialise).
// It equals the back substitution up to rounding (tests/test_manifold_edit.cpp bounds the difference).
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/anim/manifold_edit_region.h"
#include "core/anim/manifold_laplacian.h"

namespace dfm {

struct ManifoldEditOptions {
  LaplacianWeights weights = LaplacianWeights::Reciprocal;  // 4.6.1's schemes (manifold_laplacian.h)
  // t's factor in the weights' edge lengths (manifold_laplacian.h). On the keyed arm (times 0..2, 1.5
  // units long) 10 lets a turned wrist handle carry the fingers, 1 leaves them behind.
  double time_scale = 1.0;
  bool turn_details = true;     // 4.2.1: rotate the differential coordinates with the handle (false:
                                // translation-only Laplacian editing, which shears details; for comparison)
  bool preserve_volume = false;  // 4.2.2: keep each region layer's enclosed volume
  // A drag with no turn and no volume preservation moves the free vertices by the reach times the
  // translation instead of a back substitution (false: always the back substitution; for comparison).
  bool linear_translation = true;
};

struct ManifoldDrag {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // about the handle point, before translating
  // The handle's move in t (issue 35's retime; 0 keeps every t bit for bit). The region follows by its
  // reach. Refused (dfm::Error) where the region touches the first or last layer or a transition, or
  // where a prism's time edge would stop rising (the slab would fold back in time). The caller then
  // calls merge_retimed_slabs (manifold_retime.h) on the manifold holding the result.
  double retime = 0;
};

class ManifoldEditor {
 public:
  // Initialise: Laplacian rows, reach field and factorisation. `pivot` is the handle point the drag's
  // rotation turns about. Throws dfm::Error when the region's system is singular, or with
  // preserve_volume when a region vertex is on no closed prism layer.
  ManifoldEditor(const AnimationManifold& m, EditRegion selection, const Eigen::Vector3d& pivot,
                 ManifoldEditOptions options = {});
  ~ManifoldEditor();
  ManifoldEditor(const ManifoldEditor&) = delete;
  ManifoldEditor& operator=(const ManifoldEditor&) = delete;

  // The manifold's vertices after the drag (#V x 4; rows outside the region are the original rows,
  // t is changed only by a retime). A handle vertex v lands at v + translation (exactly) when rotation is the
  // identity, else at rotation (v - pivot) + pivot + translation. Throws dfm::Error (nothing changed) for
  // a non-finite drag or a rotation that is not orthonormal with determinant 1.
  MatrixX4dRow drag(const ManifoldDrag& drag) const;
  // drag() written into V (#V x 4), whose rows outside the region must be the rows the editor was
  // initialised on; its region rows may hold anything (an earlier drag's). Writes only the region rows,
  // so a frame costs the region, not the manifold. Throws as drag() does, with V unchanged outside the
  // region and the region rows the original ones (a refused retime) or untouched (anything else).
  void drag_onto(const ManifoldDrag& drag, MatrixX4dRow& V) const;

  const EditRegion& selection() const;
  // The reach field s per region vertex (selection().region order): 1 on the handle, 0 at the anchors.
  const Eigen::VectorXd& reach() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dfm
