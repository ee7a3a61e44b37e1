// Animation manifold slicing, geometry stage: one tetrahedron in (4 vertices as lines_adjacency),
// 0, 1 or 2 triangles out, captured by transform feedback as PosNormal (render/vertex_format.h).
// The case table is not written here: render/slice_pass.cpp uploads the one derived in
// core/anim/slice_table.cpp, and the rules mirror core/anim/slice.h (ties, exact vertices,
// interpolation from the above endpoint, winding flip on x and z, smooth normals interpolated with
// the position's mu after dropping the axis).
layout(lines_adjacency) in;
layout(triangle_strip, max_vertices = 6) out;

in vec4 v_position[];
in vec4 v_normal[];
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

vec3 unit_or_zero(vec3 n) {
  float len = length(n);
  return len > 0.0 ? n / len : vec3(0.0);
}

void main() {
  vec4 p[4];
  vec3 n[4];  // the vertices' 3D normals: 4D normal without the axis, renormalised
  float s[4];
  int mask = 0;
  for (int i = 0; i < 4; ++i) {
    p[i] = v_position[i];
    n[i] = unit_or_zero(drop_axis(v_normal[i]));
    s[i] = p[i][u_axis] - u_value;
    bool above = u_on_plane_above ? s[i] >= 0.0 : s[i] > 0.0;
    if (above) mask |= 1 << i;
  }
  if (mask == 0 || mask == 15) return;

  int code = u_cases[mask];
  int count = code & 3;
  for (int t = 0; t < count; ++t) {
    vec3 q[3], qn[3];
    int id[3];
    for (int j = 0; j < 3; ++j) {
      int e = (code >> (2 + 3 * (3 * t + j))) & 7;
      int a = u_edges[e].x, b = u_edges[e].y;
      if (s[a] == 0.0) {
        q[j] = drop_axis(p[a]);
        qn[j] = n[a];
        id[j] = a;
      } else if (s[b] == 0.0) {
        q[j] = drop_axis(p[b]);
        qn[j] = n[b];
        id[j] = b;
      } else {
        int up = s[a] > 0.0 ? a : b;
        int dn = s[a] > 0.0 ? b : a;
        float mu = s[up] / (s[up] - s[dn]);
        vec3 pu = drop_axis(p[up]);
        q[j] = pu + mu * (drop_axis(p[dn]) - pu);
        qn[j] = unit_or_zero(n[up] + mu * (n[dn] - n[up]));
        id[j] = 4 + e;
      }
    }
    if (id[0] == id[1] || id[1] == id[2] || id[0] == id[2]) continue;  // collapsed onto a vertex
    int order[3] = int[3](0, u_flip ? 2 : 1, u_flip ? 1 : 2);
    for (int j = 0; j < 3; ++j) {
      out_position = q[order[j]];
      out_normal = qn[order[j]];
      EmitVertex();
    }
    EndPrimitive();
  }
}
