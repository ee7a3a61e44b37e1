#pragma once
// What every glTF writer here shares: typed arrays appended to the model's one buffer, and the atomic
// save of a model as .glb or as .gltf + <stem>.bin.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <tiny_gltf.h>

namespace dfm {

// Appends typed arrays to buffer 0, one bufferView per accessor (4-byte aligned, tightly packed).
class GltfBufferBuilder {
 public:
  explicit GltfBufferBuilder(tinygltf::Model& model);

  // Floats, `width` components per element; min/max written when asked (POSITION, morph targets,
  // animation input). target: TINYGLTF_TARGET_ARRAY_BUFFER for vertex data, 0 for animation and skin data.
  int add_floats(const std::vector<float>& data, int width, int type, int target, bool bounds,
                 const std::string& name = "");

  template <class T>
  int add_ints(const std::vector<T>& data, int width, int type, int component_type, int target) {
    tinygltf::Accessor a;
    a.bufferView = add_view(data.data(), data.size() * sizeof(T), target);
    a.componentType = component_type;
    a.count = data.size() / width;
    a.type = type;
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

 private:
  int add_view(const void* bytes, size_t size, int target);
  tinygltf::Model& model_;
};

// Appends a LINEAR sampler (input: an accessor of times, output: `values`, `width` floats per key) and a
// channel driving `path` ("translation", "rotation", "scale", "weights") of `node`.
void add_linear_channel(tinygltf::Animation& anim, GltfBufferBuilder& bb, int node, const std::string& path, int input,
                        const std::vector<float>& values, int type, int width);

// Row-major floats of a matrix (one element per row).
std::vector<float> rows_to_floats(const Eigen::MatrixXd& M);

// Writes `path` atomically: .glb (binary, buffer embedded) or .gltf with <stem>.bin beside it.
// Throws dfm::Error naming the path when serialization or a write fails.
void write_gltf_model(const std::string& path, tinygltf::Model& model);

}  // namespace dfm
