// Short-lived topology between middle layers (core/anim/layer_transients.h): on a Kuhn-triangulated
// grid, a flat ring closes (a handle appears) and its middle fills a moment later (it goes). The
// Euler characteristic of each layer's inside set is counted by brute force here: vertices - edges +
// triangles - tetrahedra of the full subcomplex on inside points.
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

#include <catch2/catch.hpp>

#include "core/anim/layer_transients.h"

using namespace dfm;

namespace {

constexpr int N = 9, NZ = 5;
int id(int i, int j, int k) { return (k * N + j) * N + i; }

// The grid's cubes, each split into six tetrahedra around its main diagonal (Kuhn).
MatrixX4iRow kuhn_tets() {
  std::vector<std::array<int, 4>> tets;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k + 1 < NZ; ++k)
    for (int j = 0; j + 1 < N; ++j)
      for (int i = 0; i + 1 < N; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<int, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          tets.push_back(t);
        }
  MatrixX4iRow K(static_cast<Eigen::Index>(tets.size()), 4);
  for (size_t t = 0; t < tets.size(); ++t)
    for (int c = 0; c < 4; ++c) K(static_cast<Eigen::Index>(t), c) = tets[t][c];
  return K;
}

int euler_of_inside(const MatrixX4iRow& K, const Eigen::VectorXd& values) {
  std::set<std::vector<int>> cells[4];
  for (Eigen::Index t = 0; t < K.rows(); ++t)
    for (int mask = 1; mask < 16; ++mask) {
      std::vector<int> c;
      for (int b = 0; b < 4; ++b)
        if (mask & (1 << b)) c.push_back(K(t, b));
      if (std::all_of(c.begin(), c.end(), [&](int v) { return values[v] < 0; })) {
        std::sort(c.begin(), c.end());
        cells[c.size() - 1].insert(c);
      }
    }
  return static_cast<int>(cells[0].size()) - static_cast<int>(cells[1].size()) + static_cast<int>(cells[2].size()) -
         static_cast<int>(cells[3].size());
}

struct Ring {
  Eigen::MatrixXd X = Eigen::MatrixXd(N * N * NZ, 3);
  MatrixX4iRow K = kuhn_tets();
  std::vector<double> u;
  std::vector<Eigen::VectorXd> values;
  int gap = id(4, 2, 2), centre = id(4, 4, 2);

  // A 5 x 5 square ring at z = 2 (inside from the start) but for `gap`, which joins at 0.31; the 3 x 3
  // middle joins from 0.33, its centre at `centre_time`. Layers every 0.1 from 0.05.
  explicit Ring(double centre_time) {
    std::vector<double> join(X.rows(), 10.0);  // never
    for (int k = 0; k < NZ; ++k)
      for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
          X.row(id(i, j, k)) << i, j, k;
          if (k != 2 || i < 2 || i > 6 || j < 2 || j > 6) continue;
          const bool border = i == 2 || i == 6 || j == 2 || j == 6;
          join[id(i, j, k)] = border ? -1.0 : 0.33 + 0.004 * ((i - 3) * 3 + (j - 3));
        }
    join[gap] = 0.31;
    join[centre] = centre_time;
    for (int l = 0; l < 10; ++l) {
      u.push_back(0.05 + 0.1 * l);
      Eigen::VectorXd v(X.rows());
      for (Eigen::Index p = 0; p < X.rows(); ++p) v[p] = join[p] > 5 ? 1.0 : join[p] - u.back();
      values.push_back(v);
    }
  }
  std::vector<int> eulers() const {
    std::vector<int> e;
    for (const Eigen::VectorXd& v : values) e.push_back(euler_of_inside(K, v));
    return e;
  }
};

}  // namespace

TEST_CASE("layer transients: a ring that closes and fills within a layer interval or so happens at once", "[transition]") {
  Ring r(0.37);
  REQUIRE(r.eulers() == std::vector<int>{1, 1, 1, 0, 1, 1, 1, 1, 1, 1});  // the handle at layer 0.35 only
  const std::vector<Eigen::VectorXd> before = r.values;
  LayerTransientOptions o;
  o.radius = 2.5;  // the gap and the centre are 2 apart
  o.max_life = 0.2;
  const LayerTransientStats st = merge_layer_transients(r.X, r.K, r.u, r.values, 1e-3, o);
  CHECK(st.events == 1);
  CHECK(r.eulers() == std::vector<int>{1, 1, 1, 1, 1, 1, 1, 1, 1, 1});
  // The gap and the middle (all within 2.5 of the gap or the centre) now cross at the gap's 0.31,
  // between layers 0.25 and 0.35, at one rate; every other value is as it was, bit for bit.
  int moved = 0;
  for (Eigen::Index p = 0; p < r.X.rows(); ++p) {
    const bool middle = r.X(p, 2) == 2 && r.X(p, 0) >= 3 && r.X(p, 0) <= 5 && r.X(p, 1) >= 3 && r.X(p, 1) <= 5;
    if (!(middle || p == r.gap)) {
      for (size_t l = 0; l < r.u.size(); ++l) CHECK(r.values[l][p] == before[l][p]);
      continue;
    }
    ++moved;
    const double a = r.values[2][p], b = r.values[3][p];
    CHECK(a > 0);
    CHECK(b < 0);
    CHECK(0.25 + 0.1 * a / (a - b) == Approx(0.31).margin(1e-12));
    CHECK(b - a == Approx(r.values[3][r.gap] - r.values[2][r.gap]).margin(1e-12));
  }
  CHECK(moved == 10);
  CHECK(st.moved == moved);
}

TEST_CASE("layer transients: a handle that lives on, or changes too far apart, stay", "[transition]") {
  for (const double centre_time : {0.37, 0.75}) {
    Ring r(centre_time);
    const std::vector<Eigen::VectorXd> before = r.values;
    LayerTransientOptions o;
    o.radius = centre_time < 0.5 ? 1.5 : 2.5;  // too near, or too long a life for 0.2
    o.max_life = 0.2;
    const LayerTransientStats st = merge_layer_transients(r.X, r.K, r.u, r.values, 1e-3, o);
    CHECK(st.events == 0);
    for (size_t l = 0; l < r.u.size(); ++l) CHECK(r.values[l] == before[l]);
  }
}

TEST_CASE("layer transients: the points whose crossings make a short-lived event", "[transition]") {
  Ring r(0.37);
  LayerTransientOptions o;
  o.radius = 2.5;
  o.max_life = 0.2;
  // The handle appears where the gap joins and goes where the centre, the middle's last point, does.
  CHECK(layer_transient_points(r.X, r.K, r.u, r.values, o) == std::vector<int>{r.gap, r.centre});
  o.max_life = 0.05;  // it lives 0.06: not short-lived
  CHECK(layer_transient_points(r.X, r.K, r.u, r.values, o).empty());
}
