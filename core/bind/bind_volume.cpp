#include "core/bind/bind_volume.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <set>

#include "core/bind/closest_surface_point.h"
#include "core/bind/fem.h"
#include "core/bind/handle_geometry.h"
#include "core/bind/outside_handles.h"
#include "core/bind/rigid_pieces.h"
#include "core/bind/robust_volume.h"
#include "core/bind/tet_face_adjacency.h"
#include "core/bind/tetrahedralize.h"
#include "core/bind/winding_bvh.h"
#include "core/mesh/io_formats.h"
#include "core/util/error.h"

namespace dfm {
namespace {

using Clock = std::chrono::steady_clock;

double bbox_diagonal(const Eigen::MatrixXd& V) {
  if (V.rows() == 0) return 0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

void check_rig(const Rig& rig) {
  for (int i = 0; i < num_point_handles(rig); ++i)
    if (!rig.points[i].position.allFinite()) throw Error("point handle " + handle_name(rig, i) + " is not finite");
  if (!rig.skeleton.joints.allFinite()) throw Error("skeleton joints are not finite");
  for (const Cage& c : rig.cages)
    if (!c.mesh.V.allFinite()) throw Error("cage " + c.name + " has non-finite vertices");
}

// Everything handle-related that both surface paths share: PLC points and where each sample went.
struct HandlePlc {
  PointWelder points;
  std::vector<HandleSample> samples;
  std::vector<int> sample_point;  // sample -> row of points
  CageSoup cages;
  Eigen::MatrixXi cage_F, cage_E;  // into points
  explicit HandlePlc(double tol) : points(tol) {}
};

// The handle constraints on a finished (compacted) tet mesh. plc_to_tet maps PLC points to tet
// vertices (-1: not in the volume). Throws naming the first handle that is not in the volume.
void constrain(const Rig& rig, const HandlePlc& plc, const Eigen::VectorXi& plc_to_tet,
               const Eigen::VectorXi& user_to_plc, double tol, BindVolume& vol) {
  const int nh = num_handles(rig);
  BoundaryRows rows;
  std::vector<int> hits(nh, 0);
  for (size_t s = 0; s < plc.samples.size(); ++s) {
    const HandleSample& hs = plc.samples[s];
    const int v = plc_to_tet(plc.sample_point[s]);
    if (v < 0) {
      if (hs.required)
        throw Error(std::string(handle_kind_name(handle_ref(rig, hs.handle).kind)) + " handle \"" +
                    handle_name(rig, hs.handle) + "\" lies outside the volume (the surface and closed cages)");
      continue;
    }
    rows.add(v, hs.w);
    ++hits[hs.handle];
  }
  for (int i = 0; i < static_cast<int>(rig.regions.size()); ++i) {
    const int h = handle_index(rig, {HandleKind::Region, i});
    for (int u : rig.regions[i].vertices) {
      if (u < 0 || u >= user_to_plc.size())
        throw Error("region \"" + handle_name(rig, h) + "\": vertex " + std::to_string(u) + " out of range");
      const int v = plc_to_tet(user_to_plc(u));
      if (v >= 0) rows.add(v, {{h, 1.0}}), ++hits[h];
    }
  }
  for (int h = 0; h < nh; ++h)
    if (!hits[h])
      throw Error(std::string(handle_kind_name(handle_ref(rig, h).kind)) + " handle \"" + handle_name(rig, h) +
                  "\" has no vertex inside the volume (it lies outside the surface and closed cages)");
  add_cage_surface_rows(vol.tets.V, plc.cages, tol, rows);
  rows.finish(nh, vol.b, vol.bc);
}

void check_surface(const TriMesh& surface) {
  const int nu = surface.num_vertices();
  if (nu == 0 || surface.num_faces() == 0) throw Error("bind: the surface has no faces");
  if (surface.F.cols() != 3 || surface.V.cols() != 3) throw Error("bind: the surface must be a triangle mesh");
  if (!surface.V.allFinite()) throw Error("bind: the surface has non-finite vertex coordinates");
  if (surface.F.minCoeff() < 0 || surface.F.maxCoeff() >= nu) throw Error("bind: a face index is out of range");
}

// The PLC points: the welded surface's vertices first (unchanged), then the handles' samples and the
// cages' vertices, welded within tol; the cages' facets and edges renumbered into them.
HandlePlc handle_plc(const WeldedSurface& ws, const Rig& rig, const CageSoup& cages, double tol) {
  HandlePlc plc(tol);
  for (int i = 0; i < ws.V.rows(); ++i) plc.points.insert(ws.V.row(i).transpose());
  plc.samples = sample_handles(rig, mean_edge_length(ws.V, ws.F));
  for (const HandleSample& s : plc.samples) plc.sample_point.push_back(plc.points.add(s.x));
  plc.cages = cages;
  std::vector<int> cage_point(cages.V.rows());
  for (int i = 0; i < cages.V.rows(); ++i) cage_point[i] = plc.points.add(cages.V.row(i).transpose());
  plc.cage_F.resize(cages.F.rows(), 3);
  for (int f = 0; f < cages.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) plc.cage_F(f, k) = cage_point[cages.F(f, k)];
  plc.cage_E.resize(cages.E.rows(), 2);
  for (int e = 0; e < cages.E.rows(); ++e)
    for (int k = 0; k < 2; ++k) plc.cage_E(e, k) = cage_point[cages.E(e, k)];
  return plc;
}

// A tet mesh before compaction, and where each PLC point went in it (-1: not a vertex).
struct RawVolume {
  TetMesh mesh;
  Eigen::VectorXi input_to_raw;
};

// TetGen on the surface and the handle geometry. False (with a note) when TetGen fails and the robust
// volume may take over; with Robust::Never its error is thrown.
bool tetrahedralize_surface(const WeldedSurface& ws, const HandlePlc& plc, const Eigen::MatrixXd& P,
                            const VolumeOptions& opts, RawVolume& raw, std::vector<std::string>& notes) {
  Plc in;
  in.V = P;
  in.F.resize(ws.F.rows() + plc.cage_F.rows(), 3);
  in.F << ws.F, plc.cage_F;
  in.E = plc.cage_E;
  try {
    TetgenResult r = tetrahedralize(in, opts.tetgen_switches);
    raw.mesh = std::move(r.mesh);
    raw.input_to_raw = r.input_to_tet;
    notes.push_back("TetGen -" + opts.tetgen_switches + ": " + std::to_string(raw.mesh.T.rows()) + " tets in " +
                    std::to_string(r.seconds) + " s");
  } catch (const Error& e) {
    if (opts.robust == VolumeOptions::Robust::Never) throw;
    notes.push_back(std::string("TetGen failed on the surface (") + e.what() + "): robust (winding number) volume");
    return false;
  }
  return true;
}

// The points (surface vertices, handle geometry) in a box padded by 5% of the diagonal; cages stay
// constraint facets.
Plc padded_box_plc(const Eigen::MatrixXd& P, double diag, const HandlePlc& plc) {
  const Eigen::RowVector3d lo = P.colwise().minCoeff(), hi = P.colwise().maxCoeff();
  const Eigen::RowVector3d pad = Eigen::RowVector3d::Constant(0.05 * std::max(diag, 1e-12));
  Plc in;
  in.V.resize(P.rows() + 8, 3);
  in.V.topRows(P.rows()) = P;
  const int o = static_cast<int>(P.rows());
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k) in.V(o + c, k) = ((c >> k) & 1) ? hi(k) + pad(k) : lo(k) - pad(k);
  static const int box[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  in.F.resize(12 + plc.cage_F.rows(), 3);
  for (int f = 0; f < 12; ++f)
    for (int k = 0; k < 3; ++k) in.F(f, k) = o + box[f][k];
  in.F.bottomRows(plc.cage_F.rows()) = plc.cage_F;
  in.E = plc.cage_E;
  return in;
}

// Per point of X: how far inside it is, the winding number of the surface there, or its absolute
// winding number in a closed cage when that is larger.
Eigen::VectorXd insideness_at(const WeldedSurface& ws, const Rig& rig, const Eigen::MatrixXd& X) {
  // Only the side of 1/2 matters here: a loose tree (errors ~1e-3) is several times faster.
  const WindingAccuracy loose{2.0, 1e300};
  Eigen::VectorXd w = winding_numbers(build_winding_tree(ws.V, ws.F), X, loose);
  for (const Cage& cage : rig.cages)
    if (is_closed_surface(cage.mesh.F)) w = w.cwiseMax(winding_numbers(build_winding_tree(cage.mesh.V, cage.mesh.F), X, loose).cwiseAbs());
  return w;
}

// Per sample: whether its point is on the input surface or within `reach` of it (1% of the surface's
// bbox diagonal): such a handle is always accepted, whatever the winding number says there (issue 19).
std::vector<char> samples_near_surface(const WeldedSurface& ws, const HandlePlc& plc, double reach) {
  const SurfaceLocator locator(ws.V, ws.F, reach);
  std::vector<char> near(plc.samples.size(), 0);
  for (size_t s = 0; s < plc.samples.size(); ++s) near[s] = locator.closest(plc.samples[s].x).found();
  return near;
}

// Handle points (and bone samples) TetGen dropped although they lie within `reach` of the closed surface
// (issue 19: always accepted) are glued to the volume, one tet each (outside_handles.h). False when one
// faces no facet (then the robust volume takes over).
bool glue_near_handles(const WeldedSurface& ws, const HandlePlc& plc, const Eigen::MatrixXd& P, double reach,
                       RawVolume& raw, std::vector<std::string>& notes) {
  bool dropped = false;
  for (size_t s = 0; s < plc.samples.size(); ++s) dropped = dropped || raw.input_to_raw(plc.sample_point[s]) < 0;
  if (!dropped) return true;  // the usual case: no locator to build
  const std::vector<char> near = samples_near_surface(ws, plc, reach);
  std::vector<int> points;  // distinct dropped PLC points near the surface
  for (size_t s = 0; s < plc.samples.size(); ++s)
    if (near[s] && raw.input_to_raw(plc.sample_point[s]) < 0) points.push_back(plc.sample_point[s]);
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.empty()) return true;
  Eigen::MatrixXd X(points.size(), 3);
  for (size_t i = 0; i < points.size(); ++i) X.row(i) = P.row(points[i]);
  const std::vector<int> glued =
      glue_outside_points(ws.V, ws.F, raw.input_to_raw.head(ws.V.rows()), X, reach, raw.mesh);
  for (size_t i = 0; i < points.size(); ++i) {
    if (glued[i] < 0) return false;
    raw.input_to_raw(points[i]) = glued[i];
  }
  notes.push_back(std::to_string(points.size()) + " handle points just outside the surface (within 1% of the diagonal): "
                  "one tet each on the nearest facet");
  return true;
}

// Handle points (and bone samples) must be in the volume: a point on (or near) the surface may have lost
// every incident tet to the threshold (open boundaries, non-manifold seams, a handle just outside); give
// it back one incident tet.
// A point farther from the surface gets one only when it is inside by winding number; otherwise it stays
// out and constrain() refuses it by name. Returns how many tets came back.
int rescue_handle_tets(const HandlePlc& plc, const TetgenResult& r, const Eigen::VectorXd& w,
                       const std::vector<char>& near, const Eigen::VectorXd& point_w, std::vector<char>& keep) {
  std::vector<std::vector<int>> incident(r.mesh.V.rows());
  std::vector<char> kept_vertex(r.mesh.V.rows(), 0);
  for (int t = 0; t < r.mesh.T.rows(); ++t)
    for (int k = 0; k < 4; ++k) incident[r.mesh.T(t, k)].push_back(t), kept_vertex[r.mesh.T(t, k)] |= keep[t];
  // Among them, the tet with most vertices on the kept volume first (standing on it, not reaching across
  // the box: a handle just outside would otherwise pull a large tet in), then the most inside.
  auto on_volume = [&](int t) {
    return kept_vertex[r.mesh.T(t, 0)] + kept_vertex[r.mesh.T(t, 1)] + kept_vertex[r.mesh.T(t, 2)] + kept_vertex[r.mesh.T(t, 3)];
  };
  int rescued = 0;
  for (size_t s = 0; s < plc.samples.size(); ++s) {
    const int v = r.input_to_tet(plc.sample_point[s]);
    if (v < 0) continue;
    if (!near[s] && !(point_w(s) > 0.5)) continue;
    int best = -1;
    for (int t : incident[v]) {
      if (keep[t]) { best = -2; break; }
      if (best < 0 || on_volume(t) > on_volume(best) || (on_volume(t) == on_volume(best) && w(t) > w(best))) best = t;
    }
    if (best >= 0) keep[best] = 1, ++rescued;
  }
  return rescued;
}

// F without repeated facets (the same three vertices in either orientation; the first one stays).
Eigen::MatrixXi unique_facets(const Eigen::MatrixXi& F) {
  std::set<std::array<int, 3>> seen;
  std::vector<int> rows;
  for (int f = 0; f < F.rows(); ++f) {
    std::array<int, 3> k{F(f, 0), F(f, 1), F(f, 2)};
    std::sort(k.begin(), k.end());
    if (seen.insert(k).second) rows.push_back(f);
  }
  Eigen::MatrixXi out(rows.size(), 3);
  for (size_t i = 0; i < rows.size(); ++i) out.row(i) = F.row(rows[i]);
  return out;
}

// Section 8.5: a constrained tetrahedralization of the input facets in the padded box, where TetGen
// accepts them (no self-intersections; they then bound tets and the cut can follow them), else the
// points alone. Duplicate facets are dropped first, as 8.5 does (TetGen refuses them). The facets are not
// tried when TetGen already failed on the surface.
TetgenResult robust_tetrahedralization(const WeldedSurface& ws, const Plc& box, const std::string& sw, bool try_facets,
                                       std::vector<std::string>& notes) {
  if (try_facets) {
    const Eigen::MatrixXi F = unique_facets(ws.F);
    Plc in = box;
    in.F.resize(box.F.rows() + F.rows(), 3);
    in.F << box.F, F;
    const auto t = Clock::now();
    try {
      TetgenResult r = tetrahedralize(in, sw);
      notes.push_back("robust volume: the surface's facets are constrained");
      return r;
    } catch (const Error& e) {
      std::string why = e.what();
      if (why.size() > 160) why = "..." + why.substr(why.size() - 160);  // TetGen's last words say why
      notes.push_back("robust volume: TetGen refused the surface's facets in " +
                      std::to_string(std::chrono::duration<double>(Clock::now() - t).count()) + " s (" + why +
                      "): points only");
    }
  }
  return tetrahedralize(box, sw);
}

// Which tets of the padded box's tetrahedralization are inside (Jacobson 2013, 8.5.1): the graph cut
// over shared faces (data weighted by tet volume), the surface's and the cages' facets marked where
// they are tet faces; or Eq. 8.7.
std::vector<char> segment_tets(const WeldedSurface& ws, const HandlePlc& plc, const TetgenResult& r,
                               const Eigen::VectorXd& w, const VolumeOptions& opts) {
  if (opts.segmentation == VolumeOptions::Segmentation::Threshold) return threshold_segmentation(w);
  const TetFaceAdjacency adj = tet_face_adjacency(r.mesh);
  // The welded surface's vertices are the first PLC points, so ws.F and cage_F index PLC points.
  Eigen::MatrixXi facets(ws.F.rows() + plc.cage_F.rows(), 3);
  facets << ws.F, plc.cage_F;
  for (int f = 0; f < facets.rows(); ++f)
    for (int k = 0; k < 3; ++k) facets(f, k) = r.input_to_tet(facets(f, k));
  return graph_cut_segmentation(w, tet_volumes(r.mesh.V, r.mesh.T).cwiseAbs(), adj.tets, adj.area,
                                shared_faces_on_surface(adj, facets), opts.cut);
}

// The robust volume (Jacobson 2013, section 8.3): a (constrained) Delaunay tetrahedralization of the points
// in a padded box, carved to the tets inside by winding number (or inside a closed cage): graph cut or
// threshold.
RawVolume robust_volume(const WeldedSurface& ws, const Rig& rig, const HandlePlc& plc, const Eigen::MatrixXd& P,
                        double diag, const VolumeOptions& opts, bool try_facets, std::vector<std::string>& notes) {
  std::string sw = opts.tetgen_switches;
  if (sw.find('p') == std::string::npos) sw = "p" + sw;
  TetgenResult r = robust_tetrahedralization(ws, padded_box_plc(P, diag, plc), sw, try_facets, notes);
  const auto tw = Clock::now();
  const Eigen::VectorXd w = insideness_at(ws, rig, tet_centroids(r.mesh));
  const double w_seconds = std::chrono::duration<double>(Clock::now() - tw).count();
  const auto tc = Clock::now();
  std::vector<char> keep = segment_tets(ws, plc, r, w, opts);
  const double cut_seconds = std::chrono::duration<double>(Clock::now() - tc).count();
  Eigen::MatrixXd S(plc.samples.size(), 3);
  for (size_t i = 0; i < plc.samples.size(); ++i) S.row(i) = plc.samples[i].x.transpose();
  const Eigen::VectorXd point_w = insideness_at(ws, rig, S);
  const int rescued = rescue_handle_tets(plc, r, w, samples_near_surface(ws, plc, 0.01 * bbox_diagonal(ws.V)), point_w, keep);
  int nk = 0;
  for (char k : keep) nk += k;
  RawVolume raw;
  raw.mesh.V = r.mesh.V;
  raw.mesh.T.resize(nk, 4);
  for (int t = 0, j = 0; t < r.mesh.T.rows(); ++t)
    if (keep[t]) raw.mesh.T.row(j++) = r.mesh.T.row(t);
  raw.input_to_raw = r.input_to_tet.head(P.rows());
  const bool cut = opts.segmentation == VolumeOptions::Segmentation::Cut;
  notes.push_back("robust volume: TetGen -" + sw + " on " + std::to_string(P.rows()) + " points + box: " +
                  std::to_string(r.mesh.T.rows()) + " tets in " + std::to_string(r.seconds) + " s; winding numbers in " +
                  std::to_string(w_seconds) + " s; kept " + std::to_string(nk) +
                  (cut ? " by graph cut (" : " with winding number > 0.5 (") + std::to_string(cut_seconds) + " s)" +
                  (rescued ? "; " + std::to_string(rescued) + " handle tets added back" : ""));
  if (nk == 0) throw Error("bind: the surface encloses no volume (no tet is inside by winding number)");
  return raw;
}

// User vertices -> tet vertices (#user V x #tet V), or barycentric in the (nearest) tet when the volume
// lost them.
Eigen::SparseMatrix<double> to_user_matrix(const TriMesh& surface, const WeldedSurface& ws,
                                            const Eigen::VectorXi& plc_to_tet, const TetMesh& tets,
                                            std::vector<std::string>& notes) {
  const int nu = surface.num_vertices();
  std::vector<Eigen::Triplet<double>> trip;
  std::vector<int> missing;
  for (int u = 0; u < nu; ++u) {
    const int v = plc_to_tet(ws.user_to_welded(u));
    if (v >= 0) trip.emplace_back(u, v, 1.0);
    else missing.push_back(u);
  }
  if (!missing.empty()) {
    Eigen::MatrixXd Q(missing.size(), 3);
    for (size_t i = 0; i < missing.size(); ++i) Q.row(i) = surface.V.row(missing[i]);
    const Eigen::SparseMatrix<double> B = tet_interpolation(tets, Q);
    for (int k = 0; k < B.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(B, k); it; ++it) trip.emplace_back(missing[it.row()], it.col(), it.value());
    notes.push_back(std::to_string(missing.size()) + " surface vertices are not tet vertices: interpolated in their tets");
  }
  Eigen::SparseMatrix<double> to_user(nu, tets.V.rows());
  to_user.setFromTriplets(trip.begin(), trip.end());
  return to_user;
}

}  // namespace

BindVolume build_bind_volume(const TriMesh& surface, const Rig& rig, const VolumeOptions& opts) {
  const auto t0 = Clock::now();
  check_surface(surface);
  check_rig(rig);
  if (num_handles(rig) == 0) throw Error("bind: the rig has no handles");

  BindVolume vol;
  const WeldedSurface ws = weld_surface(surface.V, surface.F);
  if (ws.F.rows() == 0) throw Error("bind: every face of the surface is degenerate");
  vol.notes.push_back("surface: " + ws.report.describe());

  // Handle geometry joins the surface's vertices as PLC points.
  const CageSoup cages = stack_cages(rig);
  Eigen::MatrixXd all(ws.V.rows() + cages.V.rows(), 3);
  all << ws.V, cages.V;
  const double diag = bbox_diagonal(all);
  const double tol = 1e-7 * diag;
  const HandlePlc plc = handle_plc(ws, rig, cages, tol);
  const Eigen::MatrixXd P = plc.points.matrix();

  bool robust = opts.robust == VolumeOptions::Robust::Always;
  if (opts.robust == VolumeOptions::Robust::Auto && !ws.report.watertight()) {
    robust = true;
    vol.notes.push_back("surface is not a closed manifold: robust (winding number) volume");
  }
  RawVolume raw;
  bool tetgen_failed = false;
  if (!robust) robust = tetgen_failed = !tetrahedralize_surface(ws, plc, P, opts, raw, vol.notes);
  if (!robust && !glue_near_handles(ws, plc, P, 0.01 * bbox_diagonal(ws.V), raw, vol.notes)) {
    robust = true;
    vol.notes.push_back("a handle just outside the surface faces no facet: robust (winding number) volume");
  }
  if (robust) raw = robust_volume(ws, rig, plc, P, diag, opts, !tetgen_failed, vol.notes);

  // Compact (drop vertices no kept tet uses); order is preserved, so the surface's vertices stay first.
  Eigen::VectorXi raw_to_tet;
  vol.tets = compact_tet_mesh(raw.mesh, raw_to_tet);
  Eigen::VectorXi plc_to_tet(P.rows());
  for (int i = 0; i < P.rows(); ++i)
    plc_to_tet(i) = raw.input_to_raw(i) >= 0 ? raw_to_tet(raw.input_to_raw(i)) : -1;
  vol.tets.F = tet_boundary_faces(vol.tets.T);
  vol.to_user = to_user_matrix(surface, ws, plc_to_tet, vol.tets, vol.notes);

  // The welded surface vertices are the first PLC points: user_to_welded maps user vertices to PLC points.
  constrain(rig, plc, plc_to_tet, ws.user_to_welded, tol, vol);
  attach_free_pieces(vol);
  vol.meshing_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return vol;
}

namespace {

void check_tet_input(const TetMesh& input, const Rig& rig) {
  const int nv = input.num_vertices();
  if (nv == 0 || input.num_tets() == 0) throw Error("bind: the tet mesh has no tets");
  if (input.T.cols() != 4) throw Error("bind: tets must have four vertices");
  if (!input.V.allFinite()) throw Error("bind: the tet mesh has non-finite vertex coordinates");
  if (input.T.minCoeff() < 0 || input.T.maxCoeff() >= nv) throw Error("bind: a tet index is out of range");
  check_rig(rig);
  if (num_handles(rig) == 0) throw Error("bind: the rig has no handles");
}

// The given tets, positively oriented, with notes on flipped and flat ones.
void orient_given_tets(TetMesh& tets, std::vector<std::string>& notes) {
  const int flipped = io::orient_tets_positively(tets.V, tets.T);
  int flat = 0;
  for (int t = 0; t < tets.T.rows(); ++t) {
    const Eigen::Vector3d a = tets.V.row(tets.T(t, 0));
    const Eigen::Vector3d e1 = tets.V.row(tets.T(t, 1)).transpose() - a;
    const Eigen::Vector3d e2 = tets.V.row(tets.T(t, 2)).transpose() - a;
    const Eigen::Vector3d e3 = tets.V.row(tets.T(t, 3)).transpose() - a;
    flat += e1.dot(e2.cross(e3)) == 0;
  }
  if (flipped) notes.push_back(std::to_string(flipped) + " negatively oriented tets flipped");
  if (flat) notes.push_back(std::to_string(flat) + " tets have zero volume");
}

// Constraint rows of a rig on tets used as given: each handle must lie on tet vertices.
class GivenTetRows {
 public:
  GivenTetRows(const TetMesh& tets, const Rig& rig) : tets_(tets), rig_(rig), tol_(1e-5 * bbox_diagonal(tets.V)), grid_(tol_) {
    for (int i = 0; i < tets.num_vertices(); ++i) grid_.insert(tets.V.row(i).transpose());
  }

  BoundaryRows rows() {
    BoundaryRows rows;
    // Point handles and cage vertices: the tet vertex at that position.
    for (const HandleSample& s : sample_handles(rig_, 0)) {
      if (handle_ref(rig_, s.handle).kind == HandleKind::Bone) continue;
      const int v = grid_.find(s.x);
      if (v < 0) throw missing(s.handle, s.x);
      rows.add(v, s.w);
    }
    for (int i = 0; i < rig_.skeleton.num_bones(); ++i) add_bone(i, rows);
    for (int i = 0; i < static_cast<int>(rig_.regions.size()); ++i) add_region(i, rows);
    add_cage_surface_rows(tets_.V, stack_cages(rig_), tol_, rows);
    return rows;
  }

 private:
  // Bones: every tet vertex on the segment (libigl's boundary_conditions does the same).
  void add_bone(int i, BoundaryRows& rows) {
    const Bone& bone = rig_.skeleton.bones[i];
    const int h = handle_index(rig_, {HandleKind::Bone, i});
    if (bone.a < 0 || bone.b < 0 || bone.a >= rig_.skeleton.num_joints() || bone.b >= rig_.skeleton.num_joints())
      throw Error("bone " + handle_name(rig_, h) + " refers to a missing joint");
    const Eigen::Vector3d a = rig_.skeleton.joints.row(bone.a), b = rig_.skeleton.joints.row(bone.b);
    const Eigen::Vector3d d = b - a;
    const double l2 = d.squaredNorm();
    int hits = 0;
    for (int v = 0; v < tets_.num_vertices(); ++v) {
      const Eigen::Vector3d p = tets_.V.row(v);
      const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
      if ((a + t * d - p).norm() <= tol_) rows.add(v, {{h, 1.0}}), ++hits;
    }
    if (!hits) throw missing(h, 0.5 * (a + b));
  }

  void add_region(int i, BoundaryRows& rows) {
    const int h = handle_index(rig_, {HandleKind::Region, i});
    if (rig_.regions[i].vertices.empty()) throw Error("region \"" + handle_name(rig_, h) + "\" has no vertices");
    for (int u : rig_.regions[i].vertices) {
      if (u < 0 || u >= tets_.num_vertices())
        throw Error("region \"" + handle_name(rig_, h) + "\": vertex " + std::to_string(u) + " out of range");
      rows.add(u, {{h, 1.0}});
    }
  }

  // Why handle h (at x) has no tet vertex: inside the mesh but not a vertex, or outside it.
  Error missing(int h, const Eigen::Vector3d& x) {
    if (!boundary_) boundary_ = std::make_unique<WindingTree>(build_winding_tree(tets_.V, tets_.F));
    const bool inside = std::abs(winding_number(*boundary_, x)) > 0.5;
    return Error(std::string(handle_kind_name(handle_ref(rig_, h).kind)) + " handle \"" + handle_name(rig_, h) + "\" " +
                 (inside ? "is not a vertex of the tet mesh: remesh it with the handle, or bind the surface"
                         : "lies outside the tet mesh"));
  }

  const TetMesh& tets_;
  const Rig& rig_;
  double tol_;
  PointWelder grid_;  // a lookup structure over the tet vertices
  std::unique_ptr<WindingTree> boundary_;
};

}  // namespace

BindVolume bind_volume_from_tets(const TetMesh& input, const Rig& rig) {
  const auto t0 = Clock::now();
  check_tet_input(input, rig);
  const int nv = input.num_vertices();
  BindVolume vol;
  vol.tets.V = input.V;
  vol.tets.T = input.T;
  orient_given_tets(vol.tets, vol.notes);
  vol.tets.F = tet_boundary_faces(vol.tets.T);
  GivenTetRows(vol.tets, rig).rows().finish(num_handles(rig), vol.b, vol.bc);
  vol.to_user.resize(nv, nv);
  vol.to_user.setIdentity();
  attach_free_pieces(vol);
  vol.notes.push_back("tet mesh used as given: " + std::to_string(nv) + " vertices, " + std::to_string(input.num_tets()) + " tets");
  vol.meshing_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return vol;
}

}  // namespace dfm
