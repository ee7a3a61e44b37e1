// Expands each line into a screen-space quad u_line_width pixels wide (core profile has no wide lines).
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 u_viewport;
uniform float u_line_width;

in vec4 v_color[];
out vec4 g_color;
noperspective out float g_across;  // -1..1 across the line, for anti-aliasing

void main() {
  vec4 p0 = gl_in[0].gl_Position, p1 = gl_in[1].gl_Position;
  // Clip a segment crossing the camera plane so its projection stays finite.
  float eps = 1e-4;
  if (p0.w < eps && p1.w < eps) return;
  if (p0.w < eps) p0 = mix(p0, p1, (eps - p0.w) / (p1.w - p0.w));
  if (p1.w < eps) p1 = mix(p1, p0, (eps - p1.w) / (p0.w - p1.w));
  vec2 s0 = p0.xy / p0.w * u_viewport * 0.5, s1 = p1.xy / p1.w * u_viewport * 0.5;
  vec2 d = s1 - s0;
  float len = length(d);
  vec2 dir = len > 1e-6 ? d / len : vec2(1.0, 0.0);
  vec2 off = vec2(-dir.y, dir.x) * (0.5 * u_line_width + 1.0) / (u_viewport * 0.5);
  g_color = v_color[0]; g_across = -1.0; gl_Position = vec4(p0.xy + off * p0.w, p0.zw); EmitVertex();
  g_color = v_color[0]; g_across = 1.0;  gl_Position = vec4(p0.xy - off * p0.w, p0.zw); EmitVertex();
  g_color = v_color[1]; g_across = -1.0; gl_Position = vec4(p1.xy + off * p1.w, p1.zw); EmitVertex();
  g_color = v_color[1]; g_across = 1.0;  gl_Position = vec4(p1.xy - off * p1.w, p1.zw); EmitVertex();
  EndPrimitive();
}
