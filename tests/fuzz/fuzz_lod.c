/* fuzz_lod.c - libFuzzer harness for banyan_mesh_lod_budget: a small mesh
 * from bytes (fuzz_mesh.h, hostile when its flags say so), then the level
 * of detail's params and budget:
 *   ratio   u8: (b + 1) / 256, or with the next byte's bit 0 a raw double
 *   flags   bit 1 billboard, bit 2 a 0.01 s budget (else 5 s: stops it
 *           between parts and cards), bit 3 a NULL params (the defaults)
 *   planes  1 + b % 9 (1 and 9 outside 2 .. 8);  size  one of 16, 32,
 *           64, 128, 256, 1000 (16 and 1000 refused);  seed u8
 * A refusal must be clean; a level must have its indices in range, parts
 * covering it in order, no more triangles than the mesh (simplified), a
 * billboard's parts 2 x planes vertical quads and a top card in turn, uvs
 * inside the picture,
 * and
 * be the same again for the same input (when no budget stopped either). */
#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_level(const banyan_mesh *in, const banyan_lod_params *p, const banyan_mesh *o) {
    FZ_ASSERT(o != NULL, "OK without a mesh");
    FZ_ASSERT(o->index_count % 3 == 0, "index_count %u", o->index_count);
    for (uint32_t i = 0; i < o->index_count; i++)
        FZ_ASSERT(o->indices[i] < o->vertex_count, "index %u = %u of %u", i, o->indices[i], o->vertex_count);
    uint64_t v_end = 0, i_end = 0;
    for (uint32_t q = 0; q < o->part_count; q++) {
        const banyan_part *pt = &o->parts[q];
        FZ_ASSERT(pt->material < o->material_count, "part %u material %u of %u", q, pt->material, o->material_count);
        FZ_ASSERT(pt->vertex_offset == v_end && pt->index_offset == i_end, "part %u not in order", q);
        for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k++)
            FZ_ASSERT(o->indices[k] >= pt->vertex_offset && o->indices[k] < pt->vertex_offset + pt->vertex_count,
                      "part %u: index %u outside its vertices", q, o->indices[k]);
        v_end += pt->vertex_count;
        i_end += pt->index_count;
    }
    FZ_ASSERT(v_end == o->vertex_count && i_end == o->index_count, "parts do not cover the level");
    FZ_ASSERT(fz_finite(o->positions, 3 * (size_t)o->vertex_count), "a position is not finite");
    if (!p || !p->billboard) {
        FZ_ASSERT(o->index_count <= in->index_count, "%u indices from %u", o->index_count, in->index_count);
        FZ_ASSERT(o->part_count == in->part_count, "%u parts from %u", o->part_count, in->part_count);
    } else {
        uint32_t planes = (uint32_t)(p ? p->billboard_planes : 3);
        for (uint32_t q = 0; q < o->part_count; q++) /* 2 x planes vertical half quads, then a top card */
            FZ_ASSERT(o->parts[q].index_count == (q % 2 ? 6 : 12 * planes), "card part %u: %u indices for %u planes",
                      q, o->parts[q].index_count, planes);
        for (uint32_t v = 0; v < 2 * o->vertex_count; v++)
            FZ_ASSERT(o->uvs[v] >= 0 && o->uvs[v] <= 1, "card uv %u = %g outside the picture", v, (double)o->uvs[v]);
        for (uint32_t k = 0; k < o->image_count; k++)
            FZ_ASSERT(o->images[k].pixels && o->images[k].width >= 1 && o->images[k].height >= 1 &&
                          o->images[k].width <= (uint32_t)p->billboard_size &&
                          o->images[k].height <= (uint32_t)p->billboard_size,
                      "picture %u: %u x %u", k, o->images[k].width, o->images[k].height);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader r = {data, size, 0};
    fz_mesh fm;
    fz_mesh_read(&r, &fm);
    banyan_lod_params p;
    banyan_lod_params_init(&p);
    uint8_t rb = fz_u8(&r), flags = fz_u8(&r);
    p.ratio = (rb + 1) / 256.0;
    if (flags & 1) {
        uint8_t raw[8];
        fz_bytes(&r, raw, 8);
        memcpy(&p.ratio, raw, 8);
    }
    p.billboard = (flags >> 1) & 1;
    p.billboard_planes = 1 + fz_u8(&r) % 9;
    static const int32_t sizes[6] = {16, 32, 64, 128, 256, 1000};
    p.billboard_size = sizes[fz_u8(&r) % 6];
    p.seed = fz_u8(&r);
    banyan_budget b;
    banyan_budget_init(&b);
    b.max_seconds = flags & 4 ? 0.01 : 5.0;
    b.max_memory_mb = 1024;
    const banyan_lod_params *pp = flags & 8 ? NULL : &p;

    banyan_mesh *o = NULL, *again = NULL;
    banyan_error e, e2;
    memset(&e, 0, sizeof e);
    banyan_status s = banyan_mesh_lod_budget(&fm.m, pp, &b, &o, &e);
    if (s) {
        fz_check_failure(s, &e, o);
    } else {
        FZ_ASSERT(e.code == BANYAN_OK, "OK with err.code %d", e.code);
        check_level(&fm.m, pp, o);
        banyan_status s2 = banyan_mesh_lod_budget(&fm.m, pp, &b, &again, &e2);
        if (!fz_budget_stop(s2, &e2)) {
            FZ_ASSERT(s2 == BANYAN_OK && banyan_mesh_hash(o) == banyan_mesh_hash(again),
                      "the same input gave another level (%s)", e2.message);
        }
        banyan_mesh_free(again);
        banyan_mesh_free(o);
    }
    fz_mesh_free(&fm);
    return 0;
}
