#version 330 core
// banyan segment shader, geometry stage: the GLSL twin of the CPU reference
// banyan_segment_lines (csrc/segments/reference.c; spec segments.md).
// One point in, at most 128 vertices out: every line is one 2-vertex line
// strip, in the reference's order (axis, twigs, forks breadth-first).
// Each expression matches the reference's float operations one for one;
// keep the two in step (tests/gl/test_segments_gl.c compares them).
// `precise` (GLSL 4.00, or ARB_gpu_shader5 here) stops the compiler from
// fusing a * b + c into one fma, which the C reference never does: with it
// llvmpipe reproduces the reference bit for bit; without it the results
// still agree to about 3e-7 relative.
#ifdef GL_ARB_gpu_shader5
#extension GL_ARB_gpu_shader5 : enable
#define PRECISE precise
#else
#define PRECISE
#endif
layout(points) in;
layout(line_strip, max_vertices = 128) out;

in vec3 v_S[];
in vec3 v_A[];
in float v_l[];
flat in int v_n[];
flat in int v_s[];

uniform vec2 u_alpha; // (cos, sin) of the twig angle
uniform vec2 u_beta;  // fork yaw
uniform vec2 u_gamma; // roll of child 1
uniform vec2 u_omega; // roll of child 2
uniform float u_m;    // twig and fork length
uniform mat4 u_mvp;   // for drawing; identity when capturing

out vec4 g_seg; // (x, y, z, level code): 0 axis, 1 twig, 1 + d fork level d

const int BUDGET = 128;
const int MAX_LINES = 64;

// The breadth-first queue: per line its ends, unit direction, depth below
// its twig and the depth its twig forks to.
vec3 p0[MAX_LINES];
vec3 p1[MAX_LINES];
vec3 dir[MAX_LINES];
int depth[MAX_LINES];
int limit[MAX_LINES];

vec3 rot_z(vec3 v, float c, float s) {
    PRECISE vec3 r = vec3(c * v.x - s * v.y, s * v.x + c * v.y, v.z);
    return r;
}

// Rodrigues rotation of v about unit k: v c + (k x v) s + k (k.v)(1 - c).
vec3 rot_axis(vec3 k, vec3 v, float c, float s) {
    PRECISE float cx = k.y * v.z - k.z * v.y;
    PRECISE float cy = k.z * v.x - k.x * v.z;
    PRECISE float cz = k.x * v.y - k.y * v.x;
    PRECISE float d = (k.x * v.x + k.y * v.y) + k.z * v.z;
    PRECISE float w = d * (1.0 - c);
    PRECISE vec3 r = vec3((v.x * c + cx * s) + k.x * w,
                          (v.y * c + cy * s) + k.y * w,
                          (v.z * c + cz * s) + k.z * w);
    return r;
}

void emit_line(vec3 a, vec3 b, float level) {
    g_seg = vec4(a, level);
    gl_Position = u_mvp * vec4(a, 1.0);
    EmitVertex();
    g_seg = vec4(b, level);
    gl_Position = u_mvp * vec4(b, 1.0);
    EmitVertex();
    EndPrimitive();
}

void main() {
    PRECISE vec3 S = v_S[0];
    PRECISE vec3 A = v_A[0];
    PRECISE float l = v_l[0];
    int n = v_n[0];
    int s = v_s[0];
    PRECISE float m = u_m;

    // 1. Axis.
    PRECISE float len = sqrt((A.x * A.x + A.y * A.y) + A.z * A.z);
    PRECISE vec3 C = vec3(A.x / len, A.y / len, A.z / len);
    PRECISE vec3 B2 = vec3(S.x + C.x * l, S.y + C.y * l, S.z + C.z * l);
    emit_line(S, B2, 0.0);

    // 2. Twigs.
    for (int i = 1; i <= n; i++) {
        PRECISE float t = float(i) / float(n + 1);
        PRECISE vec3 D = vec3(S.x + (B2.x - S.x) * t, S.y + (B2.y - S.y) * t, S.z + (B2.z - S.z) * t);
        PRECISE vec3 F = rot_z(C, u_alpha.x, (i & 1) == 1 ? u_alpha.y : -u_alpha.y);
        PRECISE vec3 E = vec3(D.x + F.x * m, D.y + F.y * m, D.z + F.z * m);
        p0[i] = D;
        p1[i] = E;
        dir[i] = F;
        depth[i] = 0;
        limit[i] = s + i - 1;
        emit_line(D, E, 1.0);
    }

    // 3-4. Hierarchy, breadth-first, budget checked before every fork.
    int nl = n + 1;
    for (int q = 1; q < MAX_LINES; q++) {
        if (q >= nl) break;
        if (depth[q] >= limit[q]) continue;
        if (2 * nl + 4 > BUDGET) break;
        PRECISE vec3 I1 = p0[q];
        PRECISE vec3 I2 = p1[q];
        PRECISE vec3 L = dir[q];
        PRECISE vec3 d = vec3(I2.x - I1.x, I2.y - I1.y, I2.z - I1.z);
        PRECISE vec3 G1 = vec3(I1.x + d.x * 0.3, I1.y + d.y * 0.3, I1.z + d.z * 0.3);
        PRECISE vec3 G2 = vec3(I1.x + d.x * 0.7, I1.y + d.y * 0.7, I1.z + d.z * 0.7);
        PRECISE vec3 J1 = rot_axis(L, rot_z(L, u_beta.x, u_beta.y), u_gamma.x, u_gamma.y);
        PRECISE vec3 J2 = rot_axis(L, rot_z(L, u_beta.x, -u_beta.y), u_omega.x, u_omega.y);
        PRECISE vec3 H1 = vec3(G1.x + J1.x * m, G1.y + J1.y * m, G1.z + J1.z * m);
        PRECISE vec3 H2 = vec3(G2.x + J2.x * m, G2.y + J2.y * m, G2.z + J2.z * m);
        int dq = depth[q] + 1;
        p0[nl] = G1;
        p1[nl] = H1;
        dir[nl] = J1;
        depth[nl] = dq;
        limit[nl] = limit[q];
        p0[nl + 1] = G2;
        p1[nl + 1] = H2;
        dir[nl + 1] = J2;
        depth[nl + 1] = dq;
        limit[nl + 1] = limit[q];
        nl += 2;
        emit_line(G1, H1, float(1 + dq));
        emit_line(G2, H2, float(1 + dq));
    }
}
