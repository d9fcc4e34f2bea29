/* Panel words of the parameter tables (banyan.h, banyan_param_info.label
 * and .group): every row of every generator has a label and a group, a
 * label is words (see words_only), labels are unique within a table, and a
 * group's rows are consecutive so the table's order is the panel's. */
#include <ctype.h>
#include <string.h>

#include "check.h"
#include "banyan.h"

#define MAX_ROWS 256

/* Words: starts with a capital; each word (split at spaces, brackets,
 * '/', ',', '-') is letters only and at least two of them, or "a". So
 * "Branch angle" and "Forward pull (min)" pass, "T0", "W geo", "H1 buds"
 * and "stem_radius" do not: the paper's symbols belong in the tooltip. */
static int words_only(const char *s) {
    if (!isupper((unsigned char)s[0])) return 0;
    const char *p = s;
    while (*p) {
        while (*p && strchr(" ()/,-", *p)) p++;
        const char *w = p;
        while (*p && !strchr(" ()/,-", *p)) {
            if (!isalpha((unsigned char)*p)) return 0;
            p++;
        }
        size_t n = (size_t)(p - w);
        if (n == 1 && *w != 'a' && *w != 'A') return 0;
    }
    return 1;
}

int main(void) {
    CHECK(words_only("Branch angle") && words_only("Forward pull (min)") && !words_only("T0") &&
              !words_only("W geo") && !words_only("H1 buds") && !words_only("stem_radius"),
          "the rule itself");
    for (int g = 0; g < BANYAN_GEN_COUNT; g++) {
        const char *gen = banyan_generator_name((banyan_generator)g);
        int32_t n = banyan_param_count((banyan_generator)g);
        CHECK(n > 0 && n <= MAX_ROWS, "%s: %d rows", gen, n);
        if (n <= 0 || n > MAX_ROWS) continue;
        const char *groups[MAX_ROWS];
        int ngroups = 0;
        for (int32_t i = 0; i < n; i++) {
            const banyan_param_info *p = banyan_param_get((banyan_generator)g, i);
            CHECK(p->label && p->label[0], "%s.%s has no label", gen, p->name);
            CHECK(p->group && p->group[0], "%s.%s has no group", gen, p->name);
            if (!p->label || !p->group || !p->label[0] || !p->group[0]) continue;
            CHECK(words_only(p->label), "%s.%s: label '%s' is not words an artist knows", gen, p->name, p->label);
            CHECK(words_only(p->group), "%s.%s: group '%s' is not words", gen, p->name, p->group);
            for (int32_t j = 0; j < i; j++) {
                const banyan_param_info *q = banyan_param_get((banyan_generator)g, j);
                CHECK(strcmp(q->label, p->label) != 0, "%s: '%s' labels both %s and %s", gen, p->label, q->name,
                      p->name);
            }
            /* A new group starts here unless it continues the previous row's. */
            if (ngroups == 0 || strcmp(groups[ngroups - 1], p->group) != 0) {
                for (int k = 0; k < ngroups; k++)
                    CHECK(strcmp(groups[k], p->group) != 0, "%s: group '%s' is split (again at %s)", gen, p->group,
                          p->name);
                groups[ngroups++] = p->group;
            }
        }
        CHECK(ngroups >= 2 && ngroups <= 10, "%s: %d groups (a handful is readable)", gen, ngroups);
    }
    return check_done("test_param_labels");
}
