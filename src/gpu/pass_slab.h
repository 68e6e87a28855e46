/* src/gpu/pass_slab.h: the slab pass: the GPU side of the multiple-scattering slab model (Kol 3.1.3-3.1.5): the
 * fitted tables as textures and the slab maps from the sun and from the zenith (shaders_gles/slab_map.frag),
 * mipmapped for the collector-area blur. */
#ifndef CU_PASS_SLAB_H
#define CU_PASS_SLAB_H
#include "gpu_scene.h"
#include "target.h"

typedef struct cu_pass_slab {
    cu_slab_model *model;           /* the fitted tables (slab and collector modes), kept between scenes */
    struct cu_collector *collector; /* the collector table (collector mode) */
    GLuint prog, tab_tex, coll_tex;
    cu_density_locs density;
    GLint map_dir, map_right, map_up, map_R, map_size;
    int maps;                       /* slab maps a cloud has: from the sun [0] and (with a Preetham sky) the zenith [1] */
    cu_slab_maps out;               /* the tables every cloud's maps share (cu_pass_slab_maps_create copies them) */
} cu_pass_slab;

/* The multiple-scattering mode in use for ctx->scene (slab needs half-float targets: else octaves), into *ms_mode;
 * loads data_dir/slab_fit_bouthors.txt (and slab_collector.txt) when it needs them. */
int cu_pass_slab_load(cu_pass_slab *p, const cu_gpu_scene *ctx, const char *data_dir, int *ms_mode, cu_error *err);
/* The shader defines of the loaded model (node counts, SKY_SPLIT); non-zero when buf is too small. */
int cu_pass_slab_defines(const cu_pass_slab *p, const cu_gpu_scene *ctx, char *buf, size_t n);
/* Tables and program (built with `defines`), for ctx->ms_mode. */
int cu_pass_slab_create(cu_pass_slab *p, const cu_gpu_scene *ctx, const char *defines, cu_error *err);
/* A cloud's slab maps (the cloud owns them: cu_target_delete), and what the cloud pass reads: out. Nothing when the
 * mode is not the slab model's. */
int cu_pass_slab_maps_create(const cu_pass_slab *p, const cu_gpu_scene *ctx, int size, cu_target map[2],
                             cu_slab_maps *out, cu_error *err);
/* GL objects only: the tables stay loaded for the next scene. */
void cu_pass_slab_destroy(cu_pass_slab *p, const cu_gl *gl);
/* The tables (with the renderer). */
void cu_pass_slab_free(cu_pass_slab *p);
/* Renders ctx->cloud's map 0 (from the sun) or 1 (from the zenith: it depends on the cloud alone), its rows
 * [rows[0], rows[1]) (a band, frame_maps.c; NULL: all), and its mip chain when mipmaps (the last band of the map).
 * Leaves the scissor as cu_sun_band_scissor sets it. */
void cu_pass_slab_update(const cu_pass_slab *p, const cu_gpu_scene *ctx, int which, const cu_target map[2],
                         const int rows[2], cu_slab_maps *out, int mipmaps);
#endif
