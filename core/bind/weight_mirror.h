#pragma once
// Mirror weights across a plane (Blender's "Mirror Vertex Group"): a vertex takes the weights at its
// reflection, read from the surface there, with every handle's column swapped for its mirror handle's.
//
// Vertices: the reflection of vertex i is located on the surface (closest point within
// tolerance * bounding-box diagonal; SurfaceLocator) and its weights are the barycentric blend of that
// triangle's rows: on a mirror-symmetric mesh that is the mirror vertex's row exactly, on a nearly
// symmetric one (a sculpted or remeshed model) an interpolation instead of a nearest-vertex jump. A
// blend of rows in [0, 1] summing to 1 stays so (Jacobson 2013, Eq. 4.5-4.6), columns swapped too.
// A vertex whose reflection is farther than the tolerance keeps its weights (counted).
//
// Handles (mirror_handles): by name first, with the usual left/right conventions (l_arm / r_arm,
// arm.L / arm.R, arm_l, and the words left / Left / LEFT / right as a whole word: "LeftEye", "upper
// right arm"), between handles of one kind;
// else by geometry: the handle whose pivot (point, cage vertex, region centroid; a bone: both joints)
// is the reflection of this one's, mutually nearest within the tolerance. A handle on the plane is its
// own mirror; one that finds none is its own mirror too, as in Blender, and is reported.
#include <vector>

#include <Eigen/Core>

#include "core/rig/rig.h"

namespace dfm {

enum class MirrorMode {
  PositiveToNegative,  // the side where normal . x > offset is copied onto the other
  NegativeToPositive,
  Flip,                // both sides swap (applying it twice gives the weights back on a symmetric mesh)
};

struct MirrorOptions {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // the plane normal . x = offset (normalized here)
  double offset = 0;
  MirrorMode mode = MirrorMode::PositiveToNegative;
  double tolerance = 0.01;  // times the surface's bounding-box diagonal
};

struct MirrorReport {
  std::vector<int> handle_mirror;      // per handle, its mirror handle
  std::vector<int> unmatched_handles;  // off the plane but without a mirror (their own columns were used)
  int vertices_changed = 0;
  int vertices_unmatched = 0;          // reflection farther than the tolerance from the surface: kept
};

// The name of the other side ("l_arm" -> "r_arm", "Arm.L" -> "Arm.R", "LeftEye" -> "RightEye"), or ""
// when the name follows no left/right convention ("spine", "bright").
std::string mirrored_name(const std::string& name);

// Per handle (rig.h order), its mirror handle. V: the surface (region centroids). tol: absolute.
std::vector<int> mirror_handles(const Rig& rig, const Eigen::MatrixXd& V, const Eigen::Vector3d& normal,
                                double offset, double tol, std::vector<int>* unmatched = nullptr);

// W: #V x #handles on the surface (V, F); `fixed` rows (#V flags or empty: the bind's constrained
// vertices) are kept bit for bit. In the copy modes, vertices within 1e-6 of the diagonal from the
// plane take the mean of their row and its mirror (symmetric afterwards); the source side is untouched.
// Throws dfm::Error for a zero normal, a negative tolerance or mismatched sizes.
Eigen::MatrixXd mirror_weights(const Eigen::MatrixXd& W, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                               const Rig& rig, const std::vector<bool>& fixed, const MirrorOptions& opts,
                               MirrorReport* report = nullptr);

}  // namespace dfm
