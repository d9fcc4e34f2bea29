/* Compact glTF (banyan_gltf_options.compact): KHR_mesh_quantization and
 * EXT_meshopt_compression, made from the .glb that banyan's own writer
 * writes (docs/gltf.md "Compact files"). */
#ifndef BANYAN_GLTF_COMPACT_H
#define BANYAN_GLTF_COMPACT_H

#include "banyan.h"

#include <functional>

/* Writes the compact asset at `path` (binary: .glb, else .gltf with the
 * buffer as a data URI). `write_plain` writes the uncompressed .glb to the
 * path it is given (a temporary file beside `path`, removed afterwards);
 * its result is read back, quantized and compressed. The target is
 * replaced only when all of it is written (base/atomic_file.h); `sync`
 * fsyncs it first. `engine_uvs`: TEXCOORD_1 and _2 hold pivots
 * (banyan_gltf_options.engine_uvs), which follow the positions' frame. */
banyan_status gltf_compact_write(const char *path, bool binary, bool sync, bool engine_uvs,
                                 const std::function<banyan_status(const char *plain_glb)> &write_plain,
                                 banyan_error *err);

#endif
