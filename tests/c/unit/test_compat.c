/* test_compat - the entry point names banyan/compat.h keeps (ABI 19's and
 * ABI 20's) give what the calls they wrap give: the same mesh bytes,
 * lines, stats, sizes and refusals. */
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "test_hosts.h"

int main(void) {
    banyan_error err = {0, ""};
    const banyan_box box = banyan_box_make(0, 0, 0.5, 0.5, 0.5, 0.5);
    banyan_hosts *h = TEST_HOSTS(&box, 1);

    banyan_roots_params rp;
    banyan_roots_params_init(&rp);
    banyan_mesh *a = NULL, *b = NULL, *c = NULL;
    banyan_roots_stats sa, sb;
    CHECK(banyan_roots_generate(&rp, h, &a, &sa, NULL, &err) == BANYAN_OK, "roots: %s", err.message);
    CHECK(banyan_roots_generate_hosts(&rp, h, &b, &sb, NULL, &err) == BANYAN_OK, "roots_generate_hosts: %s",
          err.message);
    CHECK(a && b && banyan_mesh_hash(a) == banyan_mesh_hash(b) && !memcmp(&sa, &sb, sizeof sa),
          "banyan_roots_generate_hosts differs from banyan_roots_generate");
    CHECK(banyan_roots_generate_stats(&rp, &box, 1, &c, &sb, &err) == BANYAN_OK, "roots_generate_stats: %s",
          err.message);
    CHECK(a && c && banyan_mesh_hash(a) == banyan_mesh_hash(c) && !memcmp(&sa, &sb, sizeof sa),
          "banyan_roots_generate_stats on the box differs from banyan_roots_generate on its host set");
    banyan_mesh_free(b), banyan_mesh_free(c);
    b = c = NULL;
    CHECK(banyan_roots_generate_stats(&rp, &box, 0, &c, NULL, &err) != BANYAN_OK && c == NULL,
          "roots_generate_stats: no box accepted");
    banyan_mesh_free(a);

    banyan_ivy_params ip;
    banyan_ivy_params_init(&ip);
    ip.steps = 60;
    banyan_ivy_stats ia, ib;
    a = b = NULL;
    CHECK(banyan_ivy_generate(&ip, h, &a, &ia, NULL, &err) == BANYAN_OK, "ivy: %s", err.message);
    CHECK(banyan_ivy_generate_hosts_stats(&ip, h, &b, &ib, NULL, &err) == BANYAN_OK, "ivy_generate_hosts_stats: %s",
          err.message);
    ia.step_seconds = ib.step_seconds = 0; /* the clock's */
    CHECK(a && b && banyan_mesh_hash(a) == banyan_mesh_hash(b) && !memcmp(&ia, &ib, sizeof ia),
          "banyan_ivy_generate_hosts_stats differs from banyan_ivy_generate");
    banyan_mesh_free(b);
    b = NULL;
    CHECK(banyan_ivy_generate_hosts(&ip, h, &b, NULL, &err) == BANYAN_OK && b &&
              banyan_mesh_hash(a) == banyan_mesh_hash(b),
          "banyan_ivy_generate_hosts differs from banyan_ivy_generate");
    banyan_mesh_free(b);
    banyan_ivy *iv = NULL;
    b = NULL;
    CHECK(banyan_ivy_create_hosts(&ip, h, &iv, &err) == BANYAN_OK && banyan_ivy_step(iv, ip.steps, &err) == BANYAN_OK &&
              banyan_ivy_mesh(iv, &b, &err) == BANYAN_OK && banyan_mesh_hash(a) == banyan_mesh_hash(b),
          "banyan_ivy_create_hosts then steps differ from banyan_ivy_generate: %s", err.message);
    banyan_ivy_free(iv);
    banyan_mesh_free(a), banyan_mesh_free(b);

    CHECK(banyan_sizeof_keyaki_statistics() == banyan_sizeof_keyaki_stats(), "keyaki stats sizes differ");

    /* ABI 20's names of the segment reference. */
    banyan_segment_params sgp;
    banyan_segment_params_init(&sgp);
    banyan_segment_input ins[2] = {{{0, 0, 0}, {0, 0, 1}, 2.0, 5, 2}, {{1, 0, 0}, {1, 0, 1}, 1.0, 3, 1}};
    static float xa[2 * 3 * BANYAN_SEGMENT_MAX_VERTICES], xb[2 * 3 * BANYAN_SEGMENT_MAX_VERTICES];
    static uint8_t la[2 * BANYAN_SEGMENT_MAX_VERTICES], lb[2 * BANYAN_SEGMENT_MAX_VERTICES];
    int32_t ca[2] = {0, 0}, cb[2] = {0, 0};
    CHECK(banyan_segment_lines(&ins[0], &sgp, xa, la, &ca[0], &err) == BANYAN_OK &&
              banyan_segment_generate(&ins[0], &sgp, xb, lb, &cb[0], &err) == BANYAN_OK && ca[0] > 2 &&
              ca[0] == cb[0] && !memcmp(xa, xb, sizeof(float) * 3 * (size_t)ca[0]) && !memcmp(la, lb, (size_t)ca[0]),
          "banyan_segment_generate differs from banyan_segment_lines: %s", err.message);
    memset(xa, 0, sizeof xa), memset(xb, 0, sizeof xb);
    CHECK(banyan_segment_lines_many(ins, 2, &sgp, xa, la, ca, &err) == BANYAN_OK &&
              banyan_segment_generate_many(ins, 2, &sgp, xb, lb, cb, &err) == BANYAN_OK && ca[1] > 2 &&
              ca[0] == cb[0] && ca[1] == cb[1] && !memcmp(xa, xb, sizeof xa) && !memcmp(la, lb, sizeof la),
          "banyan_segment_generate_many differs from banyan_segment_lines_many: %s", err.message);
    ins[1].n = 64;
    CHECK(banyan_segment_generate(&ins[1], &sgp, xb, NULL, &cb[0], &err) == BANYAN_E_RANGE && cb[0] == 0 &&
              strstr(err.message, "n = 64"),
          "banyan_segment_generate accepted n = 64: %s", err.message);
    CHECK(banyan_segment_generate_many(ins, 2, &sgp, xb, NULL, cb, &err) == BANYAN_E_RANGE &&
              strstr(err.message, "ins[1].n"),
          "banyan_segment_generate_many accepted ins[1].n = 64: %s", err.message);
    banyan_hosts_free(h);
    return check_done("test_compat");
}
