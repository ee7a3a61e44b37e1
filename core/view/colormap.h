#pragma once
// The turbo colour map (Mikhailov 2019) as its polynomial fit: perceptually ordered, readable on dark
// themes. This is the one copy of its coefficients: the Weights panel's legend evaluates turbo() here and
// the surface shader receives the same numbers as #defines (turbo_shader_defines).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace dfm::view {

// x clamped to [0, 1]; RGB in about [0, 1].
Eigen::Vector3d turbo(double x);

// "TURBO_R vec4(c0, c1, c2, c3)", "TURBO_R2 vec2(c4, c5)" and the same for G and B, for ProgramDesc::defines:
// turbo(x) = dot(TURBO_R, (1, x, x^2, x^3)) + dot(TURBO_R2, (x^4, x^5)), per channel.
std::vector<std::string> turbo_shader_defines();

}  // namespace dfm::view
