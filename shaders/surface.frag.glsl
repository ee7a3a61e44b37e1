// Surface shading: a key and a fill light in view space plus a sky/ground ambient; back faces of open
// meshes in their own colour; optional weight colour map with isolines, vertex colours, and (compiled
// with WIREFRAME, after surface.geom.glsl) the wireframe.
in vec3 g_pos_view;
in vec3 g_normal_view;
in vec4 g_data;
#ifdef WIREFRAME
noperspective in vec3 g_edge_dist;
#endif

uniform vec3 u_base_color;
uniform vec3 u_back_color;
uniform int u_color_mode;      // 0 shaded, 1 scalar colour map (data.x) + isolines, 2 vertex colour (data.rgb)
uniform float u_isolines;      // number of isoline intervals over [0,1]; 0 = none
uniform vec3 u_wire_color;
uniform int u_flat;            // 1: faceted normals from screen-space derivatives

out vec4 frag_color;

// Turbo colour map (Mikhailov 2019), polynomial fit; its coefficients come as #defines from
// core/view/colormap.cpp (turbo_shader_defines), the one copy the Weights panel's legend uses too.
vec3 turbo(float x) {
  x = clamp(x, 0.0, 1.0);
  vec4 v4 = vec4(1.0, x, x * x, x * x * x);
  vec2 v2 = v4.zw * v4.z;
  return vec3(dot(v4, TURBO_R) + dot(v2, TURBO_R2), dot(v4, TURBO_G) + dot(v2, TURBO_G2),
              dot(v4, TURBO_B) + dot(v2, TURBO_B2));
}

void main() {
  vec3 n = normalize(g_normal_view);
  if (u_flat == 1) n = normalize(cross(dFdx(g_pos_view), dFdy(g_pos_view)));
  vec3 view_dir = normalize(-g_pos_view);
  bool front = gl_FrontFacing;
  if (!front) n = -n;

  vec3 albedo = front ? u_base_color : u_back_color;
  float iso = 0.0;
  if (front && u_color_mode == 1) {
    float w = g_data.x;
    albedo = turbo(w);
    if (u_isolines > 0.0) {
      float f = w * u_isolines;
      float d = abs(fract(f - 0.5) - 0.5) / max(fwidth(f), 1e-5);
      // Interior levels only: where w is exactly 0 (or 1) over a triangle, fwidth is 0 and the
      // level-0 line would cover the whole zero region with dark blotches.
      float level = floor(f + 0.5);
      if (level >= 1.0 && level <= u_isolines - 1.0) iso = 1.0 - clamp(d - 0.5, 0.0, 1.0);
    }
  } else if (front && u_color_mode == 2) {
    albedo = g_data.rgb;
  }

  // Key light from upper left, fill from lower right, both attached to the camera.
  vec3 key_dir = normalize(vec3(-0.45, 0.65, 0.62));
  vec3 fill_dir = normalize(vec3(0.6, -0.25, 0.75));
  float key = max(dot(n, key_dir), 0.0);
  float fill = max(dot(n, fill_dir), 0.0);
  float hemi = 0.5 + 0.5 * n.y;
  vec3 ambient = mix(vec3(0.10, 0.09, 0.09), vec3(0.22, 0.24, 0.28), hemi);
  vec3 h = normalize(key_dir + view_dir);
  // x^48 and x^3 by products: pow costs a log and an exp per fragment on software GL.
  float s1 = max(dot(n, h), 0.0), s2 = s1 * s1, s4 = s2 * s2, s8 = s4 * s4, s16 = s8 * s8, s32 = s16 * s16;
  float spec = front ? s32 * s16 * 0.25 : 0.0;
  float r1 = 1.0 - max(dot(n, view_dir), 0.0);
  float rim = r1 * r1 * r1 * 0.18;
  vec3 color = albedo * (ambient + 0.85 * key * vec3(1.0, 0.96, 0.90) + 0.28 * fill * vec3(0.70, 0.80, 1.0)) +
               vec3(spec) + rim * vec3(0.55, 0.65, 0.85);
  color = mix(color, vec3(0.05), iso * 0.85);

#ifdef WIREFRAME
  float d = min(g_edge_dist.x, min(g_edge_dist.y, g_edge_dist.z));
  float a = 1.0 - smoothstep(0.4, 1.2, d);
  color = mix(color, u_wire_color, a * 0.8);
#endif
  // Display gamma: shading is computed in linear space.
  frag_color = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
