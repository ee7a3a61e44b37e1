#pragma once
// The points a transition's field lives on (transition.h): each key's conforming surface and fill at
// its time, and the middle layers' lattice. Internal to core/anim/transition.cpp.
#include <functional>
#include <utility>

#include <Eigen/Core>

#include "core/anim/conforming_surface.h"
#include "core/anim/key_distance.h"
#include "core/mesh/mesh.h"

namespace dfm::transition_detail {

struct Box {
  Eigen::RowVector3d lo, hi;
};

// A 1-Lipschitz field evaluated at many points at once (rows of #P x 3).
using PointField = std::function<Eigen::VectorXd(const Eigen::MatrixXd&)>;

// Field values are kept at least this far from 0 (relative to the spacing), so that no crossing
// sits on a point and no piece of the level set is flat.
constexpr double kMinValue = 1e-4;
constexpr double kAway = 0.025;  // in the spacing of the points' layer

// |v| at least eps; positive values at least sqrt(2) eps, so that two clamped values never put a
// crossing halfway between layers (a round time a user scrubs to, where a slice would pass through
// the crossing itself).
double clamp_away_from_zero(double v, double eps);

// The middle layers' points: a body-centred cubic lattice of cube edge a (its Delaunay tetrahedra
// are congruent and well shaped, so the blend's zero set is cut cleanly) where g < band, and a
// coarse jittered grid of spacing 2a where g >= band. g is evaluated first on the coarse grid to
// find the cells the band may reach.
Eigen::MatrixXd lattice_band_points(const Box& box, double a, double band, const PointField& g);

// The origin of lattice_band_points' lattice: a cube corner.
Eigen::RowVector3d lattice_origin(const Box& box, double a);

// One key's points at its time: the conforming surface (anchored, just inside), its fill near the
// surface at the key's own spacing and farther out at the middle spacing, and the centroids that
// keep concavities from being bridged.
struct KeyLayer {
  ConformingSurface surface;
  Eigen::VectorXd fill_values;
  Eigen::Index banded = 0;  // fill points before the chord cover's
  int chords = 0;
};

// The key's points at its time: conforming surface, fill near it at h_key and farther at h_mid
// (`layer` seeds the jitter), its signed distances d. Throws dfm::Error when the key cannot be made
// conforming or the spacing is too fine for its size.
KeyLayer key_layer(const TriMesh& key, const SignedDistance& d, const Box& box, double h_key, double h_mid,
                   int max_rounds, int layer);

}  // namespace dfm::transition_detail
