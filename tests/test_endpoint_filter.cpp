// The endpoint weights' filter curve (core/skin/endpoint_filter.h; Jacobson 2013, Fig. 6.9): through
// (0, 0), the user's points and (1, 1), monotone, within [0, 1], C1; the identity on the diagonal;
// malformed points refused by name.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/skin/endpoint_filter.h"
#include "core/util/error.h"

using namespace dfm;

TEST_CASE("endpoint filter: through its points, monotone, bounded, C1; the diagonal is the identity", "[skin][stbs]") {
  const std::vector<EndpointFilter> filters = {
      {{0.5, 0.1}}, {{0.3, 0.6}, {0.7, 0.9}}, {{0.1, 0.0}, {0.2, 0.9}, {0.3, 0.95}}, {{0.4, 0.4}, {0.5, 0.4}, {0.9, 1.0}}};
  for (const EndpointFilter& f : filters) {
    CHECK(filter_endpoint(f, 0) == 0);
    CHECK(filter_endpoint(f, 1) == 1);
    for (const Eigen::Vector2d& p : f) CHECK(filter_endpoint(f, p.x()) == Approx(p.y()).margin(1e-15));
    double prev = 0;
    for (int i = 0; i <= 2000; ++i) {
      const double y = filter_endpoint(f, i / 2000.0);
      CHECK(y >= prev - 1e-15);
      CHECK(y >= 0);
      CHECK(y <= 1);
      prev = y;
    }
    // C1 at each interior point: the slopes from either side agree.
    for (const Eigen::Vector2d& p : f) {
      const double h = 1e-7;  // one-sided slopes differ by about h times the second derivative (up to ~300 here)
      const double left = (filter_endpoint(f, p.x()) - filter_endpoint(f, p.x() - h)) / h;
      const double right = (filter_endpoint(f, p.x() + h) - filter_endpoint(f, p.x())) / h;
      CHECK(left == Approx(right).margin(1e-4));
    }
  }
  for (int i = 0; i <= 100; ++i) CHECK(filter_endpoint({{0.25, 0.25}, {0.6, 0.6}}, i / 100.0) == Approx(i / 100.0).margin(1e-15));
  CHECK(filter_endpoint({}, 0.3) == 0.3);
  CHECK(filter_endpoint({{0.5, 0.1}}, 1.7) == 1);  // clamped

  Eigen::MatrixXd E(2, 2);
  E << 0.5, 0.5, 0.25, 1;
  const Eigen::MatrixXd G = filter_endpoints(E, {{{0.5, 0.1}}});  // the second bone: none
  CHECK(G(0, 0) == Approx(0.1).margin(1e-15));
  CHECK(G.col(1) == E.col(1));

  CHECK_THROWS_WITH(check_endpoint_filter({{0.5, 0.1}, {0.4, 0.2}}, "f"), Catch::Contains("f: point 2") && Catch::Contains("increase"));
  CHECK_THROWS_WITH(check_endpoint_filter({{0.5, 0.6}, {0.7, 0.2}}, "f"), Catch::Contains("must not decrease"));
  CHECK_THROWS_WITH(check_endpoint_filter({{1.0, 0.6}}, "f"), Catch::Contains("inside (0, 1)"));
  CHECK_THROWS_WITH(check_endpoint_filter({{0.5, NAN}}, "f"), Catch::Contains("not finite"));
}
