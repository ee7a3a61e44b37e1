// Surface pass: a PosNormal vertex (world space) plus one optional vec4 of per-vertex data
// (x = scalar for the weight map, rgb = colour for the all-handles blend).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_data;

uniform mat4 u_view;
uniform mat4 u_proj;

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

void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_pos_view = p.xyz;
  v_normal_view = mat3(u_view) * a_normal;  // the view matrix is rigid
  v_data = a_data;
  gl_Position = u_proj * p;
}
