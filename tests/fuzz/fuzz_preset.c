/* fuzz_preset.c - libFuzzer harness for the preset reader: the bytes are a
 * preset file. Every reader runs on them - banyan_preset_apply for each
 * generator, banyan_preset_hosts, banyan_preset_meshes, banyan_segments_preset_read (counting,
 * then filling) - and, when the text has a '=', banyan_param_set_text with
 * the text before it as key and after it as value. What a reader accepts
 * must pass the checks the generators run (banyan_params_check,
 * banyan_box_validate, banyan_segment_check). The input is copied into a
 * buffer of exactly its size, so ASan sees any read past the end. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *text = malloc(size ? size : 1);
    memcpy(text, data, size);
    static unsigned char params[8192];
    banyan_error e;
    for (int g = 0; g < BANYAN_GEN_COUNT; g++) {
        fz_params_init((banyan_generator)g, params);
        memset(&e, 0, sizeof e);
        banyan_status s = banyan_preset_apply((banyan_generator)g, params, text, size, "fuzz.json", &e);
        if (s) {
            fz_check_failure(s, &e, NULL);
            continue;
        }
        banyan_status c = banyan_params_check((banyan_generator)g, params, &e);
        FZ_ASSERT(c == BANYAN_OK, "%s: a preset the reader accepts fails the table check: %s",
                  banyan_generator_name((banyan_generator)g), e.message);
    }
    static banyan_box hosts[BANYAN_MAX_HOSTS];
    uint32_t n = 77;
    memset(&e, 0, sizeof e);
    banyan_status s = banyan_preset_hosts(text, size, "fuzz.json", hosts, BANYAN_MAX_HOSTS, &n, &e);
    if (s) {
        fz_check_failure(s, &e, NULL);
        FZ_ASSERT(n == 0, "hosts count %u on failure", n);
    } else {
        FZ_ASSERT(n <= BANYAN_MAX_HOSTS, "%u hosts", n);
        for (uint32_t i = 0; i < n; i++)
            FZ_ASSERT(banyan_box_validate(&hosts[i], i, &e) == BANYAN_OK, "host %u accepted but invalid: %s", i,
                      e.message);
    }
    /* Mesh host entries: composed transforms finite, paths and names
     * terminated, indices inside the hosts list. */
    static banyan_preset_mesh meshes[BANYAN_MAX_HOSTS];
    n = 77;
    memset(&e, 0, sizeof e);
    s = banyan_preset_meshes(text, size, "fuzz.json", "base", meshes, BANYAN_MAX_HOSTS, &n, &e);
    if (s) {
        fz_check_failure(s, &e, NULL);
        FZ_ASSERT(n == 0, "mesh count %u on failure", n);
    } else {
        FZ_ASSERT(n <= BANYAN_MAX_HOSTS, "%u mesh hosts", n);
        for (uint32_t i = 0; i < n; i++) {
            for (int k = 0; k < 12; k++)
                FZ_ASSERT(isfinite(meshes[i].transform[k]), "mesh %u transform[%d] not finite", i, k);
            FZ_ASSERT(memchr(meshes[i].path, 0, sizeof meshes[i].path) && memchr(meshes[i].name, 0, sizeof meshes[i].name),
                      "mesh %u path or name unterminated", i);
            FZ_ASSERT(i == 0 || meshes[i].index > meshes[i - 1].index, "mesh %u index %u out of order", i,
                      meshes[i].index);
        }
    }
    uint32_t count = 0;
    s = banyan_segments_preset_read(text, size, "fuzz.json", NULL, 0, &count, NULL, NULL, &e);
    if (s) fz_check_failure(s, &e, NULL);
    else if (count > 0 && count <= 4096) {
        banyan_segment_input *segs = malloc(sizeof *segs * count);
        double trunk[6];
        int32_t has = 0;
        uint32_t count2 = 0;
        s = banyan_segments_preset_read(text, size, "fuzz.json", segs, count, &count2, trunk, &has, &e);
        FZ_ASSERT(s == BANYAN_OK && count2 == count, "counted %u, read %u: %s", count, count2, e.message);
        banyan_segment_params sp;
        banyan_segment_params_init(&sp);
        for (uint32_t i = 0; i < count; i++)
            FZ_ASSERT(banyan_segment_check(&segs[i], &sp, &e) == BANYAN_OK, "segment %u accepted but invalid: %s", i,
                      e.message);
        free(segs);
    }
    /* key=value through --set's parser. */
    const char *eq = memchr(text, '=', size);
    if (eq && size < 512) {
        char kv[512];
        memcpy(kv, text, size);
        kv[size] = 0;
        kv[eq - text] = 0;
        for (int g = 0; g < BANYAN_GEN_COUNT; g++) {
            fz_params_init((banyan_generator)g, params);
            s = banyan_param_set_text((banyan_generator)g, params, kv, kv + (eq - text) + 1, &e);
            if (s) fz_check_failure(s, &e, NULL);
            else FZ_ASSERT(banyan_params_check((banyan_generator)g, params, &e) == BANYAN_OK,
                           "--set %s accepted but the table check fails: %s", kv, e.message);
        }
    }
    free(text);
    return 0;
}
