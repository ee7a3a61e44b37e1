// Skinning by transform feedback: rest position + normal -> posed position + normal (PosNormal).
// One method per compiled program: METHOD_LBS, METHOD_DQS, METHOD_STBS or METHOD_STBS_DQS.
// Mirrors core/skin/{lbs,dqs,stbs,stbs_dqs}.cpp term by term (the double-precision references).
// Influences: every nonzero weight of the vertex, in compressed sparse rows (SparseInfluences):
//   row_offsets  R32I, #V + 1: vertex i's entries are row_offsets[i] .. row_offsets[i + 1] - 1
//   pairs        RG32I per entry: handle index, float bits of the weight (largest weight first)
//   endpoints    R32F per entry: STBS bone endpoint weight e
// Handle data: a texture buffer (RGBA32F), HANDLE_TEXELS texels per handle:
//   0-2  rows of [A | t]
//   3    dual quaternion real part (x y z w)      4  dual part
//   5-7  rows of the DQS stretch S = R^T A
//   8    STBS: bone origin a (xyz), twist angle at the second joint (w)
//   9    STBS: unit bone axis (xyz), 1 if the bone is active (w)
//   10   STBS: stretch offset (sigma - 1)(b - a) (xyz), twist angle at the first joint (w)
//   11-13  STBS: rows of T' = T W^-1 (the bone without its twist/stretch) for active bones
//   14-15  STBS over DQS: the dual quaternion of T' (real, dual) for active bones
#define HANDLE_TEXELS 16
// Handles from first_additional on are additional handles (core/rig/additional_handles.h): linear
// whatever the method (their transforms may be zero, which has no dual quaternion); the DQS methods
// add their term to the position, as core/skin/skin.cpp does.

layout(location = 0) in vec3 rest_position;
layout(location = 1) in vec3 rest_normal;

uniform samplerBuffer handles;
uniform isamplerBuffer row_offsets;
uniform isamplerBuffer pairs;
uniform samplerBuffer endpoints;
uniform int first_additional;

out vec3 out_position;
out vec3 out_normal;

vec4 texel(int h, int i) { return texelFetch(handles, h * HANDLE_TEXELS + i); }

mat3 rows3(int h, int first) {
  return transpose(mat3(texel(h, first).xyz, texel(h, first + 1).xyz, texel(h, first + 2).xyz));
}

// cof(M) n, normalized: how normals transform under a linear map.
vec3 transform_normal(mat3 M, vec3 n) {
  mat3 C = mat3(cross(M[1], M[2]), cross(M[2], M[0]), cross(M[0], M[1]));
  vec3 r = C * n;
  float len = length(r);
  return len > 0.0 ? r / len : r;
}

vec3 dq_transform(vec4 r, vec4 d, vec3 p) {
  return p + 2.0 * cross(r.xyz, cross(r.xyz, p) + r.w * p) + 2.0 * (r.w * d.xyz - d.w * r.xyz + cross(r.xyz, d.xyz));
}

vec4 qmul(vec4 a, vec4 b) { return vec4(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz)); }

mat3 axis_rotation(vec3 u, float angle) {
  float c = cos(angle), s = sin(angle);
  mat3 cross_u = mat3(0.0, u.z, -u.y, -u.z, 0.0, u.x, u.y, -u.x, 0.0);  // columns: cross_u * v = u x v
  return c * mat3(1.0) + s * cross_u + (1.0 - c) * outerProduct(u, u);
}

void main() {
  int first = texelFetch(row_offsets, gl_VertexID).x;
  int last = texelFetch(row_offsets, gl_VertexID + 1).x;
  vec3 p = rest_position;
  vec3 n = rest_normal;

#if defined(METHOD_LBS) || defined(METHOD_STBS)
  vec3 q = vec3(0.0);
  mat3 A = mat3(0.0);
  for (int j = first; j < last; ++j) {
    ivec2 entry = texelFetch(pairs, j).xy;
    int h = entry.x;
    float w = intBitsToFloat(entry.y);
#ifdef METHOD_STBS
    vec4 axis = texel(h, 9);
    if (axis.w > 0.5) {
      vec4 s0 = texel(h, 11), s1 = texel(h, 12), s2 = texel(h, 13);
      mat3 L = transpose(mat3(s0.xyz, s1.xyz, s2.xyz));
      vec3 t = vec3(s0.w, s1.w, s2.w);
      vec4 origin = texel(h, 8);
      float e = texelFetch(endpoints, j).x;
      vec4 stretch = texel(h, 10);  // w: the twist at the first joint
      float angle = mix(stretch.w, origin.w, e);  // (1 - e) theta_a + e theta_b, Eq. 6.5
      mat3 R = axis_rotation(axis.xyz, angle);
      vec3 rel = p - origin.xyz;
      vec3 pp = p + (R * rel - rel) + e * stretch.xyz;
      q += w * (L * pp + t);
      A += w * (L * R);
      continue;
    }
#endif
    vec4 r0 = texel(h, 0), r1 = texel(h, 1), r2 = texel(h, 2);
    mat3 L = transpose(mat3(r0.xyz, r1.xyz, r2.xyz));
    vec3 t = vec3(r0.w, r1.w, r2.w);
    q += w * (L * p + t);
    A += w * L;
  }
  out_position = q;
  out_normal = transform_normal(A, n);
#endif

#if defined(METHOD_DQS) || defined(METHOD_STBS_DQS)
  vec4 pivot = first < last ? texel(texelFetch(pairs, first).x, 3) : vec4(0.0);
  vec4 br = vec4(0.0), bd = vec4(0.0);
  mat3 S = mat3(1.0);
  vec3 additional = vec3(0.0);
  for (int j = first; j < last; ++j) {
    ivec2 entry = texelFetch(pairs, j).xy;
    int h = entry.x;
    float w = intBitsToFloat(entry.y);
    if (h >= first_additional) {
      vec4 a0 = texel(h, 0), a1 = texel(h, 1), a2 = texel(h, 2);
      additional += w * (transpose(mat3(a0.xyz, a1.xyz, a2.xyz)) * p + vec3(a0.w, a1.w, a2.w));
      continue;
    }
    vec4 r = texel(h, 3);
    vec4 d = texel(h, 4);
#ifdef METHOD_STBS_DQS
    vec4 axis = texel(h, 9);
    if (axis.w > 0.5) {  // T' composed with the twist and stretch at this vertex's endpoint weight
      float e = texelFetch(endpoints, j).x;
      vec4 origin = texel(h, 8);
      vec4 stretch = texel(h, 10);  // w: the twist at the first joint
      float angle = mix(stretch.w, origin.w, e);  // Eq. 6.5
      vec4 q = vec4(sin(0.5 * angle) * axis.xyz, cos(0.5 * angle));
      vec3 t = origin.xyz - axis_rotation(axis.xyz, angle) * origin.xyz + e * stretch.xyz;
      vec4 tr = texel(h, 14), td = texel(h, 15);
      r = qmul(tr, q);
      d = qmul(tr, 0.5 * qmul(vec4(t, 0.0), q)) + qmul(td, q);
      if (j == first) pivot = r;
      float sw = dot(r, pivot) < 0.0 ? -w : w;
      br += sw * r;
      bd += sw * d;
      continue;  // T' is rigid: no stretch term
    }
    if (j == first) pivot = r;
#endif
    float sw = dot(r, pivot) < 0.0 ? -w : w;
    br += sw * r;
    bd += sw * d;
    S += w * (rows3(h, 5) - mat3(1.0));
  }
  float len = length(br);
  if (len == 0.0) {
    out_position = p + additional;
    out_normal = n;
  } else {
    br /= len;
    bd /= len;
    out_position = dq_transform(br, bd, S * p) + additional;
    out_normal = dq_transform(br, vec4(0.0), transform_normal(S, n));
  }
#endif
}
