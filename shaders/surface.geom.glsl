// Single-pass wireframe (Baerentzen et al. 2006): each fragment learns its screen-space distance to
// the triangle's three edges, so the fragment shader can draw anti-aliased edges on the shaded surface.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

uniform vec2 u_viewport;

in vec3 v_pos_view[];
in vec3 v_normal_view[];
in vec4 v_data[];

out vec3 g_pos_view;
out vec3 g_normal_view;
out vec4 g_data;
noperspective out vec3 g_edge_dist;

void main() {
  vec2 s[3];
  for (int i = 0; i < 3; ++i) s[i] = u_viewport * 0.5 * gl_in[i].gl_Position.xy / gl_in[i].gl_Position.w;
  vec2 e0 = s[2] - s[1], e1 = s[2] - s[0], e2 = s[1] - s[0];
  float area = abs(e1.x * e2.y - e1.y * e2.x);
  vec3 h = vec3(area / max(length(e0), 1e-6), area / max(length(e1), 1e-6), area / max(length(e2), 1e-6));
  for (int i = 0; i < 3; ++i) {
    g_pos_view = v_pos_view[i];
    g_normal_view = v_normal_view[i];
    g_data = v_data[i];
    g_edge_dist = vec3(i == 0 ? h.x : 0.0, i == 1 ? h.y : 0.0, i == 2 ? h.z : 0.0);
    gl_Position = gl_in[i].gl_Position;
    EmitVertex();
  }
  EndPrimitive();
}
