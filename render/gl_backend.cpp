#include "render/gl_backend.h"

#include <cstdint>

#include "render/interval_slice_pass.h"
#include "render/skin_pass.h"
#include "render/slice_pass.h"

namespace dfm::gl {

namespace {

class GlSkin final : public SkinDeformer {
 public:
  GlSkin(const SkinBinding& binding, const Eigen::MatrixXi& F) : pass_(binding) {
    std::vector<std::uint32_t> idx(F.size());
    for (int f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c) idx[3 * f + c] = static_cast<std::uint32_t>(F(f, c));
    // GL_ARRAY_BUFFER: binding GL_ELEMENT_ARRAY_BUFFER would change whatever VAO is bound.
    indices_.upload(GL_ARRAY_BUFFER, idx);
    index_count_ = static_cast<int>(idx.size());
  }
  void set_pose(const Pose& pose, const std::vector<StbsHandle>& stbs) override { pass_.set_pose(pose, stbs); }
  void run(SkinMethod method) override { pass_.run(method); }
  GeometryRef output() const override {
    return {pass_.output_buffer(), pass_.num_vertices(), indices_.id(), index_count_};
  }
  std::vector<PosNormal> read_back() const override { return pass_.read_back(); }

 private:
  SkinPass pass_;
  Buffer indices_;
  int index_count_ = 0;
};

class GlSlicer final : public ManifoldSlicer {
 public:
  void upload(const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4) override {
    pass_.upload(m, &vertex_normals4);
  }
  void upload_vertices(const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4) override {
    pass_.upload_vertices(m, vertex_normals4);
  }
  int slice(SliceAxis axis, double value) override { return pass_.slice(axis, value); }
  GeometryRef output() const override { return {pass_.output().id(), 3 * pass_.triangle_count(), 0, 0}; }
  std::vector<PosNormal> read_back() const override { return pass_.read_back(); }

 private:
  SlicePass pass_;
};

class GlIntervalSlicer final : public IntervalSlicer {
 public:
  void upload(const IntervalSlice& interval, const AnimationManifold& m, const Eigen::MatrixXd& vertex_normals4,
              const IntervalRecords* prepared) override {
    if (prepared) pass_.upload(interval, *prepared);
    else pass_.upload(interval, m, vertex_normals4);
  }
  void evaluate(double t) override { pass_.evaluate(t); }
  GeometryRef output() const override {
    return {pass_.record_buffer(), pass_.num_vertices(), pass_.index_buffer(), pass_.index_count(), true, pass_.dt()};
  }
  const Eigen::MatrixXi& faces() const override { return pass_.faces(); }
  std::vector<PosNormal> read_back() const override { return pass_.read_back(); }

 private:
  IntervalSlicePass pass_;
};

}  // namespace

GlBackend::GlBackend() = default;

std::unique_ptr<SkinDeformer> GlBackend::make_skin(const SkinBinding& binding, const Eigen::MatrixXi& F) {
  return std::make_unique<GlSkin>(binding, F);
}
std::unique_ptr<ManifoldSlicer> GlBackend::make_slicer() { return std::make_unique<GlSlicer>(); }
std::unique_ptr<IntervalSlicer> GlBackend::make_interval_slicer() { return std::make_unique<GlIntervalSlicer>(); }

void GlBackend::show_geometry(const GeometryRef& g) {
  if (g.interval)
    surface_.set_interval_geometry(g.vertex_buffer, g.vertex_count, g.index_buffer, g.index_count, g.interval_dt);
  else
    surface_.set_geometry(g.vertex_buffer, g.vertex_count, g.index_buffer, g.index_count);
}

}  // namespace dfm::gl
