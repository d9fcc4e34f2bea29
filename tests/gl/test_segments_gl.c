/* The GLSL twin against the CPU reference (spec segments.md, "The GLSL
 * version"). A surfaceless EGL context on Mesa's software llvmpipe (no
 * display, no GPU) compiles the library's embedded segment shaders, draws
 * random segment inputs as points, and captures every emitted vertex with
 * transform feedback. Every vertex, in order, must equal the reference's
 * within 1e-4 relative (relative to the segment's scale, see `close`), and
 * every level code must match exactly. The inputs include budget-hitting
 * ones, n = 0, l = 0, vertical, tiny and huge A, and huge coordinates, under
 * the paper's angles and under random ones.
 *
 * When no OpenGL 3.2+ context can be made the test FAILS (exit 1) with a
 * loud message: a missing driver must never look like a pass.
 *
 *   test_segments_gl [OUT_DIR] [--count N] [--seed S] [--bench] [--exact]
 *                    [--geom FILE]
 * --bench also times the shader (vertices per second, for context only);
 * --exact also requires every vertex to match bit for bit (true on
 * llvmpipe with `precise`; not part of the spec's contract); --geom tries
 * an edited geometry shader before it is re-embedded.
 *
 * The geometry shader is run twice: as shipped (with `precise` where
 * GL_ARB_gpu_shader5 exists) and with its no-`precise` fallback branch
 * forced, so both paths of the source are checked.
 * Needs libegl-dev, libgl-dev (libopengl-dev), libegl-mesa0 and
 * libgl1-mesa-dri; links with -lEGL -lOpenGL. */
#define _POSIX_C_SOURCE 200809L
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "banyan.h"
#include "check.h"
#include "base/rng.h"
#include "base/vec.h"

#define MAXV BANYAN_SEGMENT_MAX_VERTICES

/* Under AddressSanitizer (BANYAN_SANITIZE): Mesa's dlopen'ed driver leaves a
 * few allocations LeakSanitizer cannot attribute (unknown module) at exit.
 * The library's own leaks are checked by the tests/c tests; here only
 * memory errors count. Ignored without ASan. */
const char *__asan_default_options(void);
/* Exported: the test is built with hidden visibility, and the ASan
 * runtime must see this hook to honour it. */
__attribute__((visibility("default"))) const char *__asan_default_options(void) { return "detect_leaks=0"; }

static int fail_loudly(const char *what) {
    fprintf(stderr,
            "\n*** test_segments_gl: FAILED: %s ***\n"
            "*** No OpenGL 3.2+ context on Mesa's llvmpipe via surfaceless EGL: the shader was NOT tested. ***\n"
            "*** Install libegl-mesa0 and libgl1-mesa-dri (Debian) and check EGL_MESA_platform_surfaceless. ***\n\n",
            what);
    printf("test_segments_gl: 0 passed, 1 failed\n");
    return 1;
}

typedef struct gl_ctx {
    EGLDisplay dpy;
    EGLContext ctx;
} gl_ctx;

static const char *make_context(gl_ctx *g) {
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!ext || !strstr(ext, "EGL_MESA_platform_surfaceless")) return "EGL_MESA_platform_surfaceless is missing";
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display) return "eglGetPlatformDisplayEXT is missing";
    g->dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLint major, minor;
    if (g->dpy == EGL_NO_DISPLAY || !eglInitialize(g->dpy, &major, &minor)) return "eglInitialize failed";
    if (!eglBindAPI(EGL_OPENGL_API)) return "eglBindAPI(EGL_OPENGL_API) failed";
    static const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    g->ctx = eglCreateContext(g->dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attrs);
    if (g->ctx == EGL_NO_CONTEXT) {
        /* Without EGL_KHR_no_config_context: any OpenGL-capable config. */
        static const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig cfg;
        EGLint n = 0;
        if (eglChooseConfig(g->dpy, want, &cfg, 1, &n) && n == 1)
            g->ctx = eglCreateContext(g->dpy, cfg, EGL_NO_CONTEXT, attrs);
    }
    if (g->ctx == EGL_NO_CONTEXT) return "eglCreateContext (OpenGL 3.3 core) failed";
    if (!eglMakeCurrent(g->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, g->ctx)) return "eglMakeCurrent (surfaceless) failed";
    GLint gl_major = 0, gl_minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &gl_major);
    glGetIntegerv(GL_MINOR_VERSION, &gl_minor);
    if (gl_major * 10 + gl_minor < 32) return "the context is older than OpenGL 3.2 (no geometry shaders)";
    return NULL;
}

static GLuint compile(GLenum type, const char *src, const char *name) {
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 1, &src, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        fprintf(stderr, "test_segments_gl: %s shader does not compile:\n%s\n", name, log);
        return 0;
    }
    return sh;
}

/* --geom FILE: try a geometry shader from a file instead of the embedded
 * one (for editing the shader before re-embedding it). */
static char *geom_override;

static GLuint build_program(const char *geom) {
    const char *names[3] = {"vertex", "geometry", "fragment"};
    const GLenum types[3] = {GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER};
    GLuint prog = glCreateProgram();
    for (int i = 0; i < 3; i++) {
        const char *src = i == 1 ? geom : banyan_segment_shader_source(i);
        if (!src) return 0;
        GLuint sh = compile(types[i], src, names[i]);
        if (!sh) return 0;
        glAttachShader(prog, sh);
        glDeleteShader(sh);
    }
    const char *varyings[1] = {"g_seg"};
    glTransformFeedbackVaryings(prog, 1, varyings, GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetProgramInfoLog(prog, sizeof log, NULL, log);
        fprintf(stderr, "test_segments_gl: the program does not link:\n%s\n", log);
        return 0;
    }
    return prog;
}

/* The vertex layout of one point: the five inputs as the shader reads them. */
typedef struct gpu_in {
    float S[3], A[3], l;
    int32_t n, s;
} gpu_in;

typedef struct gl_state {
    GLuint prog, vao, vbo, tfo, fbo, rbo, query_written, query_generated;
    GLuint out_buf;
    size_t out_cap; /* vertices */
} gl_state;

static void setup(gl_state *st) {
    glGenVertexArrays(1, &st->vao);
    glBindVertexArray(st->vao);
    glGenBuffers(1, &st->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, st->vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(gpu_in), (void *)offsetof(gpu_in, S));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(gpu_in), (void *)offsetof(gpu_in, A));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, sizeof(gpu_in), (void *)offsetof(gpu_in, l));
    glEnableVertexAttribArray(3);
    glVertexAttribIPointer(3, 1, GL_INT, sizeof(gpu_in), (void *)offsetof(gpu_in, n));
    glEnableVertexAttribArray(4);
    glVertexAttribIPointer(4, 1, GL_INT, sizeof(gpu_in), (void *)offsetof(gpu_in, s));
    /* Transform feedback needs a complete framebuffer even with the
     * rasterizer off. */
    glGenFramebuffers(1, &st->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, st->fbo);
    glGenRenderbuffers(1, &st->rbo);
    glBindRenderbuffer(GL_RENDERBUFFER, st->rbo);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, st->rbo);
    glViewport(0, 0, 1, 1);
    glEnable(GL_RASTERIZER_DISCARD);
    glGenTransformFeedbacks(1, &st->tfo);
    glGenBuffers(1, &st->out_buf);
    glGenQueries(1, &st->query_written);
    glGenQueries(1, &st->query_generated);
}

static void set_uniforms(GLuint prog, const float u[9]) {
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    glUseProgram(prog);
    glUniform2f(glGetUniformLocation(prog, "u_alpha"), u[0], u[1]);
    glUniform2f(glGetUniformLocation(prog, "u_beta"), u[2], u[3]);
    glUniform2f(glGetUniformLocation(prog, "u_gamma"), u[4], u[5]);
    glUniform2f(glGetUniformLocation(prog, "u_omega"), u[6], u[7]);
    glUniform1f(glGetUniformLocation(prog, "u_m"), u[8]);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_mvp"), 1, GL_FALSE, identity);
}

/* Draws `count` segments; fills out (4 floats per vertex) and returns the
 * vertex count captured, or -1 on a GL error / overflow. */
static long draw(gl_state *st, const gpu_in *in, uint32_t count, float *out, int read_back) {
    size_t need = (size_t)count * MAXV;
    glBindBuffer(GL_ARRAY_BUFFER, st->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(gpu_in) * count), in, GL_STATIC_DRAW);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, st->tfo);
    if (need > st->out_cap) {
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, st->out_buf);
        glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, (GLsizeiptr)(need * 4 * sizeof(float)), NULL, GL_DYNAMIC_READ);
        st->out_cap = need;
    }
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, st->out_buf);
    glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, st->query_written);
    glBeginQuery(GL_PRIMITIVES_GENERATED, st->query_generated);
    glBeginTransformFeedback(GL_LINES);
    glDrawArrays(GL_POINTS, 0, (GLsizei)count);
    glEndTransformFeedback();
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    GLuint written = 0, generated = 0;
    glGetQueryObjectuiv(st->query_written, GL_QUERY_RESULT, &written);
    glGetQueryObjectuiv(st->query_generated, GL_QUERY_RESULT, &generated);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        fprintf(stderr, "test_segments_gl: GL error 0x%x while drawing\n", e);
        return -1;
    }
    if (written != generated) {
        fprintf(stderr, "test_segments_gl: %u lines generated but only %u captured\n", generated, written);
        return -1;
    }
    if (read_back) {
        glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, st->out_buf);
        glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, (GLsizeiptr)((size_t)written * 2 * 4 * sizeof(float)), out);
    }
    return (long)written * 2;
}

/* ------------------------------------------------------------- inputs */

static double rand_dir_len(pcg32 *r, double lo_exp, double hi_exp, double v[3]) {
    double z = rng_range(r, -1, 1), a = rng_range(r, 0, 2 * BANYAN_PI), q = sqrt(1 - z * z);
    double len = pow(10.0, rng_range(r, lo_exp, hi_exp));
    v[0] = q * cos(a) * len;
    v[1] = q * sin(a) * len;
    v[2] = z * len;
    return len;
}

/* Input k of a run: most random, some hitting the budget, and a fixed list
 * of edge cases first. */
static void make_input(pcg32 *r, uint32_t k, banyan_segment_input *in) {
    for (int c = 0; c < 3; c++) in->S[c] = rng_range(r, -100, 100);
    rand_dir_len(r, -3, 3, in->A);
    in->l = rng_range(r, 0, 50);
    in->n = (int32_t)rng_below(r, 64);
    in->s = (int32_t)rng_below(r, 11);
    if (k % 4 == 1) { /* small segments, mostly within the budget */
        in->n = (int32_t)rng_below(r, 7);
        in->s = (int32_t)rng_below(r, 4);
    } else if (k % 4 == 3) {
        in->n = (int32_t)rng_below(r, 11);
        in->s = (int32_t)rng_below(r, 3);
    }
    switch (k) {
    case 0: in->n = 0; break;
    case 1: in->l = 0; break;
    case 2: in->A[0] = in->A[1] = 0; in->A[2] = 3; break;         /* vertical: twigs along the axis */
    case 3: in->A[0] = in->A[1] = 0; in->A[2] = -1e-12; break;    /* tiny, downwards */
    case 4: in->A[0] = 7e11; in->A[1] = -7e11; in->A[2] = 1; break; /* huge */
    case 5: in->l = 1e12; break;
    case 6: in->S[0] = 1e12; in->S[1] = -1e12; break;
    case 7: in->n = 63; in->s = 0; break;
    case 8: in->n = 63; in->s = 64; break;
    case 9: in->n = 1; in->s = 64; break;
    case 10: in->n = 1; in->s = 5; break;  /* exactly 126 vertices */
    case 11: in->n = 2; in->s = 4; break;
    case 12: in->A[0] = 1e-12; in->A[1] = 3e-13; in->A[2] = 0; break;
    case 13: in->n = 31; in->s = 1; break;
    default:
        if (k % 4 == 0) { /* budget hitters */
            in->n = 1 + (int32_t)rng_below(r, 20);
            in->s = 3 + (int32_t)rng_below(r, 8);
        }
        break;
    }
}

/* Within 1e-4 relative to the segment's scale: the magnitude of the
 * numbers the vertex is computed from (|S|, l, m) and of the vertex. Plain
 * per-coordinate relative error would fail on cancellation, e.g. a twig
 * tip near x = 0 on an axis from x = -1e3. */
static double rel_error(const float *g, const float *c, const gpu_in *in, float m) {
    double scale = fmax(fmax(fabs(in->S[0]), fabs(in->S[1])), fmax(fabs(in->S[2]), fabs(in->l)));
    scale = fmax(scale, m);
    for (int k = 0; k < 3; k++) scale = fmax(scale, fabs(c[k]));
    double e = 0;
    for (int k = 0; k < 3; k++) e = fmax(e, fabs((double)g[k] - c[k]));
    return scale > 0 ? e / scale : e;
}

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

typedef struct run_result {
    long vertices, exact, bad_pos, bad_level;
    double max_rel;
} run_result;

static int require_exact; /* --exact: every vertex bit for bit */

/* Vertices a segment would have without the budget (saturated). */
static long wanted(int n, int s) {
    long v = 2 + 2L * n;
    for (int i = 1; i <= n && v <= MAXV; i++) v += s + i - 1 >= 20 ? MAXV : 4 * ((1L << (s + i - 1)) - 1);
    return v;
}

/* One comparison run of `count` inputs under `params`. */
static int compare_run(gl_state *st, const banyan_segment_params *params, uint32_t count, uint64_t seed,
                       run_result *res) {
    memset(res, 0, sizeof *res);
    banyan_segment_input *ins = malloc(sizeof *ins * count);
    gpu_in *gin = malloc(sizeof *gin * count);
    float *cpu = malloc(sizeof(float) * 3 * MAXV * count);
    uint8_t *lev = malloc((size_t)MAXV * count);
    int32_t *counts = malloc(sizeof *counts * count);
    float *gpu = malloc(sizeof(float) * 4 * MAXV * count);
    if (!ins || !gin || !cpu || !lev || !counts || !gpu) {
        fprintf(stderr, "test_segments_gl: out of memory\n");
        return 0;
    }
    pcg32 r;
    pcg32_seed(&r, seed, 6);
    banyan_error err;
    for (uint32_t i = 0; i < count; i++) {
        make_input(&r, i, &ins[i]);
        CHECK(banyan_segment_check(&ins[i], params, &err) == BANYAN_OK, "input %u refused: %s", i, err.message);
        for (int c = 0; c < 3; c++) {
            gin[i].S[c] = (float)ins[i].S[c];
            gin[i].A[c] = (float)ins[i].A[c];
        }
        gin[i].l = (float)ins[i].l;
        gin[i].n = ins[i].n;
        gin[i].s = ins[i].s;
    }
    float u[9];
    CHECK(banyan_segment_uniforms(params, u, &err) == BANYAN_OK, "uniforms: %s", err.message);
    banyan_status rs = banyan_segment_lines_many(ins, count, params, cpu, lev, counts, &err);
    CHECK(rs == BANYAN_OK, "reference: %s", err.message);
    if (rs) count = 0; /* nothing to compare against */
    set_uniforms(st->prog, u);
    long got = draw(st, gin, count, gpu, 1);
    long want = 0, hits = 0;
    for (uint32_t i = 0; i < count; i++) {
        want += counts[i];
        hits += counts[i] < wanted(ins[i].n, ins[i].s);
    }
    CHECK(got == want, "the shader emitted %ld vertices, the reference %ld", got, want);
    res->vertices = got;
    if (got == want) {
        long v = 0;
        for (uint32_t i = 0; i < count; i++) {
            for (int32_t j = 0; j < counts[i]; j++, v++) {
                const float *g = gpu + 4 * v, *c = cpu + (size_t)3 * (MAXV * (size_t)i + j);
                double e = rel_error(g, c, &gin[i], u[8]);
                if (e > res->max_rel) res->max_rel = e;
                if (memcmp(g, c, 3 * sizeof(float)) == 0) res->exact++;
                if (!(e <= 1e-4)) {
                    if (res->bad_pos++ < 5)
                        fprintf(stderr, "segment %u vertex %d: shader (%.9g %.9g %.9g) reference (%.9g %.9g %.9g)\n", i,
                                j, g[0], g[1], g[2], c[0], c[1], c[2]);
                }
                if (g[3] != (float)lev[MAXV * (size_t)i + j]) {
                    if (res->bad_level++ < 5)
                        fprintf(stderr, "segment %u vertex %d: shader level %g, reference %u\n", i, j, g[3],
                                lev[MAXV * (size_t)i + j]);
                }
            }
        }
    }
    CHECK(res->bad_pos == 0, "%ld vertices differ by more than 1e-4 relative (max %.3g)", res->bad_pos, res->max_rel);
    CHECK(res->bad_level == 0, "%ld vertices with the wrong level", res->bad_level);
    if (require_exact) CHECK(res->exact == got, "--exact: %ld of %ld vertices differ in some bit", got - res->exact, got);
    CHECK(hits > 0, "no input hit the 128-vertex budget; the test lost its edge cases");
    printf("  %u segments (%ld at the budget), %ld vertices, %ld bit-exact (%.2f%%), max relative error %.3g\n", count,
           hits, got, res->exact, got ? 100.0 * res->exact / got : 0.0, res->max_rel);
    free(ins);
    free(gin);
    free(cpu);
    free(lev);
    free(counts);
    free(gpu);
    return 1;
}

static void bench(gl_state *st) {
    enum { N = 50000, RUNS = 5 };
    banyan_segment_params p;
    banyan_segment_params_init(&p);
    float u[9];
    banyan_segment_uniforms(&p, u, NULL);
    set_uniforms(st->prog, u);
    gpu_in *gin = malloc(sizeof *gin * N);
    pcg32 r;
    pcg32_seed(&r, 7, 6);
    for (uint32_t i = 0; i < N; i++) {
        banyan_segment_input in;
        make_input(&r, 100 + i, &in);
        for (int c = 0; c < 3; c++) {
            gin[i].S[c] = (float)in.S[c];
            gin[i].A[c] = (float)in.A[c];
        }
        gin[i].l = (float)in.l;
        gin[i].n = in.n;
        gin[i].s = in.s;
    }
    double rates[RUNS], seg_rates[RUNS];
    long verts = 0;
    draw(st, gin, N, NULL, 0); /* warm-up: shader compile to native code */
    for (int k = 0; k < RUNS; k++) {
        double t0 = now();
        verts = draw(st, gin, N, NULL, 0);
        glFinish();
        double t1 = now();
        rates[k] = verts / (t1 - t0);
        seg_rates[k] = N / (t1 - t0);
    }
    for (int i = 0; i < RUNS; i++)
        for (int j = i + 1; j < RUNS; j++) {
            if (rates[j] < rates[i]) { double t = rates[i]; rates[i] = rates[j]; rates[j] = t; }
            if (seg_rates[j] < seg_rates[i]) { double t = seg_rates[i]; seg_rates[i] = seg_rates[j]; seg_rates[j] = t; }
        }
    printf("bench: llvmpipe geometry shader, %d segments (%ld vertices) per draw, median of %d: %.3g vertices/s, "
           "%.3g segments/s (%s)\n", N, verts, RUNS, rates[RUNS / 2], seg_rates[RUNS / 2],
           (const char *)glGetString(GL_RENDERER));
    free(gin);
}

int main(int argc, char **argv) {
    uint32_t count = 20000;
    uint64_t seed = 2019;
    int do_bench = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--bench")) do_bench = 1;
        else if (!strcmp(argv[i], "--exact")) require_exact = 1;
        else if (!strcmp(argv[i], "--count") && i + 1 < argc) count = (uint32_t)strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--seed") && i + 1 < argc) seed = strtoull(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--geom") && i + 1 < argc) {
            FILE *f = fopen(argv[++i], "rb");
            if (!f) {
                fprintf(stderr, "test_segments_gl: cannot read %s\n", argv[i]);
                return 1;
            }
            geom_override = calloc(1, 1 << 20);
            if (!geom_override || fread(geom_override, 1, (1 << 20) - 1, f) == 0) return 1;
            fclose(f);
            printf("test_segments_gl: geometry shader from %s\n", argv[i]);
        }
    }
    if (count < 20) count = 20;
    /* Mesa's software rasteriser even where a GPU exists. */
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    setenv("GALLIUM_DRIVER", "llvmpipe", 0);
    gl_ctx g;
    const char *why = make_context(&g);
    if (why) return fail_loudly(why);
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    printf("test_segments_gl: %s, %s\n", (const char *)glGetString(GL_VERSION), renderer);
    if (!strstr(renderer, "llvmpipe"))
        fprintf(stderr, "test_segments_gl: note: the renderer is not llvmpipe; comparing anyway\n");
    GLint maxv = 0, maxc = 0;
    glGetIntegerv(GL_MAX_GEOMETRY_OUTPUT_VERTICES, &maxv);
    glGetIntegerv(GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS, &maxc);
    CHECK(maxv >= MAXV && maxc >= 8 * MAXV, "the driver allows %d geometry vertices, %d components", maxv, maxc);

    gl_state st;
    memset(&st, 0, sizeof st);
    const char *geom = geom_override ? geom_override : banyan_segment_shader_source(1);
    st.prog = build_program(geom);
    if (!st.prog) {
        CHECK(0, "the embedded shaders do not build");
        return check_done("test_segments_gl");
    }
    const char *ext_gs5 = "GL_ARB_gpu_shader5";
    GLint n_ext = 0, has_gs5 = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n_ext);
    for (GLint i = 0; i < n_ext; i++) has_gs5 |= !strcmp((const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i), ext_gs5);
    printf("test_segments_gl: %s %s: the shader uses `precise`\n", ext_gs5, has_gs5 ? "present" : "absent");
    setup(&st);
    CHECK(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE, "the 1x1 framebuffer is incomplete");

    run_result res;
    banyan_segment_params p;
    banyan_segment_params_init(&p);
    printf("paper parameters:\n");
    CHECK(compare_run(&st, &p, count, seed, &res), "run failed");
    /* Random angles and twig lengths. */
    pcg32 r;
    pcg32_seed(&r, seed, 7);
    for (int k = 0; k < 3; k++) {
        p.alpha_deg = rng_range(&r, -180, 180);
        p.beta_deg = rng_range(&r, -180, 180);
        p.gamma_deg = rng_range(&r, -180, 180);
        p.omega_deg = rng_range(&r, -180, 180);
        p.m = pow(10, rng_range(&r, -3, 3));
        printf("alpha %.3g beta %.3g gamma %.3g omega %.3g m %.3g:\n", p.alpha_deg, p.beta_deg, p.gamma_deg,
               p.omega_deg, p.m);
        CHECK(compare_run(&st, &p, count / 4, seed + 1 + (uint64_t)k, &res), "run failed");
    }
    /* The shader's fallback for drivers without `precise`: the same source
     * with the ARB_gpu_shader5 branch switched off. */
    char *plain = malloc(strlen(geom) + 1);
    const char *at = strstr(geom, "#ifdef GL_ARB_gpu_shader5");
    CHECK(at != NULL, "the geometry shader lost its `precise` switch");
    if (plain && at) {
        memcpy(plain, geom, strlen(geom) + 1);
        memcpy(plain + (at - geom), "#if 0 //", 8); /* same length as "#ifdef G" */
        GLuint fallback = build_program(plain);
        CHECK(fallback != 0, "the fallback (no precise) shader does not build");
        if (fallback) {
            GLuint keep = st.prog;
            st.prog = fallback;
            banyan_segment_params_init(&p);
            int saved = require_exact;
            require_exact = 0; /* fma fusion may change the last bits */
            printf("paper parameters, fallback without `precise`:\n");
            CHECK(compare_run(&st, &p, count / 4, seed + 10, &res), "run failed");
            require_exact = saved;
            st.prog = keep;
            glDeleteProgram(fallback);
        }
    }
    free(plain);
    if (do_bench) bench(&st);
    eglMakeCurrent(g.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(g.dpy, g.ctx);
    eglTerminate(g.dpy);
    return check_done("test_segments_gl");
}
