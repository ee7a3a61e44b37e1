#pragma once
// A RenderBackend (render/backend.h) with no GPU, for the viewport's tests (test_scene_view.cpp): it
// records every call and the data passed, and its deformers compute on the CPU with the core
// references the GPU passes are tested against (skin(), slice_manifold, evaluate_interval_slice), so
// what the view reads back is checkable too. Each object it makes gets its own buffer names and a log
// that outlives it (alive turns false when the view drops it).
#include <memory>
#include <utility>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "core/anim/interval_slice.h"
#include "core/anim/slice.h"
#include "core/skin/skin.h"
#include "render/backend.h"

namespace dfm::test {

inline std::vector<gl::PosNormal> to_pos_normal(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N) {
  std::vector<gl::PosNormal> out(V.rows());
  for (int i = 0; i < V.rows(); ++i)
    for (int k = 0; k < 3; ++k) {
      out[i].position[k] = static_cast<float>(V(i, k));
      out[i].normal[k] = N.rows() == V.rows() ? static_cast<float>(N(i, k)) : 0.0f;
    }
  return out;
}

class MockRenderBackend final : public gl::RenderBackend {
 public:
  struct SkinLog {
    SkinBinding binding;
    Eigen::MatrixXi F;
    gl::GeometryRef output;
    int runs = 0;
    Pose pose;
    SkinMethod method = SkinMethod::LBS;
    bool alive = true;
  };
  struct SlicerLog {
    int uploads = 0;
    int vertex_uploads = 0;  // upload_vertices: positions and normals only
    std::vector<std::pair<SliceAxis, double>> slices;
    unsigned buffer = 0;
    bool alive = true;
  };
  struct IntervalLog {
    IntervalSlice topology;
    int uploads = 0;
    int prepared = 0;  // uploads that came with records made beforehand
    std::vector<double> evaluations;
    gl::GeometryRef output;
    bool alive = true;
  };
  struct OverlayBatch {
    std::vector<gl::OverlayVertex> vertices;
    float size = 0;  // line width or point size
    bool depth_test = false;
  };
  struct SurfaceDraw {
    gl::SurfaceStyle style;
    gl::GeometryRef geometry;
    size_t data_size = 0;
  };

  // The buffers show_mesh fills.
  const unsigned mesh_vertex_buffer = 1, mesh_index_buffer = 2;

  std::vector<std::unique_ptr<SkinLog>> skins;
  std::vector<std::unique_ptr<SlicerLog>> slicers;
  std::vector<std::unique_ptr<IntervalLog>> intervals;
  int mesh_uploads = 0;
  TriMesh mesh;  // the last show_mesh
  int geometry_sets = 0;
  gl::GeometryRef geometry;  // what the surface draws now
  int data_uploads = 0;
  std::vector<Eigen::Vector4f> data;  // the surface's per-vertex data now
  std::vector<SurfaceDraw> surface_draws;
  std::vector<OverlayBatch> lines, points;

  // Forgets the draws (not the state or the logs), to look at one frame.
  void clear_draws() {
    surface_draws.clear();
    lines.clear();
    points.clear();
  }

  std::unique_ptr<gl::SkinDeformer> make_skin(const SkinBinding& binding, const Eigen::MatrixXi& F) override;
  std::unique_ptr<gl::ManifoldSlicer> make_slicer() override;
  std::unique_ptr<gl::IntervalSlicer> make_interval_slicer() override;

  void show_mesh(const TriMesh& m) override {
    ++mesh_uploads;
    mesh = m;
    show_geometry({mesh_vertex_buffer, m.num_vertices(), mesh_index_buffer, 3 * m.num_faces()});
  }
  void show_geometry(const gl::GeometryRef& g) override {
    ++geometry_sets;
    geometry = g;
  }
  void set_surface_data(const std::vector<Eigen::Vector4f>& d) override {
    ++data_uploads;
    data = d;
  }
  void draw_surface(const view::Camera&, const gl::SurfaceStyle& style) override {
    surface_draws.push_back({style, geometry, data.size()});
  }
  void draw_lines(const view::Camera&, const std::vector<gl::OverlayVertex>& pairs, float width,
                  bool depth_test) override {
    lines.push_back({pairs, width, depth_test});
  }
  void draw_points(const view::Camera&, const std::vector<gl::OverlayVertex>& pts, float size,
                   bool depth_test) override {
    points.push_back({pts, size, depth_test});
  }

 private:
  unsigned next_buffer_ = 100;
  unsigned new_buffer() { return next_buffer_++; }
};

namespace mock_detail {

class Skin final : public gl::SkinDeformer {
 public:
  explicit Skin(MockRenderBackend::SkinLog* log) : log_(log) {}
  ~Skin() override { log_->alive = false; }
  void set_pose(const Pose& pose, const std::vector<StbsHandle>& stbs) override {
    log_->pose = pose;
    stbs_ = stbs;
  }
  void run(SkinMethod method) override {
    ++log_->runs;
    log_->method = method;
    result_ = skin(method, log_->binding, log_->pose, stbs_);
  }
  gl::GeometryRef output() const override { return log_->output; }
  std::vector<gl::PosNormal> read_back() const override { return to_pos_normal(result_.V, result_.N); }

 private:
  MockRenderBackend::SkinLog* log_;
  std::vector<StbsHandle> stbs_;
  SkinResult result_;
};

// A soup, 3 vertices per triangle, as the GPU slice pass writes it.
class Slicer final : public gl::ManifoldSlicer {
 public:
  explicit Slicer(MockRenderBackend::SlicerLog* log) : log_(log) {}
  ~Slicer() override { log_->alive = false; }
  void upload(const AnimationManifold& m, const Eigen::MatrixXd& normals4) override {
    ++log_->uploads;
    m_ = m;
    normals4_ = normals4;
  }
  void upload_vertices(const AnimationManifold& m, const Eigen::MatrixXd& normals4) override {
    ++log_->vertex_uploads;
    if (!(m.T == m_.T) || !(m.V.col(3) == m_.V.col(3)))  // the caller's promise
      throw std::logic_error("upload_vertices with other tetrahedra or times than the last upload");
    m_.V = m.V;
    normals4_ = normals4;
  }
  int slice(SliceAxis axis, double value) override {
    log_->slices.emplace_back(axis, value);
    const TriMesh s = slice_manifold(m_, axis, value, &normals4_).mesh;
    soup_V_.resize(3 * s.num_faces(), 3);
    soup_N_.resize(3 * s.num_faces(), 3);
    for (int f = 0; f < s.num_faces(); ++f)
      for (int c = 0; c < 3; ++c) {
        soup_V_.row(3 * f + c) = s.V.row(s.F(f, c));
        soup_N_.row(3 * f + c) = s.N.row(s.F(f, c));
      }
    return s.num_faces();
  }
  gl::GeometryRef output() const override {
    return {log_->buffer, static_cast<int>(soup_V_.rows()), 0, 0};
  }
  std::vector<gl::PosNormal> read_back() const override { return to_pos_normal(soup_V_, soup_N_); }

 private:
  MockRenderBackend::SlicerLog* log_;
  AnimationManifold m_;
  Eigen::MatrixXd normals4_, soup_V_, soup_N_;
};

class Interval final : public gl::IntervalSlicer {
 public:
  explicit Interval(MockRenderBackend::IntervalLog* log) : log_(log) {}
  ~Interval() override { log_->alive = false; }
  void upload(const IntervalSlice& s, const AnimationManifold& m, const Eigen::MatrixXd& normals4,
              const gl::IntervalRecords* prepared) override {
    ++log_->uploads;
    log_->prepared += prepared != nullptr;
    log_->topology = s;
    log_->output.vertex_count = s.num_vertices();
    log_->output.index_count = 3 * s.num_faces();
    m_ = m;
    normals4_ = normals4;
  }
  void evaluate(double t) override {
    log_->evaluations.push_back(t);
    log_->output.interval_dt = static_cast<float>(t - log_->topology.t_lo);
    slice_ = evaluate_interval_slice(log_->topology, m_, normals4_, t);
  }
  gl::GeometryRef output() const override { return log_->output; }
  const Eigen::MatrixXi& faces() const override { return log_->topology.F; }
  std::vector<gl::PosNormal> read_back() const override { return to_pos_normal(slice_.V, slice_.N); }

 private:
  MockRenderBackend::IntervalLog* log_;
  AnimationManifold m_;
  Eigen::MatrixXd normals4_;
  TriMesh slice_;
};

}  // namespace mock_detail

inline std::unique_ptr<gl::SkinDeformer> MockRenderBackend::make_skin(const SkinBinding& binding,
                                                                      const Eigen::MatrixXi& F) {
  auto log = std::make_unique<SkinLog>();
  log->binding = binding;
  log->F = F;
  log->output = {new_buffer(), static_cast<int>(binding.V.rows()), new_buffer(), static_cast<int>(F.size())};
  skins.push_back(std::move(log));
  return std::make_unique<mock_detail::Skin>(skins.back().get());
}

inline std::unique_ptr<gl::ManifoldSlicer> MockRenderBackend::make_slicer() {
  auto log = std::make_unique<SlicerLog>();
  log->buffer = new_buffer();
  slicers.push_back(std::move(log));
  return std::make_unique<mock_detail::Slicer>(slicers.back().get());
}

inline std::unique_ptr<gl::IntervalSlicer> MockRenderBackend::make_interval_slicer() {
  auto log = std::make_unique<IntervalLog>();
  log->output.vertex_buffer = new_buffer();
  log->output.index_buffer = new_buffer();
  log->output.interval = true;
  intervals.push_back(std::move(log));
  return std::make_unique<mock_detail::Interval>(intervals.back().get());
}

}  // namespace dfm::test
