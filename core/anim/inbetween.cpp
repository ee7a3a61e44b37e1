#include "core/anim/inbetween.h"

#include <memory>

#include "core/anim/arap_interpolation.h"
#include "core/util/error.h"

namespace dfm {

std::vector<KeySurface> mesh_inbetweens(const KeySurface& a, const KeySurface& b, int count, InbetweenMethod method) {
  if (method == InbetweenMethod::Handles)
    throw Error("in-betweens by handles need the rig's keyed poses, not meshes (" + a.name + " to " + b.name + ")");
  if (count < 0) throw Error("in-betweens per interval must be >= 0, got " + std::to_string(count));
  if (!same_connectivity(a, b))
    throw Error(b.name + ": its vertices or triangles differ from " + a.name +
                "'s (in-betweens need one connectivity; a transition joins different meshes)");
  std::vector<KeySurface> out;
  if (count == 0) return out;
  const TriMesh k0{a.V, a.F, {}};
  std::unique_ptr<ArapInterpolation> arap;
  if (method == InbetweenMethod::Arap) {
    try {
      arap = std::make_unique<ArapInterpolation>(k0, b.V);
    } catch (const Error& e) {
      throw Error(a.name + ": " + e.what());
    }
  }
  for (int j = 1; j <= count; ++j) {
    const double u = double(j) / (count + 1);
    KeySurface s{a.time + (b.time - a.time) * j / (count + 1), {}, a.F,
                 std::string(inbetween_method_name(method)) + " in-between of " + a.name + " and " + b.name};
    s.V = arap ? arap->at(u) : linear_interpolation(a.V, b.V, u);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<KeySurface> with_mesh_inbetweens(const std::vector<KeySurface>& keys,
                                             const std::vector<InbetweenMethod>& methods, int count) {
  std::vector<KeySurface> out;
  for (size_t i = 0; i < keys.size(); ++i) {
    out.push_back(keys[i]);
    const InbetweenMethod m = i < methods.size() ? methods[i] : InbetweenMethod::Handles;
    if (i + 1 < keys.size() && m != InbetweenMethod::Handles && same_connectivity(keys[i], keys[i + 1]))
      for (KeySurface& s : mesh_inbetweens(keys[i], keys[i + 1], count, m)) out.push_back(std::move(s));
  }
  return out;
}

}  // namespace dfm
