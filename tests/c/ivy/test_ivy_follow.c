/* test_ivy_follow - runs alongside stems (follow_length, csrc/ivy/growth.c
 * follow_stem) on ivy_wall: off at 0, runs no longer than follow_length,
 * each followed internode beside a stem that is not its own, and the
 * plant the same on a second run. */
#include <stdio.h>
#include <stdlib.h>

#include "banyan.h"
#include "check.h"
#include "ivy/ivy_internal.h"
#include "ivy_look.h"

/* Is a stem not sharing bud i (nor its parent) within `reach` of bud i? */
static int beside_a_stem(const banyan_ivy *iv, int32_t i, double reach) {
    const ivy_bud *b = &iv->buds[i];
    for (int32_t j = 0; j < iv->n; j++) {
        const ivy_bud *c = &iv->buds[j];
        if (j == i || j == b->parent || c->parent == i || c->parent < 0 || c->parent == b->parent) continue;
        if (v3_dist(c->P, b->P) < reach) return 1;
    }
    return 0;
}

int main(void) {
    banyan_ivy_params p;
    banyan_error err = {0, ""};
    banyan_hosts *H = ivy_look_wall(&p);
    if (!H) return 1;
    p.steps = 300;

    p.follow_length = 0;
    banyan_ivy *iv = ivy_look_grow(&p, H);
    CHECK(iv, "ivy_wall did not grow");
    int32_t followers = 0;
    for (int32_t i = 0; iv && i < iv->n; i++) followers += iv->buds[i].follow > 0;
    CHECK(iv && followers == 0, "follow_length 0: %d buds grew alongside a stem", followers);
    banyan_ivy_free(iv);

    p.follow_length = 4 * p.internode;
    iv = ivy_look_grow(&p, H);
    CHECK(iv, "ivy_wall did not grow");
    CHECK(iv, "ivy_wall did not grow");
    int32_t longest = 0, lone = 0;
    followers = 0;
    for (int32_t i = 0; iv && i < iv->n; i++) {
        const ivy_bud *b = &iv->buds[i];
        if (b->follow <= 0) continue;
        followers++;
        longest = b->follow > longest ? b->follow : longest;
        lone += !beside_a_stem(iv, i, 2 * p.internode);
    }
    printf("  ivy_wall, 300 steps, follow_length 4 internodes: %d of %d buds grown alongside, longest run %d\n",
           followers, iv ? iv->n : 0, longest);
    CHECK(followers >= 50, "only %d buds grew alongside a stem", followers);
    CHECK(longest <= 4, "a run of %d internodes, follow_length allows 4", longest);
    CHECK(lone == 0, "%d buds grown alongside no stem within 2 internodes", lone);
    banyan_mesh *m1 = NULL, *m2 = NULL;
    CHECK(iv && banyan_ivy_mesh(iv, &m1, &err) == BANYAN_OK, "mesh: %s", err.message);
    banyan_ivy_free(iv);
    iv = ivy_look_grow(&p, H);
    CHECK(iv, "ivy_wall did not grow");
    CHECK(iv, "ivy_wall did not grow");
    CHECK(iv && banyan_ivy_mesh(iv, &m2, &err) == BANYAN_OK, "mesh again: %s", err.message);
    CHECK(m1 && m2 && banyan_mesh_hash(m1) == banyan_mesh_hash(m2), "a second run differs");
    banyan_mesh_free(m1);
    banyan_mesh_free(m2);
    banyan_ivy_free(iv);
    banyan_hosts_free(H);
    return check_done("test_ivy_follow");
}
