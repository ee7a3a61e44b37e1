#pragma once
// An animation manifold through key surfaces of any connectivity: neighbouring keys that share one
// triangle list are joined by the exact prism build (manifold.h), others by a transition
// (transition.h). Slabs follow each other in time; each run of same-connectivity keys shares its
// layer vertices, a transition has its own copies of its two keys' vertices. The last few
// transitions built are kept, so asking again for the same keys costs a comparison.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/anim/manifold.h"
#include "core/anim/transition.h"

namespace dfm {

struct KeySurface {
  double time = 0;
  Eigen::MatrixXd V;  // #V x 3
  Eigen::MatrixXi F;  // #F x 3, outward
  std::string name;   // for messages (a file name, "key 2", ...)
  // Picked pairs toward the next key (TransitionOptions::pairs: x y z on this key, x y z on the next),
  // used where the two are joined by a transition; #pairs x 6 or empty.
  Eigen::MatrixXd pairs_to_next = Eigen::MatrixXd(0, 6);
};

struct SequenceStats {
  int prism_slabs = 0, transition_slabs = 0;
  TransitionStats transitions;  // summed over the transitions
  double seconds = 0;
};

// Keys sorted by strictly increasing time (>= 2). Throws dfm::Error naming the key on a bad key
// (see check_transition_key for keys that need a transition) or unsorted times.
// `progress(done, total)` is called after each slab; returning false cancels (dfm::Error).
AnimationManifold build_manifold_sequence(const std::vector<KeySurface>& keys,
                                          const TransitionOptions& options = {},
                                          SequenceStats* stats = nullptr,
                                          const std::function<bool(int, int)>& progress = {});

// True when two keys can be joined by the prism build (same vertex count and the same triangles).
bool same_connectivity(const KeySurface& a, const KeySurface& b);

}  // namespace dfm
