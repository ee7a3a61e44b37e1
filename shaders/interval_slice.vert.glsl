// Playback of one cached time interval (t_lo, t_hi) of an animation manifold
// (render/interval_slice_pass.h): one slice vertex in, its position and smooth normal at time t out
// (transform feedback into PosNormal, rasterizer off). The edge behind the vertex is fixed over the
// interval; the rules are core/anim/slice.cpp's (and core/anim/interval_slice.cpp's): interpolate from
// the above endpoint (the later one) with mu = (t_up - t) / (t_up - t_down), positions and the
// endpoints' 3D normals (4D vertex normals without t, renormalised, on the CPU at upload), then
// renormalise the normal.
// mu is linear in t: mu = A + B (t - t_lo), with A = (t_up - t_lo) / (t_up - t_down) and
// B = -1 / (t_up - t_down) computed in double at upload, and u_dt = t - t_lo in double per frame.
// So float rounding of the times never meets a short edge in time (a transition has edges whose
// endpoints' times differ by far less than float resolution of t relative to their length in space).
layout(location = 0) in vec3 a_up;       // x y z of the edge's later endpoint
layout(location = 1) in vec3 a_down;     // ... and of its earlier one
layout(location = 2) in vec3 a_n_up;     // their unit 3D slice normals
layout(location = 3) in vec3 a_n_down;
layout(location = 4) in vec2 a_mu;       // A, B

uniform float u_dt;  // t - t_lo

out vec3 out_position;
out vec3 out_normal;

void main() {
  float mu = clamp(a_mu.x + a_mu.y * u_dt, 0.0, 1.0);
  out_position = a_up + mu * (a_down - a_up);
  vec3 n = a_n_up + mu * (a_n_down - a_n_up);
  float len = length(n);
  out_normal = len > 0.0 ? n / len : vec3(0.0);
  gl_Position = vec4(out_position, 1.0);
}
