#include "core/scene/key_pairs.h"

#include <string>

#include "core/anim/manifold_sequence.h"
#include "core/anim/transition.h"
#include "core/scene/key_surfaces.h"
#include "core/util/error.h"

namespace dfm {

int pair_interval(const Document& doc, double t) {
  const int n = static_cast<int>(doc.keys().size());
  if (n < 2) throw Error("picked pairs join two keys: the animation has " + std::to_string(n));
  int k = 0;
  while (k + 2 < n && doc.keys()[k + 1].time <= t) ++k;
  return k;
}

void add_key_pair(Document& doc, int index, const Eigen::Matrix<double, 1, 6>& pair) {
  const int n = static_cast<int>(doc.keys().size());
  if (index < 0 || index + 1 >= n) throw Error("picked pairs join a key to the next: no key after key " + std::to_string(index));
  const std::vector<KeySurface> surfaces = key_surfaces(doc);
  const KeySurface *a = nullptr, *b = nullptr;
  for (const KeySurface& s : surfaces) {
    if (s.time == doc.keys()[index].time) a = &s;
    if (s.time == doc.keys()[index + 1].time) b = &s;
  }
  if (!a || !b) throw Error("the keys at " + std::to_string(doc.keys()[index].time) + " and " +
                            std::to_string(doc.keys()[index + 1].time) + " have no surfaces yet (bind first)");
  if (same_connectivity(*a, *b))
    throw Error("the keys at " + std::to_string(a->time) + " and " + std::to_string(b->time) +
                " share one connectivity: picked pairs steer transitions between different meshes");
  const Eigen::MatrixXd& old = doc.keys()[index].pairs_to_next;
  Eigen::MatrixXd pairs(old.rows() + 1, 6);
  if (old.rows() > 0) pairs.topRows(old.rows()) = old;
  pairs.bottomRows(1) = pair;
  if (const auto bad = transition_pair_problem({a->V, a->F, {}}, {b->V, b->F, {}}, pairs))
    throw Error("picked pair " + std::to_string(bad->pair + 1) + ": " + bad->problem);
  doc.set_key_pairs(index, pairs);
}

}  // namespace dfm
