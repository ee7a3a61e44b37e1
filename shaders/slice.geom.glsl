// Animation manifold slicing, geometry stage: one tetrahedron in (4 vertices as lines_adjacency),
// 0, 1 or 2 triangles out, captured by transform feedback as PosNormal (render/vertex_format.h).
// The case table is not written here: render/slice_pass.cpp uploads the one derived in
// core/anim/slice_table.cpp, and the rules mirror core/anim/slice.h (ties, exact vertices,
// interpolation from the above endpoint, winding flip on x and z).
layout(lines_adjacency) in;
layout(triangle_strip, max_vertices = 6) out;

in vec4 v_position[];
out vec3 out_position;
out vec3 out_normal;

uniform int u_axis;              // 0..3 = x, y, z, t
uniform float u_value;           // the hyperplane: coordinate u_axis == u_value
uniform bool u_on_plane_above;   // vertices on the hyperplane count as above
uniform bool u_flip;             // reverse the table's winding (x and z)
uniform int u_cases[16];         // bits 0-1: triangle count; then 3 bits per corner edge index
uniform ivec2 u_edges[6];        // the tetrahedron's edges as vertex pairs

vec3 drop_axis(vec4 p) {
  if (u_axis == 0) return p.yzw;
  if (u_axis == 1) return p.xzw;
  if (u_axis == 2) return p.xyw;
  return p.xyz;
}

float det3(vec3 a, vec3 b, vec3 c) { return dot(a, cross(b, c)); }

void main() {
  vec4 p[4];
  float s[4];
  int mask = 0;
  for (int i = 0; i < 4; ++i) {
    p[i] = v_position[i];
    s[i] = p[i][u_axis] - u_value;
    bool above = u_on_plane_above ? s[i] >= 0.0 : s[i] > 0.0;
    if (above) mask |= 1 << i;
  }
  if (mask == 0 || mask == 15) return;

  // 4D normal, <N, w> = det[w, e1, e2, e3] (the generalized cross product), axis dropped.
  vec4 e1 = p[1] - p[0], e2 = p[2] - p[0], e3 = p[3] - p[0];
  vec4 N = vec4(det3(e1.yzw, e2.yzw, e3.yzw), -det3(e1.xzw, e2.xzw, e3.xzw),
                det3(e1.xyw, e2.xyw, e3.xyw), -det3(e1.xyz, e2.xyz, e3.xyz));
  vec3 n = drop_axis(N);
  float len = length(n);
  n = len > 0.0 ? n / len : vec3(0.0);

  int code = u_cases[mask];
  int count = code & 3;
  for (int t = 0; t < count; ++t) {
    vec3 q[3];
    int id[3];
    for (int j = 0; j < 3; ++j) {
      int e = (code >> (2 + 3 * (3 * t + j))) & 7;
      int a = u_edges[e].x, b = u_edges[e].y;
      if (s[a] == 0.0) {
        q[j] = drop_axis(p[a]);
        id[j] = a;
      } else if (s[b] == 0.0) {
        q[j] = drop_axis(p[b]);
        id[j] = b;
      } else {
        int up = s[a] > 0.0 ? a : b;
        int dn = s[a] > 0.0 ? b : a;
        float mu = s[up] / (s[up] - s[dn]);
        vec3 pu = drop_axis(p[up]);
        q[j] = pu + mu * (drop_axis(p[dn]) - pu);
        id[j] = 4 + e;
      }
    }
    if (id[0] == id[1] || id[1] == id[2] || id[0] == id[2]) continue;  // collapsed onto a vertex
    int order[3] = int[3](0, u_flip ? 2 : 1, u_flip ? 1 : 2);
    for (int j = 0; j < 3; ++j) {
      out_position = q[order[j]];
      out_normal = n;
      EmitVertex();
    }
    EndPrimitive();
  }
}
