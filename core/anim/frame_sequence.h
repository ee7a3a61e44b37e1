#pragma once
// Frames of an animation manifold saved as a numbered file sequence: the one rule the script's
// save-frames, the editor's File > Save frames and `deform manifold --sequence` share.
//
// PREFIX names the files: "out/walk" and "out/walk.obj" both give out/walk0000.obj, out/walk0001.obj, ...;
// "out/walk.ply" (or .off, .stl) picks that format. COUNT frames (manifold_frame.h) at times evenly spaced from the
// manifold's first to its last time, both included (one frame: the first time).
#include <string>
#include <vector>

#include "core/anim/manifold.h"

namespace dfm {

constexpr int kDefaultFrameCount = 30;

struct FrameNaming {
  std::string stem;  // PREFIX without a surface extension
  std::string ext;   // ".obj" (default), ".ply", ".off" or ".stl"
};

FrameNaming frame_naming(const std::string& prefix);
// stem + four-digit index + ext.
std::string frame_path(const FrameNaming& naming, int index);
// Time of frame `index` of `count` over [t0, t1].
double frame_time(double t0, double t1, int index, int count);

// Writes the COUNT slices (atomic saves, as write_surface does); returns the paths in order. Throws
// dfm::Error for count < 1, a manifold without tets, or a file that cannot be written (naming it).
std::vector<std::string> write_frame_sequence(const AnimationManifold& m, const std::string& prefix, int count);

}  // namespace dfm
