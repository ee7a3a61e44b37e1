#pragma once
// A curve through which a bone's STBS endpoint weights pass (Jacobson 2013, Fig. 6.9: "filtered through a
// spline curve to adjust their effect interactively", e.g. to concentrate a torso's twist in the
// abdomen). The curve runs from (0, 0) to (1, 1) through the user's points, a monotone cubic Hermite
// spline (Fritsch and Carlson 1980): it is C1, passes through every point, and never leaves [0, 1] or
// turns back, so filtered weights keep 6.2.2's properties (0 at the first joint, 1 at the second,
// bounded, increasing along the bone).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace dfm {

// Interior points (x strictly increasing in (0, 1), y nondecreasing in [0, 1]); empty = the identity.
using EndpointFilter = std::vector<Eigen::Vector2d>;

// Throws dfm::Error naming `what` and the problem when the points are not as above.
void check_endpoint_filter(const EndpointFilter& f, const std::string& what);

// The curve at e (clamped to [0, 1]).
double filter_endpoint(const EndpointFilter& f, double e);

// E: #V x #bones endpoint weights; filters: one per bone or fewer (the rest the identity).
Eigen::MatrixXd filter_endpoints(const Eigen::MatrixXd& E, const std::vector<EndpointFilter>& filters);

}  // namespace dfm
