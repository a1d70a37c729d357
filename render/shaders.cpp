// GLSL 4.10 core sources (see shaders.h). World space is metres; normals are unit vectors.
#include "render/shaders.h"

namespace serosa::render::shaders {

// Vertex pulling: the draw is glDrawArrays(GL_PATCHES, 0, 3t), so gl_VertexID is the corner's
// position in the triangle list and gl_VertexID / 3 the triangle. Positions, normals, indices
// and per-triangle materials are read from buffer textures. (gl_PrimitiveID would be the natural
// triangle id, but llvmpipe in Mesa 22 restarts it every few hundred patches.)
const char* const kVisualVertex = R"(#version 410 core
uniform samplerBuffer u_pos;           // (n) world positions, m
uniform samplerBuffer u_nrm;           // (n) unit normals
uniform samplerBuffer u_rest;          // (2n) rest position, m, and the wound's rim; stain
uniform usamplerBuffer u_tri;          // (3t) vertex ids
uniform samplerBuffer u_tri_material;  // (2t) per triangle: colour and specular; its look
out vec3 v_pos;
out vec3 v_nrm;
out vec4 v_rest;
out float v_stain;
out vec4 v_material;
out vec4 v_look;
void main() {
  int vid = int(texelFetch(u_tri, gl_VertexID).r);
  v_pos = texelFetch(u_pos, vid).xyz;
  v_nrm = texelFetch(u_nrm, vid).xyz;
  v_rest = texelFetch(u_rest, 2 * vid);
  v_stain = texelFetch(u_rest, 2 * vid + 1).x;
  int tri = gl_VertexID / 3;
  v_material = texelFetch(u_tri_material, 2 * tri);
  v_look = texelFetch(u_tri_material, 2 * tri + 1);
}
)";

// One patch per surface triangle; the same level on every edge and inside, so neighbouring
// patches agree on their shared edge (no cracks). Level 1 leaves the triangle as it is.
// A patch wholly outside the view (its corners' bounding sphere, widened for the Phong bulge,
// beyond one of the frustum's planes) gets level 0, which discards it before it is tessellated
// and shaded: the endoscope sees a part of the organs, and a software renderer's cost follows
// the patches it tessellates.
const char* const kVisualTessControl = R"(#version 410 core
layout(vertices = 3) out;
in vec3 v_pos[];
in vec3 v_nrm[];
in vec4 v_rest[];
in float v_stain[];
in vec4 v_material[];
in vec4 v_look[];
out vec3 c_pos[];
out vec3 c_nrm[];
out vec4 c_rest[];
out float c_stain[];
patch out vec4 c_material;  // rgb: sRGB colour, a: specular strength
patch out vec4 c_look;      // vessels, lobules, mottle, kind
uniform float u_level;
uniform vec4 u_planes[6];  // the view frustum's planes, world space, unit normals pointing in
bool outside() {
  vec3 c = (v_pos[0] + v_pos[1] + v_pos[2]) / 3.0;
  float r = 1.5 * max(max(distance(c, v_pos[0]), distance(c, v_pos[1])), distance(c, v_pos[2]));
  for (int k = 0; k < 6; ++k)
    if (dot(u_planes[k].xyz, c) + u_planes[k].w < -r) return true;
  return false;
}
void main() {
  c_pos[gl_InvocationID] = v_pos[gl_InvocationID];
  c_nrm[gl_InvocationID] = v_nrm[gl_InvocationID];
  c_rest[gl_InvocationID] = v_rest[gl_InvocationID];
  c_stain[gl_InvocationID] = v_stain[gl_InvocationID];
  if (gl_InvocationID == 0) {
    c_material = v_material[0];  // the same for the three corners
    c_look = v_look[0];
    float level = outside() ? 0.0 : u_level;
    gl_TessLevelOuter[0] = level;
    gl_TessLevelOuter[1] = level;
    gl_TessLevelOuter[2] = level;
    gl_TessLevelInner[0] = level;
  }
}
)";

// Phong tessellation: the linear point p(u, v, w) is projected onto the tangent plane of each
// corner, the three projections are blended with the same barycentric weights, and the result
// is mixed with p by the shape factor alpha (0 = flat, 3/4 recommended by the paper).
// The per-triangle material comes through the control stage as a per-patch value; the rest
// position (the pattern's coordinates) is interpolated linearly.
const char* const kVisualTessEval = R"(#version 410 core
layout(triangles, equal_spacing, ccw) in;
in vec3 c_pos[];
in vec3 c_nrm[];
in vec4 c_rest[];
in float c_stain[];
patch in vec4 c_material;
patch in vec4 c_look;
out vec3 e_pos;
out vec3 e_nrm;
out vec4 e_rest;
out float e_stain;
flat out vec4 e_material;  // rgb: sRGB colour, a: specular strength
flat out vec4 e_look;      // vessels, lobules, mottle, kind (0 outside, 0.5 cut, 1 charred)
uniform mat4 u_view_proj;
uniform float u_alpha;
vec3 unit_or_zero(vec3 n) {
  float l = length(n);
  return l > 1e-12 ? n / l : vec3(0.0);
}
vec3 project(vec3 q, vec3 p, vec3 n) { return q - dot(q - p, n) * n; }
void main() {
  vec3 b = gl_TessCoord;
  vec3 n0 = unit_or_zero(c_nrm[0]);
  vec3 n1 = unit_or_zero(c_nrm[1]);
  vec3 n2 = unit_or_zero(c_nrm[2]);
  vec3 p = b.x * c_pos[0] + b.y * c_pos[1] + b.z * c_pos[2];
  vec3 s = b.x * project(p, c_pos[0], n0) + b.y * project(p, c_pos[1], n1) +
           b.z * project(p, c_pos[2], n2);
  vec3 q = mix(p, s, u_alpha);
  e_pos = q;
  e_nrm = b.x * n0 + b.y * n1 + b.z * n2;
  e_rest = b.x * c_rest[0] + b.y * c_rest[1] + b.z * c_rest[2];
  e_stain = b.x * c_stain[0] + b.y * c_stain[1] + b.z * c_stain[2];
  e_material = c_material;
  e_look = c_look;
  gl_Position = u_view_proj * vec4(q, 1.0);
}
)";

// Tissue under the endoscope's light, in linear colour. The light sits at the scope's tip (the
// eye) and falls off with the square of the distance, normalised to 1 at the camera target's
// distance and capped. The pattern volume (render/tissue_pattern.h), sampled at the rest position
// at two scales, gives the serosa its vessels and mottling, fat its lobules, and every surface a
// fine relief that bends the normal (a bump from the screen-space derivatives of the height, so
// no tangent frame is needed): the tight wet highlight then breaks up into glints. Red light
// reaches further round the terminator than blue (a wrapped diffuse term: the warmth of light
// scattered under the surface), and a Fresnel sheen brightens grazing wet surfaces. A cut face
// shows the darker inside with the pattern's stipple, darkest and glossiest at its oozing rim;
// coagulated tissue is matt tan with charred specks. Both sides are lit (cut surfaces can be
// seen from behind).
const char* const kVisualFragment = R"(#version 410 core
in vec3 e_pos;
in vec3 e_nrm;
in vec4 e_rest;
in float e_stain;
flat in vec4 e_material;
flat in vec4 e_look;
out vec4 frag_color;
uniform vec3 u_eye;          // light and eye position, m
uniform float u_ref_dist;    // distance at which the light's intensity is 1, m
uniform sampler3D u_pattern; // R vessels, G lobule borders, B mottle, A relief
uniform float u_period;      // m of rest space per repeat of the pattern
uniform float u_relief;      // height of the relief, m
uniform int u_detail;        // 0: the plain colour, no pattern or relief
uniform vec3 u_taenia_centre;  // rest space, m
uniform vec3 u_taenia_axis;    // unit; zero: no taeniae
// The taeniae: three bands 120 degrees apart round the axis, narrowing towards its far side and
// strongest where they converge on the appendix; 0 off them.
float taenia(vec3 rest) {
  if (dot(u_taenia_axis, u_taenia_axis) < 0.5) return 0.0;
  vec3 d = rest - u_taenia_centre;
  float along = dot(normalize(d), u_taenia_axis);
  vec3 b1 = normalize(cross(u_taenia_axis, abs(u_taenia_axis.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
  vec3 b2 = cross(u_taenia_axis, b1);
  float phi = atan(dot(d, b2), dot(d, b1));
  return smoothstep(0.94, 0.985, cos(3.0 * phi)) * smoothstep(-0.6, 0.4, along);
}
uniform int u_pools;         // pools of blood (at most 4)
uniform vec4 u_pool[4];      // centre, m; radius, m
uniform vec3 u_pool_up[4];   // unit normal of the surface each lies on
// How much a pool of blood covers this point: a film over whatever lies within its radius and
// up to 7 mm above its plane (the wall's undulation, the organs' undersides), its edge ragged.
float pooled(vec3 p, float ragged) {
  float w = 0.0;
  for (int k = 0; k < u_pools; ++k) {
    vec3 d = p - u_pool[k].xyz;
    float h = dot(d, u_pool_up[k]);
    float across = length(d - h * u_pool_up[k]);
    float edge = u_pool[k].w * (0.9 + 0.2 * ragged);
    w = max(w, (1.0 - smoothstep(0.85 * edge, edge, across)) * (1.0 - smoothstep(0.005, 0.007, h)));
  }
  return w;
}
vec3 bumped(vec3 n, float h) {
  vec3 dpx = dFdx(e_pos);
  vec3 dpy = dFdy(e_pos);
  vec3 r1 = cross(dpy, n);
  vec3 r2 = cross(n, dpx);
  float det = dot(dpx, r1);
  vec3 grad = sign(det) * (dFdx(h) * r1 + dFdy(h) * r2);
  vec3 m = abs(det) * n - grad;
  return dot(m, m) > 0.0 ? normalize(m) : n;
}
void main() {
  vec3 n = e_nrm;
  if (dot(n, n) < 1e-12) n = cross(dFdx(e_pos), dFdy(e_pos));
  n = normalize(n);
  if (!gl_FrontFacing) n = -n;
  vec3 albedo = pow(e_material.rgb, vec3(2.2));
  float wet = e_material.a;
  float vessels = e_look.r, lobules = e_look.g, mottle = e_look.b, kind = e_look.a;
  vec3 q = e_rest.xyz / u_period;
  vec4 coarse = vec4(0.0, 0.0, 0.5, 0.5), fine = coarse;
  if (u_detail != 0) {
    coarse = texture(u_pattern, q);
    fine = texture(u_pattern, q * 2.7 + vec3(0.31, 0.57, 0.13));
  }
  float h;
  if (u_detail == 0) {
    h = 0.0;
  } else if (kind < 0.375) {
    float band = kind > 0.125 ? taenia(e_rest.xyz) : 0.0;
    albedo *= 1.0 + mottle * (0.9 * (coarse.b - 0.5) + 0.5 * (fine.b - 0.5));
    albedo = mix(albedo, albedo * vec3(0.95, 0.62, 0.45), lobules * 0.6 * coarse.g);
    float vein = clamp(coarse.r + 0.6 * fine.r * (1.0 - lobules), 0.0, 1.0);
    albedo = mix(albedo, vec3(0.16, 0.012, 0.03), vessels * 0.85 * vein * (1.0 - 0.7 * band));
    albedo = mix(albedo, vec3(0.80, 0.55, 0.48), 0.6 * band);
    h = mix(fine.a, 1.0 - coarse.g, lobules) + 0.4 * vessels * coarse.r + 1.5 * band;
  } else if (kind < 0.75) {
    albedo *= 0.55 + 0.9 * fine.b * coarse.b;
    float rim = smoothstep(0.35, 1.0, e_rest.w);
    albedo = mix(albedo, vec3(0.09, 0.004, 0.008), rim);
    wet = mix(wet, 1.0, rim);
    h = fine.a;
  } else {
    float speck = smoothstep(0.55, 0.75, fine.b) * smoothstep(0.4, 0.6, coarse.b);
    albedo = mix(albedo, vec3(0.03, 0.02, 0.015), speck);
    h = fine.b;
  }
  // Seen from very close, one voxel of the pattern spans many pixels and the relief's trilinear
  // slopes would show as facets: it fades out there.
  float voxels_per_pixel = length(fwidth(q * 2.7 * float(textureSize(u_pattern, 0).x)));
  // Blood that pooled over the tissue, or that lies on it now: dark red, a smooth wet film.
  float blood = max(smoothstep(0.05, 0.6, e_stain), pooled(e_pos, coarse.b));
  float relief = u_relief * smoothstep(0.04, 0.15, voxels_per_pixel) * (1.0 - blood);
  if (u_detail != 0) n = bumped(n, relief * h);
  albedo = mix(albedo, vec3(0.15, 0.002, 0.005), blood);
  wet = mix(wet, 0.6, blood);
  vec3 l = u_eye - e_pos;
  float d = max(length(l), 1e-9);
  l /= d;
  float att = min((u_ref_dist * u_ref_dist) / (d * d), 3.0);
  float ndl = dot(n, l);
  vec3 wrap = vec3(0.30, 0.12, 0.08);
  vec3 diffuse = clamp((vec3(ndl) + wrap) / (1.0 + wrap), 0.0, 1.0);
  float c = max(ndl, 0.0);
  // Light and eye coincide: the half vector is l itself, and n.v = n.l.
  // A film of blood is a mirror: its tight highlight stays, the broad sheen of tissue goes.
  float spec = pow(c, 90.0) + (1.0 - blood) * 0.2 * pow(c, 14.0);
  float fresnel = (1.0 - blood) * (0.02 + 0.98 * pow(1.0 - c, 5.0));
  vec3 lit = albedo * (0.06 + 0.94 * diffuse * att) +
             wet * (spec + 0.12 * fresnel) * att * vec3(1.0, 0.96, 0.92);
  // A soft shoulder above 0.8 instead of a hard clip: bright fat close to the scope keeps its
  // lobules rather than burning out to white (the camera's exposure would do the same).
  vec3 over = max(lit - 0.8, 0.0);
  lit = min(lit, 0.8) + 0.2 * (1.0 - exp(-over / 0.2));
  frag_color = vec4(pow(lit, vec3(1.0 / 2.2)), 1.0);
}
)";

// The scenery: per-corner attributes (the renderer repeats each triangle's material at its three
// corners), handed to kVisualFragment under the names the tessellation evaluation stage uses. It
// does not move, so its pattern is laid out in its own positions.
const char* const kSceneryVertex = R"(#version 410 core
layout(location = 0) in vec3 a_pos;       // world position, m
layout(location = 1) in vec3 a_nrm;       // unit normal
layout(location = 2) in vec4 a_material;  // rgb: sRGB colour, a: specular strength
layout(location = 3) in vec4 a_look;      // vessels, lobules, mottle, kind
out vec3 e_pos;
out vec3 e_nrm;
out vec4 e_rest;
out float e_stain;
flat out vec4 e_material;
flat out vec4 e_look;
uniform mat4 u_view_proj;
void main() {
  e_pos = a_pos;
  e_nrm = a_nrm;
  e_rest = vec4(a_pos, 0.0);
  e_stain = 0.0;
  e_material = a_material;
  e_look = a_look;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
)";

// Surgical smoke: one camera-facing quad per puff (instanced: its centre, radius and density are
// per-instance attributes), a soft round cloud whose density falls off towards its rim and is
// broken up by a little noise; blended over the picture, depth-tested but not written, so a puff
// behind tissue is hidden by it.
const char* const kSmokeVertex = R"(#version 410 core
layout(location = 0) in vec4 a_puff;     // centre, m; radius, m
layout(location = 1) in float a_density; // [0, 1]
out vec2 v_corner;
flat out float v_density;
flat out float v_seed;
uniform mat4 u_view_proj;
uniform vec3 u_right;  // unit: the picture's right, world space
uniform vec3 u_up;     // unit: the picture's up
void main() {
  vec2 c = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
  v_corner = c;
  v_density = a_density;
  v_seed = fract(dot(a_puff.xyz, vec3(173.1, 291.7, 117.3)));
  vec3 p = a_puff.xyz + a_puff.w * (c.x * u_right + c.y * u_up);
  gl_Position = u_view_proj * vec4(p, 1.0);
}
)";

const char* const kSmokeFragment = R"(#version 410 core
in vec2 v_corner;
flat in float v_density;
flat in float v_seed;
out vec4 frag_color;
void main() {
  float r2 = dot(v_corner, v_corner);
  if (r2 >= 1.0) discard;
  float a = atan(v_corner.y, v_corner.x);
  float ragged = 0.85 + 0.15 * sin(5.0 * a + 6.283 * v_seed) * sin(3.0 * a + 11.0 * v_seed);
  float cloud = max(1.0 - r2 / (ragged * ragged), 0.0);
  frag_color = vec4(vec3(0.86, 0.84, 0.80), v_density * cloud * cloud);
}
)";

const char* const kFlatVertex = R"(#version 410 core
layout(location = 0) in vec3 a_pos;  // world position, m
out vec3 v_pos;
uniform mat4 u_view_proj;
void main() {
  v_pos = a_pos;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
)";

// u_shaded = 1: faceted shading from the screen-space derivatives of the position (one normal per
// triangle), lit from the eye; 0: the plain colour (lines).
const char* const kFlatFragment = R"(#version 410 core
in vec3 v_pos;
out vec4 frag_color;
uniform vec4 u_color;  // sRGB
uniform int u_shaded;
uniform vec3 u_eye;
void main() {
  if (u_shaded == 0) {
    frag_color = u_color;
    return;
  }
  vec3 n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
  float lambert = abs(dot(n, normalize(u_eye - v_pos)));
  frag_color = vec4(u_color.rgb * (0.25 + 0.75 * lambert), u_color.a);
}
)";

// Instruments (render/tool_mesh.h): per-vertex normal and material, lit like the tissue by the
// light at the eye with the same distance falloff; metal gets a sharper, stronger highlight.
const char* const kToolVertex = R"(#version 410 core
layout(location = 0) in vec3 a_pos;       // world position, m
layout(location = 1) in vec3 a_nrm;       // unit normal
layout(location = 2) in vec4 a_material;  // rgb: sRGB colour, a: specular strength
out vec3 v_pos;
out vec3 v_nrm;
out vec4 v_material;
uniform mat4 u_view_proj;
void main() {
  v_pos = a_pos;
  v_nrm = a_nrm;
  v_material = a_material;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
)";

const char* const kToolFragment = R"(#version 410 core
in vec3 v_pos;
in vec3 v_nrm;
in vec4 v_material;
out vec4 frag_color;
uniform vec3 u_eye;        // light and eye position, m
uniform float u_ref_dist;  // distance at which the light's intensity is 1, m
void main() {
  vec3 n = normalize(v_nrm);
  if (!gl_FrontFacing) n = -n;
  vec3 l = u_eye - v_pos;
  float d = max(length(l), 1e-9);
  l /= d;
  float att = min((u_ref_dist * u_ref_dist) / (d * d), 3.0);
  float diffuse = max(dot(n, l), 0.0);
  float spec = pow(diffuse, 90.0) + 0.3 * pow(diffuse, 8.0);
  vec3 albedo = pow(v_material.rgb, vec3(2.2));
  vec3 c = albedo * (0.10 + 0.90 * diffuse * att) + v_material.a * spec * att * vec3(1.0);
  frag_color = vec4(pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
)";

}  // namespace serosa::render::shaders
