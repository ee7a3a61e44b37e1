// Exported glTF files pass the Khronos glTF Validator (npm package gltf-validator, run with Node.js)
// with zero errors and zero warnings. The validator is installed into tests/gltf/node_modules on first
// use; when it cannot be installed the test fails under CI=true and is skipped (with a warning) elsewhere.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/export/gltf_export.h"
#include "core/skin/lbs.h"
#include "tests/test_gltf_fixtures.h"
#include "tests/test_gltf_validator.h"
#include "tests/test_support.h"

using namespace dfm;
namespace fs = std::filesystem;

TEST_CASE("validator: synthetic rig exports (.glb/.gltf, 4/8 influences, morph and residual targets) are clean", "[gltf][validator]") {
  if (!test::gltf_validator_ready()) return;
  const fs::path dir = test::gltf_temp_dir("validator");
  GltfExportInput in = test::synthetic_input();
  std::vector<std::string> files;
  for (int k : {4, 8})
    for (const std::string ext : {"glb", "gltf"}) {
      files.push_back((dir / ("tube" + std::to_string(k) + "." + ext)).string());
      export_gltf(files.back(), in, {k});
    }
  for (size_t i = 0; i < in.keys.size(); ++i) {
    in.morph_frames.push_back(lbs(in.surface.V, in.weights, in.keys[i].pose));
    in.morph_times.push_back(in.keys[i].time);
  }
  files.push_back((dir / "morph.gltf").string());
  export_gltf(files.back(), in, {4});
  // Residual morph targets on the skinned mesh, animated with the keys (plus the baked frames above).
  GltfExportOptions residual;
  residual.residual_morph_tolerance = 1e-6;
  files.push_back((dir / "residual.glb").string());
  CHECK(export_gltf(files.back(), in, residual).residual_targets == static_cast<int>(in.keys.size()) + 1);
  // No keys at all: no animation, the current pose only.
  in.keys.clear();
  in.morph_frames.clear();
  in.morph_times.clear();
  files.push_back((dir / "still.glb").string());
  export_gltf(files.back(), in, {4});
  files.push_back((dir / "still-residual.glb").string());
  CHECK(export_gltf(files.back(), in, residual).residual_targets == 1);
  for (const auto& f : files) test::check_gltf_valid(f);
  fs::remove_all(dir);
}

TEST_CASE("validator: a broken file is caught (the harness can fail)", "[gltf][validator]") {
  if (!test::gltf_validator_ready()) return;
  const fs::path dir = test::gltf_temp_dir("broken");
  const std::string path = (dir / "broken.gltf").string();
  std::ofstream(path) << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":3}],"scenes":[{"nodes":[0]}]})";
  const nlohmann::json r = test::run_gltf_validator(path);
  CHECK(r.value("errors", 0) > 0);
  fs::remove_all(dir);
}
