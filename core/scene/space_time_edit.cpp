#include "core/scene/space_time_edit.h"

#include <cmath>

#include "core/util/error.h"

namespace dfm {

bool SpaceTimeEdit::same_setup(const SpaceTimeEdit& o) const {
  return region.center == o.region.center && region.dabs == o.region.dabs && region.radius == o.region.radius && region.t0 == o.region.t0 &&
         region.t1 == o.region.t1 && handle.point == o.handle.point && handle.time == o.handle.time &&
         weights == o.weights && time_scale == o.time_scale && preserve_volume == o.preserve_volume;
}

bool SpaceTimeEdit::operator==(const SpaceTimeEdit& o) const {
  return same_setup(o) && move == o.move && rotation.coeffs() == o.rotation.coeffs() && retime == o.retime &&
         refine == o.refine;
}

void check_space_time_edit(const SpaceTimeEdit& e) {
  if (!e.region.center.allFinite() || !std::isfinite(e.region.radius) || !(e.region.radius > 0))
    throw Error("space-time edit: the region needs a finite centre and a positive radius");
  for (const Eigen::Vector3d& d : e.region.dabs)
    if (!d.allFinite()) throw Error("space-time edit: a brushed dab of the region is not finite");
  if (!std::isfinite(e.region.t0) || !std::isfinite(e.region.t1) || !(e.region.t0 < e.region.t1))
    throw Error("space-time edit: the time window needs T0 < T1");
  if (!e.handle.point.allFinite() || !std::isfinite(e.handle.time))
    throw Error("space-time edit: the handle is not finite");
  if (e.handle.time < e.region.t0 || e.handle.time > e.region.t1)
    throw Error("space-time edit: the handle's time " + std::to_string(e.handle.time) + " is outside the window [" +
                std::to_string(e.region.t0) + ", " + std::to_string(e.region.t1) + "]");
  if (!e.move.allFinite() || !std::isfinite(e.retime) || !e.rotation.coeffs().allFinite() || std::abs(e.rotation.norm() - 1) > 1e-9)
    throw Error("space-time edit: the move is not finite or the rotation not a unit quaternion");
  if (!std::isfinite(e.time_scale) || !(e.time_scale > 0))
    throw Error("space-time edit: the time scale must be positive");
}

}  // namespace dfm
