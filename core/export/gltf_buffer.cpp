#include "core/export/gltf_buffer.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {

GltfBufferBuilder::GltfBufferBuilder(tinygltf::Model& model) : model_(model) {
  if (model_.buffers.empty()) model_.buffers.emplace_back();
}

int GltfBufferBuilder::add_floats(const std::vector<float>& data, int width, int type, int target, bool bounds,
                                  const std::string& name) {
  tinygltf::Accessor a;
  a.bufferView = add_view(data.data(), data.size() * sizeof(float), target);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = data.size() / width;
  a.type = type;
  a.name = name;
  if (bounds) {
    a.minValues.assign(width, std::numeric_limits<double>::infinity());
    a.maxValues.assign(width, -std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < data.size(); ++i) {
      a.minValues[i % width] = std::min<double>(a.minValues[i % width], data[i]);
      a.maxValues[i % width] = std::max<double>(a.maxValues[i % width], data[i]);
    }
  }
  model_.accessors.push_back(a);
  return static_cast<int>(model_.accessors.size()) - 1;
}

int GltfBufferBuilder::add_view(const void* bytes, size_t size, int target) {
  auto& buf = model_.buffers[0].data;
  while (buf.size() % 4) buf.push_back(0);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = buf.size();
  v.byteLength = size;
  v.target = target;  // 0 (unset) for animation and skin data
  const auto* p = static_cast<const unsigned char*>(bytes);
  buf.insert(buf.end(), p, p + size);
  model_.bufferViews.push_back(v);
  return static_cast<int>(model_.bufferViews.size()) - 1;
}

void add_linear_channel(tinygltf::Animation& anim, GltfBufferBuilder& bb, int node, const std::string& path, int input,
                        const std::vector<float>& values, int type, int width) {
  tinygltf::AnimationSampler s;
  s.input = input;
  s.output = bb.add_floats(values, width, type, 0, false);
  s.interpolation = "LINEAR";
  anim.samplers.push_back(s);
  tinygltf::AnimationChannel c;
  c.sampler = static_cast<int>(anim.samplers.size()) - 1;
  c.target_node = node;
  c.target_path = path;
  anim.channels.push_back(c);
}

std::vector<float> rows_to_floats(const Eigen::MatrixXd& M) {
  std::vector<float> out(M.size());
  for (int i = 0; i < M.rows(); ++i)
    for (int j = 0; j < M.cols(); ++j) out[i * M.cols() + j] = static_cast<float>(M(i, j));
  return out;
}

void write_gltf_model(const std::string& path, tinygltf::Model& model) {
  const std::string ext = file_extension(path);
  tinygltf::TinyGLTF writer;
  if (ext == "glb") {
    write_file_atomic(
        path,
        [&](std::ostream& os) {
          if (!writer.WriteGltfSceneToStream(&model, os, false, true)) throw Error(path + ": glTF serialization failed");
        },
        true);
    return;
  }
  // .gltf + <stem>.bin: tinygltf's stream writer embeds buffers as data URIs, so write the bin file
  // ourselves (atomically) and point the buffer at it.
  const std::filesystem::path p(path);
  const std::string bin_name = p.stem().string() + ".bin";
  const std::string bin_path = (p.parent_path() / bin_name).string();
  const std::vector<unsigned char> bin = model.buffers.at(0).data;
  write_file_atomic(bin_path, [&](std::ostream& os) { os.write(reinterpret_cast<const char*>(bin.data()), bin.size()); },
                    true);
  std::ostringstream json_text;
  if (!writer.WriteGltfSceneToStream(&model, json_text, true, false)) throw Error(path + ": glTF serialization failed");
  nlohmann::json j = nlohmann::json::parse(json_text.str());
  j["buffers"][0] = nlohmann::json{{"byteLength", bin.size()}, {"uri", bin_name}};
  write_file_atomic(path, [&](std::ostream& os) { os << j.dump(2) << "\n"; });
}

}  // namespace dfm
