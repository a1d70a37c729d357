// GLSL sources of the renderer's programs (text only; compiled by frame_renderer.cpp).
#pragma once

namespace serosa::render::shaders {

// Visual view: vertex -> tessellation control -> tessellation evaluation (Phong tessellation,
// Boubekeur & Alexa 2008) -> fragment (Phong lighting, light at the eye with distance falloff).
extern const char* const kVisualVertex;
extern const char* const kVisualTessControl;
extern const char* const kVisualTessEval;
extern const char* const kVisualFragment;
/// The scenery around the organs (render/scenery.h): untessellated triangles with per-corner
/// normal and material, linked with kVisualFragment so it is lit exactly like the organs.
extern const char* const kSceneryVertex;

// Collision and mechanical views: untessellated triangles or lines, flat shaded or one colour.
extern const char* const kSmokeVertex;
extern const char* const kSmokeFragment;
extern const char* const kFlatVertex;
extern const char* const kFlatFragment;
extern const char* const kToolVertex;    ///< instruments: position, normal, material attributes
extern const char* const kToolFragment;  ///< instruments: lit from the eye, metallic highlight

}  // namespace serosa::render::shaders
