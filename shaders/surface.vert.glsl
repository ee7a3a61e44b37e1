// Surface pass: a PosNormal vertex (world space) plus one optional vec4 of per-vertex data
// (x = scalar for the weight map, rgb = colour for the all-handles blend).
//
// Compiled with INTERVAL, the vertex is one slice vertex of a cached interval of an animation manifold
// (render/interval_slice_pass.h, issue 16): the manifold edge behind it, fixed over the interval, is
// interpolated to the frame's time here, so playback draws straight from the interval's records. The
// rules are core/anim/slice.cpp's (and core/anim/interval_slice.cpp's): from the edge's later endpoint
// with mu = (t_up - t) / (t_up - t_down), positions and the endpoints' 3D normals (4D vertex normals
// without t, renormalised, on the CPU at upload). mu is linear in t: mu = A + B (t - t_lo), with
// A = (t_up - t_lo) / (t_up - t_down) and B = -1 / (t_up - t_down) computed in double at upload and
// u_dt = t - t_lo in double per frame, so float rounding of the times never meets a short edge in time
// (a transition's edges can be far shorter in time than float resolution of t relative to their
// length in space).
// Compiled with CAPTURE as well, it writes the world-space vertex by transform feedback
// instead: the read-back of exactly what is drawn.
#ifdef INTERVAL
layout(location = 0) in vec3 a_up;       // x y z of the edge's later endpoint
layout(location = 1) in vec3 a_n_up;     // its unit 3D slice normal
layout(location = 3) in vec3 a_down;     // ... and of its earlier one
layout(location = 4) in vec3 a_n_down;
layout(location = 5) in vec2 a_mu;       // A, B
uniform float u_dt;                      // t - t_lo
#else
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
#endif
layout(location = 2) in vec4 a_data;

uniform mat4 u_view;
uniform mat4 u_proj;

#ifdef CAPTURE
out vec3 out_position;
out vec3 out_normal;
#else
// Without the wireframe geometry shader (a program without WIREFRAME) the outputs go straight to
// the fragment shader, under its input names.
#ifndef WIREFRAME
#define v_pos_view g_pos_view
#define v_normal_view g_normal_view
#define v_data g_data
#endif
out vec3 v_pos_view;
out vec3 v_normal_view;
out vec4 v_data;
#endif

void main() {
#ifdef INTERVAL
  float mu = clamp(a_mu.x + a_mu.y * u_dt, 0.0, 1.0);
  vec3 position = a_up + mu * (a_down - a_up);
  vec3 normal = a_n_up + mu * (a_n_down - a_n_up);
  float len = length(normal);
  normal = len > 0.0 ? normal / len : vec3(0.0);
#else
  vec3 position = a_position;
  vec3 normal = a_normal;
#endif
#ifdef CAPTURE
  out_position = position;
  out_normal = normal;
  gl_Position = vec4(position, 1.0);
#else
  vec4 p = u_view * vec4(position, 1.0);
  v_pos_view = p.xyz;
  v_normal_view = mat3(u_view) * normal;  // the view matrix is rigid
  v_data = a_data;
  gl_Position = u_proj * p;
#endif
}
