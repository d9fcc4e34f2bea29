/* test_hosts.h - host sets for the tests that describe their hosts as
 * boxes: TEST_HOSTS makes one (banyan_hosts_create) and stops the test,
 * naming the line and the library's message, when it is refused; the
 * roots and ivy one-shot calls on a box array make the set, generate on
 * it and free it. */
#ifndef BANYAN_TEST_HOSTS_H
#define BANYAN_TEST_HOSTS_H

#include <stdio.h>
#include <stdlib.h>

#include "banyan.h"

static inline banyan_hosts *test_hosts_make(const banyan_box *boxes, uint32_t n, const char *file, int line) {
    banyan_hosts *h = NULL;
    banyan_error e = {0};
    banyan_status s = banyan_hosts_create(boxes, n, NULL, 0, &h, &e);
    if (s) {
        fprintf(stderr, "%s:%d: banyan_hosts_create of %u boxes failed: %s: %s\n", file, line, n,
                banyan_status_name(s), e.message);
        exit(1);
    }
    return h;
}
/* A host set of boxes[0 .. n - 1]; free it with banyan_hosts_free. */
#define TEST_HOSTS(boxes, n) test_hosts_make((boxes), (n), __FILE__, __LINE__)

/* banyan_roots_generate / banyan_ivy_generate on a host set of the boxes
 * (no stats, no progress). */
#define test_roots_boxes(params, boxes, n, out, err) test_roots_boxes_at((params), (boxes), (n), (out), (err), __FILE__, __LINE__)
#define test_ivy_boxes(params, boxes, n, out, err) test_ivy_boxes_at((params), (boxes), (n), (out), (err), __FILE__, __LINE__)

static inline banyan_status test_roots_boxes_at(const banyan_roots_params *p, const banyan_box *boxes, uint32_t n,
                                                banyan_mesh **out, banyan_error *err, const char *file, int line) {
    banyan_hosts *h = test_hosts_make(boxes, n, file, line);
    banyan_status s = banyan_roots_generate(p, h, out, NULL, NULL, err);
    banyan_hosts_free(h);
    return s;
}
static inline banyan_status test_ivy_boxes_at(const banyan_ivy_params *p, const banyan_box *boxes, uint32_t n,
                                              banyan_mesh **out, banyan_error *err, const char *file, int line) {
    banyan_hosts *h = test_hosts_make(boxes, n, file, line);
    banyan_status s = banyan_ivy_generate(p, h, out, NULL, NULL, err);
    banyan_hosts_free(h);
    return s;
}

#endif
