#include "core/scene/shape_space_keys.h"

#include <cmath>
#include <cstdio>

#include "core/scene/key_surfaces.h"
#include "core/util/error.h"

namespace dfm {

ShapeSpace key_shape_space(const Document& doc, const std::vector<double>& times, ShapeMorph morph) {
  std::vector<int> key_index;
  for (double t : times) {
    const int k = doc.key_at(t);
    if (k < 0) throw Error("no key at time " + std::to_string(t));
    for (int earlier : key_index)
      if (earlier == k) throw Error("the key at time " + std::to_string(t) + " is listed twice");
    key_index.push_back(k);
  }
  // key_surfaces holds every key (pose keys skinned) and the in-betweens; keep the keys asked for.
  const std::vector<KeySurface> all = key_surfaces(doc);
  std::vector<TriMesh> bases;
  std::vector<std::string> names;
  for (int k : key_index) {
    const double t = doc.keys()[k].time;
    for (const KeySurface& s : all)
      if (s.time == t) {
        bases.push_back(TriMesh{s.V, s.F, {}});
        char at[48];
        std::snprintf(at, sizeof at, " at t = %g", t);
        names.push_back(s.name + at);
        break;
      }
  }
  if (bases.size() != key_index.size()) throw Error("a key's surface is missing from the animation");
  return ShapeSpace(std::move(bases), std::move(names), morph);
}

std::string shape_space_key_name(const ShapeSpace& space, const Eigen::VectorXd& x) {
  std::string name = std::string("shape space ") + shape_morph_name(space.morph());
  for (int i = 0; i < x.size(); ++i) {
    char w[32];
    std::snprintf(w, sizeof w, " %.4g", x(i));
    name += w;
  }
  return name;
}

TriMesh key_synthesized_shape(Document& doc, ShapeSpace& space, const Eigen::VectorXd& x, double t,
                              const Eigen::MatrixXd& ready) {
  const bool have = ready.rows() == space.bases()[0].rows() && ready.cols() == 3;
  TriMesh mesh{have ? ready : space.synthesize(x), space.faces(), {}};
  doc.key_mesh(mesh, shape_space_key_name(space, x), t);
  return mesh;
}

}  // namespace dfm
