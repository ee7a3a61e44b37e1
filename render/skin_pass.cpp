#include "render/skin_pass.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

#include "core/util/error.h"

namespace dfm::gl {

namespace {
constexpr int kHandleTexels = 16;  // must match HANDLE_TEXELS in shaders/skin.vert.glsl

void put_row(float* dst, const Eigen::Vector4d& v) {
  for (int c = 0; c < 4; ++c) dst[c] = static_cast<float>(v[c]);
}

// A texture buffer over `buffer` holding `data` (at least one element, so it is never empty).
template <class T>
void upload_texture_buffer(Buffer& buffer, Texture& texture, GLenum format, std::vector<T> data) {
  if (data.empty()) data.resize(1);
  buffer.upload(GL_TEXTURE_BUFFER, data);
  glBindTexture(GL_TEXTURE_BUFFER, texture.id());
  glTexBuffer(GL_TEXTURE_BUFFER, format, buffer.id());
  glBindTexture(GL_TEXTURE_BUFFER, 0);
}
}  // namespace

SkinPass::SkinPass(const SkinBinding& b) {
  const Influences& inf = b.influences;
  num_vertices_ = static_cast<int>(b.V.rows());
  if (b.V.cols() != 3 || inf.num_vertices() != num_vertices_)
    throw Error("GPU skinning: positions and influences disagree on the vertex count");
  if (b.N.size() && (b.N.rows() != num_vertices_ || b.N.cols() != 3)) throw Error("GPU skinning: normals must be #V x 3");
  if (b.endpoints.size() && (b.endpoints.rows() != num_vertices_ || b.endpoints.cols() != inf.k()))
    throw Error("GPU skinning: endpoint weights must be #V x k");
  if (inf.index.size() && inf.index.minCoeff() < 0) throw Error("GPU skinning: negative handle index");
  const SparseInfluences sp = sparse_influences(inf, b.endpoints);
  num_entries_ = sp.num_entries();
  max_row_ = sp.max_row;
  num_handles_ = b.num_handles;
  first_additional_ = b.num_handles - b.additional;
  max_handle_ = sp.handle.empty() ? -1 : *std::max_element(sp.handle.begin(), sp.handle.end());
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (static_cast<long long>(std::max(num_entries_, num_vertices_ + 1)) > max_texels)
    throw Error("GPU skinning: " + std::to_string(num_entries_) + " influences of " + std::to_string(num_vertices_) +
                " vertices exceed this driver's texture buffer (" + std::to_string(max_texels) + " texels)");

  std::vector<PosNormal> rest(num_vertices_);
  for (int i = 0; i < num_vertices_; ++i)
    for (int c = 0; c < 3; ++c) {
      rest[i].position[c] = static_cast<float>(b.V(i, c));
      rest[i].normal[c] = b.N.size() ? static_cast<float>(b.N(i, c)) : 0.0f;
    }
  // (handle, weight) pairs as RG32I: the weight's float bits, read back by intBitsToFloat.
  std::vector<GLint> pairs(2 * static_cast<size_t>(num_entries_));
  std::vector<float> endpoints(num_entries_);
  for (int e = 0; e < num_entries_; ++e) {
    const float w = static_cast<float>(sp.weight[e]);
    pairs[2 * static_cast<size_t>(e)] = sp.handle[e];
    std::memcpy(&pairs[2 * static_cast<size_t>(e) + 1], &w, sizeof w);
    endpoints[e] = static_cast<float>(sp.endpoint[e]);
  }
  upload_texture_buffer(offsets_, offsets_texture_, GL_R32I, std::vector<GLint>(sp.offsets.begin(), sp.offsets.end()));
  upload_texture_buffer(pairs_, pairs_texture_, GL_RG32I, std::move(pairs));
  upload_texture_buffer(endpoints_, endpoints_texture_, GL_R32F, std::move(endpoints));

  vao_.bind();
  rest_.upload(GL_ARRAY_BUFFER, rest);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(PosNormal), reinterpret_cast<void*>(0));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(PosNormal), reinterpret_cast<void*>(3 * sizeof(float)));
  glBindVertexArray(0);
  output_.upload(GL_TRANSFORM_FEEDBACK_BUFFER, nullptr, sizeof(PosNormal) * static_cast<size_t>(num_vertices_),
                 GL_DYNAMIC_COPY);
  check_error("SkinPass upload");
}

void SkinPass::set_pose(const Pose& pose, const std::vector<StbsHandle>& stbs) {
  const int nh = pose.size();
  if (max_handle_ >= nh)
    throw Error("GPU skinning: the weights name handle " + std::to_string(max_handle_) + " but the pose has " +
                std::to_string(nh) + " transforms");
  // One record per handle, or per rig handle (the additional ones have none: inactive).
  if (!stbs.empty() && static_cast<int>(stbs.size()) != nh && static_cast<int>(stbs.size()) != std::min(nh, first_additional_))
    throw Error("GPU skinning: " + std::to_string(stbs.size()) + " twist/stretch records for " + std::to_string(nh) +
                " handles");
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (static_cast<long long>(nh) * kHandleTexels > max_texels)
    throw Error("GPU skinning: " + std::to_string(nh) + " handles exceed this driver's texture buffer (" +
                std::to_string(max_texels / kHandleTexels) + " handles)");
  // Additional handles skin linearly (the shader's first_additional): no dual quaternion, which a
  // zero (unsolved) transform would not have.
  std::vector<DqsHandle> dq(nh);
  for (int h = 0; h < std::min(nh, first_additional_); ++h) dq[h] = dqs_handle(pose.transforms[h]);
  std::vector<float> data(static_cast<size_t>(std::max(nh, 1)) * kHandleTexels * 4, 0.0f);
  for (int h = 0; h < nh; ++h) {
    float* d = &data[static_cast<size_t>(h) * kHandleTexels * 4];
    const bool active = h < static_cast<int>(stbs.size()) && stbs[h].active;
    const Eigen::Affine3d& T = pose.transforms[h];
    for (int r = 0; r < 3; ++r) put_row(d + 4 * r, T.matrix().row(r).transpose());
    put_row(d + 12, dq[h].real);
    put_row(d + 16, dq[h].dual);
    for (int r = 0; r < 3; ++r) put_row(d + 20 + 4 * r, Eigen::Vector4d(dq[h].stretch(r, 0), dq[h].stretch(r, 1), dq[h].stretch(r, 2), 0));
    if (active) {
      const StbsHandle& s = stbs[h];
      put_row(d + 32, Eigen::Vector4d(s.origin.x(), s.origin.y(), s.origin.z(), s.twist));
      put_row(d + 36, Eigen::Vector4d(s.axis.x(), s.axis.y(), s.axis.z(), 1.0));
      put_row(d + 40, Eigen::Vector4d(s.stretch.x(), s.stretch.y(), s.stretch.z(), s.twist_start));
      const Eigen::Affine3d Tp = T * s.unstretched;
      for (int r = 0; r < 3; ++r) put_row(d + 44 + 4 * r, Tp.matrix().row(r).transpose());
      const DqsHandle tq = dqs_handle(Tp);
      put_row(d + 56, tq.real);
      put_row(d + 60, tq.dual);
    }
  }
  handle_data_.upload(GL_TEXTURE_BUFFER, data, GL_STREAM_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, handle_texture_.id());
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, handle_data_.id());
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  num_handles_ = nh;
  check_error("SkinPass::set_pose");
}

const Program& SkinPass::program(SkinMethod m) {
  auto it = programs_.find(m);
  if (it != programs_.end()) return it->second;
  const char* define = m == SkinMethod::LBS    ? "METHOD_LBS"
                       : m == SkinMethod::DQS  ? "METHOD_DQS"
                       : m == SkinMethod::STBS ? "METHOD_STBS"
                                               : "METHOD_STBS_DQS";
  ProgramDesc desc;
  desc.vertex = "skin.vert.glsl";
  desc.defines = {define};
  desc.feedback_varyings = {"out_position", "out_normal"};
  return programs_.emplace(m, Program(desc)).first->second;
}

void SkinPass::run(SkinMethod method) {
  if (handle_data_.bytes() == 0) throw Error("GPU skinning: set_pose() before run()");
  const Program& prog = program(method);
  prog.use();
  const std::pair<const char*, GLuint> textures[] = {{"handles", handle_texture_.id()},
                                                     {"row_offsets", offsets_texture_.id()},
                                                     {"pairs", pairs_texture_.id()},
                                                     {"endpoints", endpoints_texture_.id()}};
  for (int unit = 0; unit < 4; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_BUFFER, textures[unit].second);
    glUniform1i(prog.uniform(textures[unit].first), unit);
  }
  glUniform1i(prog.uniform("first_additional"), first_additional_);
  capture_points(vao_, output_, num_vertices_);
  for (int unit = 3; unit >= 0; --unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
  }
  check_error("SkinPass::run");
}

std::vector<PosNormal> SkinPass::read_back() const { return output_.read<PosNormal>(num_vertices_); }

SkinResult SkinPass::read_back_result() const {
  const std::vector<PosNormal> out = read_back();
  SkinResult r;
  r.V.resize(num_vertices_, 3);
  r.N.resize(num_vertices_, 3);
  for (int i = 0; i < num_vertices_; ++i)
    for (int c = 0; c < 3; ++c) {
      r.V(i, c) = out[i].position[c];
      r.N(i, c) = out[i].normal[c];
    }
  return r;
}

}  // namespace dfm::gl
