#version 460
// The terrain and the objects with the caustics (common/terrain_lit.glsl): the refraction view
// and the main view, which sample the simulation's images.
#define TERRAIN_CAUSTICS
#include "common/terrain_lit.glsl"
