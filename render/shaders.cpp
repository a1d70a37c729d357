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
uniform usamplerBuffer u_tri;          // (3t) vertex ids
uniform samplerBuffer u_tri_material;  // (t) rgb: sRGB colour, a: specular strength
out vec3 v_pos;
out vec3 v_nrm;
out vec4 v_material;
void main() {
  int vid = int(texelFetch(u_tri, gl_VertexID).r);
  v_pos = texelFetch(u_pos, vid).xyz;
  v_nrm = texelFetch(u_nrm, vid).xyz;
  v_material = texelFetch(u_tri_material, gl_VertexID / 3);
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
in vec4 v_material[];
out vec3 c_pos[];
out vec3 c_nrm[];
patch out vec4 c_material;  // rgb: sRGB colour, a: specular strength
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
  if (gl_InvocationID == 0) {
    c_material = v_material[0];  // the same for the three corners
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
// The per-triangle material comes through the control stage as a per-patch value.
const char* const kVisualTessEval = R"(#version 410 core
layout(triangles, equal_spacing, ccw) in;
in vec3 c_pos[];
in vec3 c_nrm[];
patch in vec4 c_material;
out vec3 e_pos;
out vec3 e_nrm;
flat out vec4 e_material;  // rgb: sRGB colour, a: specular strength
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
  e_material = c_material;
  gl_Position = u_view_proj * vec4(q, 1.0);
}
)";

// Phong lighting in linear colour, the light at the eye (endoscope tip). Intensity falls off with
// the square of the distance, normalised to 1 at the distance of the camera's target and capped,
// so that tissue close to the scope is bright and far tissue dim. A tight highlight gives the wet
// look of serosa. Both sides are lit (cut surfaces can be seen from behind).
const char* const kVisualFragment = R"(#version 410 core
in vec3 e_pos;
in vec3 e_nrm;
flat in vec4 e_material;
out vec4 frag_color;
uniform vec3 u_eye;         // light and eye position, m
uniform float u_ref_dist;   // distance at which the light's intensity is 1, m
void main() {
  vec3 n = e_nrm;
  if (dot(n, n) < 1e-12) n = cross(dFdx(e_pos), dFdy(e_pos));
  n = normalize(n);
  if (!gl_FrontFacing) n = -n;
  vec3 l = u_eye - e_pos;
  float d = max(length(l), 1e-9);
  l /= d;
  float att = min((u_ref_dist * u_ref_dist) / (d * d), 3.0);
  float diffuse = max(dot(n, l), 0.0);
  // Light and eye coincide: the half vector is l itself.
  float spec = pow(diffuse, 60.0) + 0.25 * pow(diffuse, 12.0);
  vec3 albedo = pow(e_material.rgb, vec3(2.2));
  vec3 c = albedo * (0.08 + 0.92 * diffuse * att) + e_material.a * spec * att * vec3(1.0, 0.96, 0.92);
  frag_color = vec4(pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
)";

// The scenery: per-corner attributes (the renderer repeats each triangle's material at its three
// corners), handed to kVisualFragment under the names the tessellation evaluation stage uses.
const char* const kSceneryVertex = R"(#version 410 core
layout(location = 0) in vec3 a_pos;       // world position, m
layout(location = 1) in vec3 a_nrm;       // unit normal
layout(location = 2) in vec4 a_material;  // rgb: sRGB colour, a: specular strength
out vec3 e_pos;
out vec3 e_nrm;
flat out vec4 e_material;
uniform mat4 u_view_proj;
void main() {
  e_pos = a_pos;
  e_nrm = a_nrm;
  e_material = a_material;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
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
