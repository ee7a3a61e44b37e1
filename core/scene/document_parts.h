#pragma once
// Inside the document's implementation files only (document*.cpp): which parts of SceneData an
// undo step saves, and the argument checks the commands share.
#include <string>
#include <vector>

#include "core/scene/document.h"
#include "core/util/error.h"

namespace dfm {

enum Document::Part : unsigned {
  kSurface = 1u << 0,  // surface, surface_path, tets, surface_to_tet
  kRig = 1u << 1,
  kPose = 1u << 2,
  kKeys = 1u << 3,
  kWeights = 1u << 4,  // weights, bind_stats (and the weights note)
  kMask = 1u << 5,
  kSettings = 1u << 6,  // method, bind settings, in-betweens
};

namespace document_detail {

inline void check_finite(const Eigen::Vector3d& p, const char* what) {
  if (!p.allFinite()) throw Error(std::string(what) + " is not finite");
}

template <class T>
void erase_at(std::vector<T>& v, int i) {
  if (i >= 0 && i < static_cast<int>(v.size())) v.erase(v.begin() + i);
}

}  // namespace document_detail
}  // namespace dfm
