/* test_compat - ABI 19's entry point names (banyan/compat.h) give what the
 * calls they wrap give: the same mesh bytes, stats and sizes. */
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
    banyan_hosts_free(h);
    return check_done("test_compat");
}
