// Round, outlined point sprites for handles.
in vec4 v_color;
out vec4 frag_color;
void main() {
  vec2 c = gl_PointCoord * 2.0 - 1.0;
  float r = length(c);
  if (r > 1.0) discard;
  float edge = smoothstep(0.68, 0.78, r);
  vec3 rgb = mix(v_color.rgb, vec3(0.04), edge);
  float a = 1.0 - smoothstep(0.9, 1.0, r);
  frag_color = vec4(rgb, v_color.a * a);
}
