#version 460
// The terrain and the objects without caustics (common/terrain_lit.glsl): the reflection view,
// the main view from above the water, and the refraction view when it draws no caustics
// (`--caustics off`; at --quality low unless `--caustics on`: src/render/passes/terrain.rs).
#include "common/terrain_lit.glsl"
