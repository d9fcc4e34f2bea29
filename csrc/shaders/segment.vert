#version 330 core
// banyan segment shader, vertex stage: one point per segment carries the
// segment's five inputs (spec segments.md, "The GLSL version") through to
// the geometry stage unchanged.
layout(location = 0) in vec3 a_S;  // start of the axis
layout(location = 1) in vec3 a_A;  // direction of the axis (any length > 0)
layout(location = 2) in float a_l; // length of the axis
layout(location = 3) in int a_n;   // twigs, 0..63
layout(location = 4) in int a_s;   // depth of the first twig, 0..64

out vec3 v_S;
out vec3 v_A;
out float v_l;
flat out int v_n;
flat out int v_s;

void main() {
    v_S = a_S;
    v_A = a_A;
    v_l = a_l;
    v_n = a_n;
    v_s = a_s;
    gl_Position = vec4(a_S, 1.0);
}
