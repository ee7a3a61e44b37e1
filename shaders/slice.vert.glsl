// Animation manifold slicing, vertex stage: passes the 4D vertex (x, y, z, t) to slice.geom.glsl.
layout(location = 0) in vec4 a_position;
out vec4 v_position;
void main() {
  v_position = a_position;
  gl_Position = vec4(a_position.xyz, 1.0);
}
