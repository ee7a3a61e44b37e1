// Document commands of local transitions (document.h; the brush is local_transition.h, the blend
// core/sculpt/differential_blend.h). The offsets live on the interval's first key: the keys part.
#include <cmath>
#include <string>

#include "core/scene/document.h"
#include "core/scene/document_parts.h"
#include "core/util/error.h"

namespace dfm {

namespace {

void check_transition_keys(const std::vector<SceneKey>& keys, int index) {
  if (index < 0 || index + 1 >= static_cast<int>(keys.size()))
    throw Error("a local transition joins a key to the next: no key after key " + std::to_string(index));
  const SceneKey &a = keys[index], &b = keys[index + 1];
  if (!a.is_mesh() || !b.is_mesh() || a.mesh.V.rows() != b.mesh.V.rows() || a.mesh.F != b.mesh.F)
    throw Error("a local transition needs two mesh keys of one connectivity (keys " + std::to_string(index) + " and " +
                std::to_string(index + 1) + ")");
}

}  // namespace

void Document::paint_transition(int index, const std::vector<int>& vertices, const std::vector<double>& values) {
  check_transition_keys(s_.keys, index);
  const Eigen::Index n = s_.keys[index].mesh.V.rows();
  if (vertices.size() != values.size()) throw Error("paint transition: as many values as vertices");
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (vertices[i] < 0 || vertices[i] >= n) throw Error("paint transition: no vertex " + std::to_string(vertices[i]));
    if (!(values[i] > -1 && values[i] < 1)) throw Error("a transition offset must lie in (-1, 1)");
  }
  execute("paint local transition", kKeys, "paint transition " + std::to_string(index), [&](SceneData& s) {
    Eigen::VectorXd& o = s.keys[index].transition_to_next;
    if (o.size() != n) o = Eigen::VectorXd::Zero(n);
    for (size_t i = 0; i < vertices.size(); ++i) o[vertices[i]] = values[i];
  });
}

void Document::clear_transition(int index) {
  if (index < 0 || index >= static_cast<int>(s_.keys.size())) throw Error("no key " + std::to_string(index));
  execute("clear local transition", kKeys, "", [&](SceneData& s) { s.keys[index].transition_to_next.resize(0); });
}

}  // namespace dfm
