#version 460
// For tests/derived_barriers.rs only: writes one colour (samples nothing).
layout(location = 0) out vec4 colour;

void main() { colour = vec4(0.25, 0.5, 0.75, 1.0); }
