#include "core/anim/frame_sequence.h"

#include <cstdio>

#include "core/anim/manifold_frame.h"
#include "core/mesh/io.h"
#include "core/util/error.h"

namespace dfm {

FrameNaming frame_naming(const std::string& prefix) {
  for (const char* e : {".obj", ".ply", ".off", ".stl"}) {
    const std::string ext = e;
    if (prefix.size() > ext.size() && prefix.compare(prefix.size() - ext.size(), ext.size(), ext) == 0)
      return {prefix.substr(0, prefix.size() - ext.size()), ext};
  }
  return {prefix, ".obj"};
}

std::string frame_path(const FrameNaming& naming, int index) {
  char num[16];
  std::snprintf(num, sizeof num, "%04d", index);
  return naming.stem + num + naming.ext;
}

double frame_time(double t0, double t1, int index, int count) {
  return count <= 1 ? t0 : t0 + (t1 - t0) * index / (count - 1);
}

std::vector<std::string> write_frame_sequence(const AnimationManifold& m, const std::string& prefix, int count) {
  if (count < 1) throw Error("frame sequence " + prefix + ": needs at least one frame, got " + std::to_string(count));
  if (m.num_tets() == 0 || m.times.empty()) throw Error("frame sequence " + prefix + ": the animation is empty");
  const FrameNaming naming = frame_naming(prefix);
  std::vector<std::string> paths;
  for (int i = 0; i < count; ++i) {
    paths.push_back(frame_path(naming, i));
    write_surface(paths.back(), manifold_frame(m, frame_time(m.times.front(), m.times.back(), i, count)).mesh);
  }
  return paths;
}

}  // namespace dfm
