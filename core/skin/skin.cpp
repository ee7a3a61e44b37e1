#include "core/skin/skin.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "core/util/error.h"

namespace dfm {

const char* skin_method_name(SkinMethod m) {
  switch (m) {
    case SkinMethod::LBS: return "lbs";
    case SkinMethod::DQS: return "dqs";
    case SkinMethod::STBS: return "stbs";
    case SkinMethod::STBS_DQS: return "stbs-dqs";
  }
  return "?";
}

SkinMethod parse_skin_method(const std::string& name) {
  std::string s = name;
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  if (s == "lbs") return SkinMethod::LBS;
  if (s == "dqs") return SkinMethod::DQS;
  if (s == "stbs") return SkinMethod::STBS;
  if (s == "stbs-dqs") return SkinMethod::STBS_DQS;
  throw Error("unknown skinning method '" + name + "' (expected lbs, dqs, stbs or stbs-dqs)");
}

SkinBinding make_skin_binding(const Eigen::MatrixXd& V, const Eigen::MatrixXd& N, const Eigen::MatrixXd& W,
                              const Rig& rig, int k, const Eigen::MatrixXd& bone_endpoints,
                              const Eigen::MatrixXd& additional) {
  const int nh = num_handles(rig), na = static_cast<int>(additional.cols());
  if (W.rows() != V.rows())
    throw Error("weights have " + std::to_string(W.rows()) + " rows but the mesh has " + std::to_string(V.rows()) +
                " vertices");
  if (W.cols() != nh)
    throw Error("weights have " + std::to_string(W.cols()) + " columns but the rig has " + std::to_string(nh) +
                " handles");
  if (N.size() && (N.rows() != V.rows() || N.cols() != 3)) throw Error("normals must be #V x 3");
  SkinBinding b;
  b.V = V;
  b.N = N;
  b.num_handles = nh + na;
  b.additional = na;
  if (na > 0 && additional.rows() != V.rows())
    throw Error("additional weights have " + std::to_string(additional.rows()) + " rows but the mesh has " +
                std::to_string(V.rows()) + " vertices");
  b.influences = k <= 0 ? all_influences(W) : top_influences(W, k, true);
  const int np = num_point_handles(rig), nb = rig.skeleton.num_bones();
  if (bone_endpoints.size() == 0) {
    b.endpoints = gather_by_influence(b.influences, bone_endpoint_weights(V, rig));
  } else {
    if (bone_endpoints.rows() != V.rows() || bone_endpoints.cols() != nb)
      throw Error("endpoint weights are " + std::to_string(bone_endpoints.rows()) + " x " +
                  std::to_string(bone_endpoints.cols()) + ", expected #V x #bones = " + std::to_string(V.rows()) +
                  " x " + std::to_string(nb));
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(V.rows(), nh);  // per handle: bones' columns only
    E.middleCols(np, nb) = bone_endpoints;
    b.endpoints = gather_by_influence(b.influences, E);
  }
  if (na > 0) {  // every additional column, after the rig's (a DQS row's pivot stays a rig handle)
    Influences& inf = b.influences;
    const int k0 = inf.k();
    inf.index.conservativeResize(Eigen::NoChange, k0 + na);
    inf.weight.conservativeResize(Eigen::NoChange, k0 + na);
    for (int e = 0; e < na; ++e) {
      inf.index.col(k0 + e).setConstant(nh + e);
      inf.weight.col(k0 + e) = additional.col(e);
    }
    b.endpoints.conservativeResize(Eigen::NoChange, k0 + na);
    b.endpoints.rightCols(na).setZero();
  }
  return b;
}

namespace {

// The dual-quaternion methods on the rig's handles, then the additional handles' linear term.
void skin_dq_with_additional(SkinMethod method, const SkinBinding& b, const Pose& pose,
                             const std::vector<StbsHandle>& stbs, SkinResult& r) {
  const int first = b.num_handles - b.additional, k0 = b.influences.k() - b.additional;
  if (pose.size() < b.num_handles)
    throw Error("skinning: the weights name " + std::to_string(b.num_handles) + " handles but the pose has " +
                std::to_string(pose.size()) + " transforms");
  SkinBinding rig_only = b;
  rig_only.influences.index = b.influences.index.leftCols(k0);
  rig_only.influences.weight = b.influences.weight.leftCols(k0);
  rig_only.endpoints = b.endpoints.leftCols(k0);
  rig_only.num_handles = first;
  rig_only.additional = 0;
  Pose rig_pose;
  rig_pose.transforms.assign(pose.transforms.begin(), pose.transforms.begin() + first);
  std::vector<StbsHandle> rig_stbs(stbs.begin(), stbs.begin() + std::min<size_t>(stbs.size(), first));
  r = skin(method, rig_only, rig_pose, rig_stbs);
  for (int i = 0; i < r.V.rows(); ++i)
    for (int e = 0; e < b.additional; ++e) {
      const double w = b.influences.weight(i, k0 + e);
      if (w == 0) continue;
      const Eigen::Affine3d& T = pose.transforms[b.influences.index(i, k0 + e)];
      r.V.row(i) += (w * (T.linear() * b.V.row(i).transpose() + T.translation())).transpose();
    }
}

}  // namespace

SkinResult skin(SkinMethod method, const SkinBinding& b, const Pose& pose, const std::vector<StbsHandle>& stbs_in) {
  SkinResult r;
  if (b.additional > 0 && (method == SkinMethod::DQS || method == SkinMethod::STBS_DQS)) {
    skin_dq_with_additional(method, b, pose, stbs_in, r);
    return r;
  }
  std::vector<StbsHandle> padded;  // additional handles: no twist or stretch (the LBS term)
  if (!stbs_in.empty() && static_cast<int>(stbs_in.size()) < pose.size()) {
    padded = stbs_in;
    padded.resize(pose.size());
  }
  const std::vector<StbsHandle>& stbs = padded.empty() ? stbs_in : padded;
  Eigen::MatrixXd* NU = b.N.size() ? &r.N : nullptr;
  switch (method) {
    case SkinMethod::LBS: lbs(b.V, b.N, b.influences, pose, r.V, NU); break;
    case SkinMethod::DQS: dqs(b.V, b.N, b.influences, pose, r.V, NU); break;
    case SkinMethod::STBS:
    case SkinMethod::STBS_DQS: {
      std::vector<StbsHandle> none;
      if (stbs.empty()) none.resize(pose.size());
      const std::vector<StbsHandle>& h = stbs.empty() ? none : stbs;
      if (method == SkinMethod::STBS) dfm::stbs(b.V, b.N, b.influences, b.endpoints, pose, h, r.V, NU);
      else stbs_dqs(b.V, b.N, b.influences, b.endpoints, pose, h, r.V, NU);
      break;
    }
  }
  return r;
}

double truncation_error(SkinMethod method, const SkinBinding& reference, const SkinBinding& truncated,
                        const Pose& pose, const std::vector<StbsHandle>& stbs) {
  SkinBinding a = reference, t = truncated;
  a.N.resize(0, 0);
  t.N.resize(0, 0);
  const Eigen::MatrixXd d = skin(method, a, pose, stbs).V - skin(method, t, pose, stbs).V;
  return d.size() ? d.rowwise().norm().maxCoeff() : 0.0;
}

Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a);  // length = twice the area: area weighting
    for (int j = 0; j < 3; ++j) N.row(F(f, j)) += n;
  }
  for (int i = 0; i < N.rows(); ++i) {
    const double len = N.row(i).norm();
    if (len > 0) N.row(i) /= len;
  }
  return N;
}

}  // namespace dfm
