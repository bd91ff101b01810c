#version 460
// The terrain and the objects without caustics (common/terrain_lit.glsl): the reflection view.
#include "common/terrain_lit.glsl"
