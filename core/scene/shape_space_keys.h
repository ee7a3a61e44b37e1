#pragma once
// Shape spaces (Alexa 2002, ch. 5; core/anim/shape_space.h) over the document's keys: what the editor's
// Shape space panel and the script's `shape-space-key` do. Pose keys give their posed surface (skinned
// with the document's method and weights, as the animation passes through them: key_surfaces), mesh
// keys their mesh; all must share one connectivity.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/anim/shape_space.h"
#include "core/scene/document.h"

namespace dfm {

// A shape space whose base i is the key at times[i] (each a key's time within 1e-9). Throws
// dfm::Error: no key at a time, a key listed twice, pose keys without weights, keys of different
// connectivity (naming the key).
ShapeSpace key_shape_space(const Document& doc, const std::vector<double>& times, ShapeMorph morph);

// The informational name of a synthesized key ("shape space linear 0.2 0.5 0.3").
std::string shape_space_key_name(const ShapeSpace& space, const Eigen::VectorXd& x);

// Synthesizes `space` at coordinates x and keys the shape at time t (Document::key_mesh: one undo step;
// the surface's triangles join their neighbours by the prism build). `ready`, when it has the bases'
// rows: that synthesis, already made (the editor's cursor), keyed as is. Returns the keyed mesh.
TriMesh key_synthesized_shape(Document& doc, ShapeSpace& space, const Eigen::VectorXd& x, double t,
                              const Eigen::MatrixXd& ready = {});

}  // namespace dfm
