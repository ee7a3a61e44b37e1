// Anti-aliased wide line: alpha falls off over the last pixel on each side.
in vec4 g_color;
noperspective in float g_across;
uniform float u_line_width;
out vec4 frag_color;
void main() {
  float half_w = 0.5 * u_line_width + 1.0;
  float d = abs(g_across) * half_w;  // pixels from the centre line
  float a = clamp(half_w - d, 0.0, 1.0);
  frag_color = vec4(g_color.rgb, g_color.a * a);
}
