#version 330 core
// banyan segment shader, fragment stage: the minimal one a line needs, a
// colour from its level code (0 axis, 1 twig, 2.. forks), bark brown to twig green.
in vec4 g_seg;
out vec4 f_color;

void main() {
    float t = clamp(g_seg.w / 4.0, 0.0, 1.0);
    f_color = vec4(mix(vec3(0.30, 0.20, 0.12), vec3(0.35, 0.55, 0.20), t), 1.0);
}
