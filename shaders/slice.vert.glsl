// Animation manifold slicing, vertex stage: passes the 4D vertex (x, y, z, t) and its unit 4D normal
// (core/anim/manifold_normals.h) to slice.geom.glsl.
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_normal;
out vec4 v_position;
out vec4 v_normal;
void main() {
  v_position = a_position;
  v_normal = a_normal;
  gl_Position = vec4(a_position.xyz, 1.0);
}
