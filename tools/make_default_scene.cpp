// Generates the editor's default scene (assets/): a small gingerbread-like creature and a rig that shows
// all three handle types -- bones (spine, arms, legs), point handles (ears, belly) and an open cage over
// the face.
//
// The surface is the zero set of a smooth union of capsules and spheres, extracted with marching
// tetrahedra on a regular grid (each cube split into 6 tets around its main diagonal, so neighbouring
// cubes agree on face diagonals and the result is a closed, edge-manifold surface), then relaxed a few
// times (move to the neighbour average, project back onto the implicit surface) to even out the
// sliver triangles marching tetrahedra makes (six passes; the generator refuses any triangle folded
// against the field gradient). Triangles are oriented along the field gradient (outward).
//
// Usage: make_default_scene OUT_DIR   -> OUT_DIR/default.{obj,tgf}, default-cage.obj,
//                                         default.scene.json + default.scene.bin
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/io.h"
#include "core/rig/rig_io.h"
#include "core/scene/document.h"
#include "core/util/error.h"

namespace {

using Eigen::Vector3d;

// ---- the creature as an implicit function (negative inside) ----------------------------------------

double sd_capsule(const Vector3d& p, const Vector3d& a, const Vector3d& b, double r) {
  const Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm() - r;
}
double sd_sphere(const Vector3d& p, const Vector3d& c, double r) { return (p - c).norm() - r; }
// An ellipsoid's approximate distance (exact sign, smooth; fine for an iso-surface).
double sd_ellipsoid(const Vector3d& p, const Vector3d& c, const Vector3d& r) {
  const Vector3d q = (p - c).cwiseQuotient(r);
  const double k0 = q.norm(), k1 = (p - c).cwiseQuotient(r.cwiseProduct(r)).norm();
  return k1 > 0 ? k0 * (k0 - 1.0) / k1 : -r.minCoeff();
}
// Polynomial smooth minimum (blend radius k).
double smin(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

double creature(const Vector3d& p) {
  const double k = 0.09;
  double d = sd_ellipsoid(p, {0, 0, 0}, {0.45, 0.55, 0.32});             // body
  d = smin(d, sd_sphere(p, {0, 0.86, 0}, 0.36), k);                     // head
  for (double s : {-1.0, 1.0}) {
    d = smin(d, sd_sphere(p, {s * 0.24, 1.17, 0}, 0.12), 0.06);         // ears
    d = smin(d, sd_capsule(p, {s * 0.3, 0.26, 0}, {s * 0.92, 0.06, 0}, 0.13), k);  // arms
    d = smin(d, sd_sphere(p, {s * 0.98, 0.04, 0}, 0.15), 0.06);         // hands
    d = smin(d, sd_capsule(p, {s * 0.2, -0.35, 0}, {s * 0.25, -1.02, 0}, 0.16), k);  // legs
    d = smin(d, sd_ellipsoid(p, {s * 0.26, -1.12, 0.07}, {0.17, 0.12, 0.22}), 0.06);  // feet
  }
  d = smin(d, sd_sphere(p, {0, 0.84, 0.35}, 0.06), 0.04);  // nose
  return d;
}

Vector3d gradient(const Vector3d& p) {
  const double h = 1e-5;
  Vector3d g;
  for (int i = 0; i < 3; ++i) {
    Vector3d e = Vector3d::Zero();
    e[i] = h;
    g[i] = (creature(p + e) - creature(p - e)) / (2 * h);
  }
  return g;
}

// Newton steps onto f = 0 along the gradient.
Vector3d project(Vector3d p) {
  for (int it = 0; it < 8; ++it) {
    const double f = creature(p);
    const Vector3d g = gradient(p);
    if (g.squaredNorm() < 1e-12) break;
    p -= f * g / g.squaredNorm();
    if (std::abs(f) < 1e-12) break;
  }
  return p;
}

// ---- marching tetrahedra ---------------------------------------------------------------------------

dfm::TriMesh marching_tets(const Vector3d& lo, const Vector3d& hi, double h) {
  const int nx = static_cast<int>(std::ceil((hi.x() - lo.x()) / h)) + 1;
  const int ny = static_cast<int>(std::ceil((hi.y() - lo.y()) / h)) + 1;
  const int nz = static_cast<int>(std::ceil((hi.z() - lo.z()) / h)) + 1;
  auto id = [&](int i, int j, int k) { return static_cast<long long>(i) + nx * (static_cast<long long>(j) + ny * k); };
  auto pos = [&](long long g) {
    const long long i = g % nx, j = (g / nx) % ny, k = g / (static_cast<long long>(nx) * ny);
    return Vector3d(lo.x() + i * h, lo.y() + j * h, lo.z() + k * h);
  };
  std::vector<double> f(static_cast<size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        double v = creature(pos(id(i, j, k)));
        if (v == 0) v = 1e-12;  // keep the surface off grid points: no degenerate triangles
        f[id(i, j, k)] = v;
      }

  std::vector<Vector3d> verts;
  std::vector<std::array<int, 3>> faces;
  std::unordered_map<long long, int> edge_vertex;  // grid edge (a * N + b, a < b) -> vertex
  const long long N = static_cast<long long>(nx) * ny * nz;
  auto vertex_on = [&](long long a, long long b) {
    if (a > b) std::swap(a, b);
    const long long key = a * N + b;
    auto it = edge_vertex.find(key);
    if (it != edge_vertex.end()) return it->second;
    const double fa = f[a], fb = f[b];
    const Vector3d p = pos(a) + (fa / (fa - fb)) * (pos(b) - pos(a));
    verts.push_back(p);
    edge_vertex[key] = static_cast<int>(verts.size()) - 1;
    return static_cast<int>(verts.size()) - 1;
  };
  // Cube corners: bit 0 = x, bit 1 = y, bit 2 = z. Six tets around the 0-7 diagonal.
  static const int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        long long c[8];
        for (int b = 0; b < 8; ++b) c[b] = id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
        for (const auto& t : kTets) {
          std::vector<long long> in, out;
          for (int q = 0; q < 4; ++q) (f[c[t[q]]] < 0 ? in : out).push_back(c[t[q]]);
          if (in.empty() || out.empty()) continue;
          if (in.size() == 1 || out.size() == 1) {
            const auto& one = in.size() == 1 ? in : out;
            const auto& three = in.size() == 1 ? out : in;
            faces.push_back({vertex_on(one[0], three[0]), vertex_on(one[0], three[1]), vertex_on(one[0], three[2])});
          } else {  // 2-2: a quad through the four crossing edges, in cyclic order
            const int a = vertex_on(in[0], out[0]), b = vertex_on(in[0], out[1]), cc = vertex_on(in[1], out[1]),
                      d = vertex_on(in[1], out[0]);
            faces.push_back({a, b, cc});
            faces.push_back({a, cc, d});
          }
        }
      }
  dfm::TriMesh m;
  m.V.resize(verts.size(), 3);
  for (size_t i = 0; i < verts.size(); ++i) m.V.row(i) = verts[i].transpose();
  m.F.resize(faces.size(), 3);
  for (size_t i = 0; i < faces.size(); ++i) m.F.row(i) << faces[i][0], faces[i][1], faces[i][2];
  return m;
}

// Orient every triangle consistently with its neighbours (breadth-first across shared edges), then
// flip everything if the enclosed volume comes out negative. Returns how many triangles then face
// against the field gradient (folded triangles; the generator insists on none).
int orient_outward(dfm::TriMesh& m) {
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  for (int t = 0; t < m.num_faces(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = m.F(t, e), b = m.F(t, (e + 1) % 3);
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  auto has_directed = [&](int t, int a, int b) {
    for (int e = 0; e < 3; ++e)
      if (m.F(t, e) == a && m.F(t, (e + 1) % 3) == b) return true;
    return false;
  };
  std::vector<char> done(m.num_faces(), 0);
  for (int seed = 0; seed < m.num_faces(); ++seed) {
    if (done[seed]) continue;
    done[seed] = 1;
    std::vector<int> queue{seed};
    while (!queue.empty()) {
      const int t = queue.back();
      queue.pop_back();
      for (int e = 0; e < 3; ++e) {
        const int a = m.F(t, e), b = m.F(t, (e + 1) % 3);
        for (int u : edge_faces[{std::min(a, b), std::max(a, b)}]) {
          if (u == t || done[u]) continue;
          if (has_directed(u, a, b)) std::swap(m.F(u, 1), m.F(u, 2));  // must run b -> a
          done[u] = 1;
          queue.push_back(u);
        }
      }
    }
  }
  double vol = 0;
  for (int t = 0; t < m.num_faces(); ++t) {
    const Vector3d a = m.V.row(m.F(t, 0)), b = m.V.row(m.F(t, 1)), c = m.V.row(m.F(t, 2));
    vol += a.dot(b.cross(c)) / 6.0;
  }
  if (vol < 0)
    for (int t = 0; t < m.num_faces(); ++t) std::swap(m.F(t, 1), m.F(t, 2));
  int against = 0;
  for (int t = 0; t < m.num_faces(); ++t) {
    const Vector3d a = m.V.row(m.F(t, 0)), b = m.V.row(m.F(t, 1)), c = m.V.row(m.F(t, 2));
    if ((b - a).cross(c - a).dot(gradient((a + b + c) / 3.0)) <= 0) ++against;
  }
  return against;
}

// Relax: each vertex moves halfway to its neighbours' average, then back onto the surface.
void relax(dfm::TriMesh& m, int iterations) {
  std::vector<std::vector<int>> nbr(m.num_vertices());
  for (int t = 0; t < m.num_faces(); ++t)
    for (int e = 0; e < 3; ++e) {
      nbr[m.F(t, e)].push_back(m.F(t, (e + 1) % 3));
      nbr[m.F(t, (e + 1) % 3)].push_back(m.F(t, e));
    }
  for (auto& n : nbr) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  for (int it = 0; it < iterations; ++it) {
    Eigen::MatrixXd next = m.V;
    for (int v = 0; v < m.num_vertices(); ++v) {
      Vector3d avg = Vector3d::Zero();
      for (int u : nbr[v]) avg += m.V.row(u).transpose();
      avg /= double(nbr[v].size());
      next.row(v) = project(0.5 * (m.V.row(v).transpose() + avg)).transpose();
    }
    m.V = next;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_default_scene OUT_DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path out = argv[1];
    std::filesystem::create_directories(out);

    dfm::TriMesh surface = marching_tets({-1.35, -1.4, -0.5}, {1.35, 1.4, 0.5}, 0.08);
    relax(surface, 6);
    const int folded = orient_outward(surface);
    if (folded > 0) throw dfm::Error(std::to_string(folded) + " folded triangles: adjust the grid or relaxation");

    // The rig: a spine (pelvis -> chest -> neck), two arms hanging off the chest, two legs off the
    // pelvis; three point handles (ears, belly); an open cage over the face.
    dfm::TgfData tgf;
    tgf.joints.resize(13, 3);
    tgf.joints << 0, -0.30, 0,     // 0 pelvis
        0, 0.30, 0,                // 1 chest
        0, 0.62, 0,                // 2 neck
        0.60, 0.15, 0,             // 3 left elbow
        0.90, 0.05, 0,             // 4 left wrist
        -0.60, 0.15, 0,            // 5 right elbow
        -0.90, 0.05, 0,            // 6 right wrist
        0.22, -0.68, 0,            // 7 left knee
        0.25, -1.00, 0,            // 8 left ankle
        -0.22, -0.68, 0,           // 9 right knee
        -0.25, -1.00, 0,           // 10 right ankle
        0.24, 1.18, 0,             // 11 left ear (point)
        -0.24, 1.18, 0;            // 12 right ear (point)
    const int bones[][2] = {{0, 1}, {1, 2}, {1, 3}, {3, 4}, {1, 5}, {5, 6}, {0, 7}, {7, 8}, {0, 9}, {9, 10}};
    tgf.edges.resize(10, 2);
    tgf.flags.resize(10, 3);
    for (int i = 0; i < 10; ++i) {
      tgf.edges.row(i) << bones[i][0], bones[i][1];
      tgf.flags.row(i) << 1, 0, 0;
    }
    dfm::Cage cage;
    cage.name = "face cage";
    cage.mesh.V.resize(5, 3);
    cage.mesh.V << 0, 0.84, 0.24,  // tip, behind the nose
        0.15, 0.84, 0.1, 0, 0.99, 0.1, -0.15, 0.84, 0.1, 0, 0.69, 0.1;
    cage.mesh.F.resize(4, 3);  // four faces of a pyramid without its base: an open (partial) cage
    cage.mesh.F << 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1;

    const std::string obj = (out / "default.obj").string(), tgf_path = (out / "default.tgf").string(),
                      cage_path = (out / "default-cage.obj").string();
    dfm::write_surface(obj, surface);
    dfm::write_tgf(tgf_path, tgf);
    dfm::write_surface(cage_path, cage.mesh);

    // The scene goes through the same Document calls the editor makes.
    dfm::Document doc;
    doc.set_surface(surface, "default.obj");
    doc.load_skeleton(tgf_path);
    doc.add_point({0, 0.0, 0.2}, "belly");
    doc.add_cage(cage);
    const char* bone_names[] = {"spine", "neck", "l_upper_arm", "l_forearm", "r_upper_arm",
                                "r_forearm", "l_thigh", "l_shin", "r_thigh", "r_shin"};
    const int np = static_cast<int>(doc.rig().points.size());
    doc.rename_handle(0, "l_ear");
    doc.rename_handle(1, "r_ear");
    for (int b = 0; b < 10; ++b) doc.rename_handle(np + b, bone_names[b]);
    dfm::Camera cam;
    cam.position = {0, 0.1, 4.6};
    cam.target = {0, 0, 0};
    doc.set_camera(cam);
    doc.set_selection({});
    // FAST stays off as in every other document (issue 38): the Posing panel turns it on when a handle
    // is made free or pinned, or by its checkbox.
    doc.save_scene((out / "default.scene.json").string());
    std::printf("default scene: %d vertices, %d faces, %d handles -> %s\n", surface.num_vertices(),
                surface.num_faces(), doc.num_handles(), (out / "default.scene.json").string().c_str());
    return 0;
  } catch (const dfm::Error& e) {
    std::fprintf(stderr, "make_default_scene: %s\n", e.what());
    return 1;
  }
}
