/* The C API of softshadow: the only door for the Blender add-on, the CLI and outside tools.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * Conventions
 * - Every function returns an ss_status (or a plain value that cannot fail). On failure the
 *   message is in ss_last_error(), which is thread-local and valid until the next call on the
 *   same thread. No function lets a C++ exception escape.
 * - Matrices are float[16] in column-major order (OpenGL / GLM layout): m[col*4 + row].
 *   A Blender mathutils.Matrix M becomes [M[r][c] for c in range(4) for r in range(4)].
 * - Cameras look down their local -Z axis; the projection maps to OpenGL clip space.
 * - Images are float32, width x height, row 0 = the TOP row of the picture.
 * - Method names (contract): "shadow_map", "pcss", "dbuffer", "sweep", "penumbra_map",
 *   "occlusion_textures", "reference", or "auto".
 * - The scene range: meshes and lights must lie within 10000 x the camera's far clip distance
 *   of the camera (and within 1e15): a mesh beyond it is skipped (ss_result_warnings), a light
 *   beyond it gets no pass (SS_ERROR_INVALID_SCENE). See docs/reliability.md.
 */
#ifndef SOFTSHADOW_H
#define SOFTSHADOW_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define SS_API __declspec(dllexport)
#else
#define SS_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ss_status {
    SS_OK = 0,
    SS_ERROR_INVALID_ARGUMENT = 1, /* a null pointer, an unknown name, a bad option */
    SS_ERROR_INVALID_SCENE = 2,    /* NaN geometry, index out of range, zero-size light ... */
    SS_ERROR_IO = 3,               /* missing file, malformed file, unwritable output */
    SS_ERROR_GL = 4,               /* no GL backend, shader or framebuffer failure */
    SS_ERROR_UNSUPPORTED = 5,      /* a method that cannot handle this light or scene */
    SS_ERROR_CANCELLED = 6,        /* the progress callback asked to stop */
    SS_ERROR_INTERNAL = 7
} ss_status;

typedef enum ss_backend {
    SS_BACKEND_AUTO = 0,  /* EGL surfaceless first, then OSMesa */
    SS_BACKEND_EGL = 1,
    SS_BACKEND_OSMESA = 2,
    /* Reserved: pin the enum to 32 bits and make every int32 a valid value, so a bad value
       from a C caller is reported as an error rather than being undefined behaviour. */
    SS_BACKEND_RESERVED_MIN_ = -0x7fffffff - 1,
    SS_BACKEND_RESERVED_MAX_ = 0x7fffffff
} ss_backend;

typedef enum ss_light_type {
    SS_LIGHT_DISK = 0,      /* area light, size = diameter */
    SS_LIGHT_ELLIPSE = 1,   /* area light, size x size_y diameters */
    SS_LIGHT_SQUARE = 2,    /* area light, size x size */
    SS_LIGHT_RECTANGLE = 3, /* area light, size x size_y */
    SS_LIGHT_POINT = 4,     /* sphere of radius `radius` */
    SS_LIGHT_SPOT = 5,      /* sphere of radius `radius`, cone spot_size (full angle, rad) */
    SS_LIGHT_SUN = 6,       /* directional, angular diameter `angle` (rad) */
    /* Reserved, as for ss_backend. */
    SS_LIGHT_RESERVED_MIN_ = -0x7fffffff - 1,
    SS_LIGHT_RESERVED_MAX_ = 0x7fffffff
} ss_light_type;

/* Mesh flags. */
#define SS_MESH_CAST 1u    /* the mesh casts shadows */
#define SS_MESH_RECEIVE 2u /* the mesh receives shadows (pixels on it are in the mask) */
#define SS_MESH_THIN 4u    /* a thin occluder (occlusion_textures' leak fix) */
#define SS_MESH_CAMERA_HIDDEN 8u /* the camera sees past the mesh, which still casts with SS_MESH_CAST
                                    (Blender: camera ray visibility off, Cycles' Indirect Only) */

typedef struct ss_light_desc {
    const char* name;          /* unique within the scene; 1..131 bytes of UTF-8, no control chars */
    ss_light_type type;
    float light_to_world[16];  /* Blender's matrix_world: the light emits along local -Z */
    float size;                /* area: size (diameter for disk/ellipse) */
    float size_y;              /* area ellipse/rectangle: second size */
    float radius;              /* point/spot: shadow_soft_size */
    float angle;               /* sun: angular diameter in radians */
    float spot_size;           /* spot: full cone angle in radians */
    float spot_blend;          /* spot: 0..1 */
    int32_t cast_shadows;      /* 0: the light gets no pass */
} ss_light_desc;

typedef struct ss_camera_desc {
    float world_to_camera[16];  /* view matrix */
    float projection[16];       /* camera -> OpenGL clip space, pixel aspect and shift baked in */
    int32_t width, height;      /* final pixel resolution (render percentage applied) */
    float pixel_aspect;         /* informational: already part of `projection` */
} ss_camera_desc;

/* Called from the rendering thread. Return non-zero to cancel. fraction in [0,1].
 * From inside it, ss_render, ss_context_info, ss_context_destroy and ss_shutdown fail with
 * SS_ERROR_INVALID_ARGUMENT (ss_context_destroy then leaves the context alive) instead of
 * waiting on the render that is calling back. */
typedef int (*ss_progress_fn)(void* user, float fraction, const char* stage);

typedef struct ss_context ss_context; /* a GL context on a render thread owned by the library */
typedef struct ss_scene ss_scene;
typedef struct ss_result ss_result;   /* the layers of one (light, method) render */

/* Refinement in rounds: with refine = SS_REFINE_ON and refine_rounds = N > 1 a GL method's
 * uncertain pixels are traced in N shares of equal size, the largest expected correction first,
 * and after each round but the last this is called on the thread that called ss_render with the
 * result so far (`round` of `rounds`, 1-based): every ss_result_* function reads it (its
 * warnings and methods rendered come with the final result), valid until the call returns. Pixels traced in a
 * round keep their value in later rounds (up to the guard band's further rounds), so its error does not rise;
 * the last round's result, which ss_render returns, is the one-round result to the bit. Return non-zero to
 * cancel (ss_render then returns SS_ERROR_CANCELLED). The same calls are refused from inside it as from a
 * progress callback. */
typedef int (*ss_round_fn)(void* user, const ss_result* partial, int32_t round, int32_t rounds);

/* Refinement: whether ss_render re-traces a GL method's uncertain pixels with rays (the
 * settings refine_margin, refine_samples, refine_verify, error_target and guard_band tune it;
 * docs/contracts.md). The reference is exact already and is never refined; ss_sweep_shadow_mesh
 * does not read it. */
typedef enum ss_refine {
    SS_REFINE_OFF = 0,
    SS_REFINE_ON = 1,
    /* Reserved, as for ss_backend. */
    SS_REFINE_RESERVED_MIN_ = -0x7fffffff - 1,
    SS_REFINE_RESERVED_MAX_ = 0x7fffffff
} ss_refine;

/* Fill with ss_render_options_default, then set the fields wanted: a value out of range fails
 * the render with SS_ERROR_INVALID_ARGUMENT naming the field. */
typedef struct ss_render_options {
    int32_t samples;         /* light samples (reference, sweep, pcss...); 0 = method default */
    uint32_t seed;           /* deterministic sampling */
    int32_t extra_layers;    /* 1: umbra/penumbra/mask and method debug layers; 0: V only */
    ss_progress_fn progress; /* may be NULL */
    void* progress_user;
    const char* settings;    /* optional "key=value;key=value" method settings, may be NULL */
    ss_round_fn round;       /* may be NULL: refinement rounds are not handed out */
    void* round_user;
    ss_refine refine;      /* default SS_REFINE_OFF */
    int32_t refine_rounds; /* with SS_REFINE_ON: the shares the pixels are traced in, 1..64
                              (0: 1); each but the last goes to `round` */
} ss_render_options;

SS_API const char* ss_version(void);
SS_API const char* ss_last_error(void);
SS_API void ss_render_options_default(ss_render_options* options);
/* Unlinks the temporary files of writes in progress (ss_write_exr, ss_scene_save). Async-signal-
 * safe: call it from a SIGINT/SIGTERM handler so an interrupted write leaves nothing behind. */
SS_API void ss_remove_temporary_files(void);
/* Installs, for SIGINT, SIGTERM and SIGHUP where each still has its default action (it ends the
 * process), a handler that calls ss_remove_temporary_files and then ends the process by that
 * signal (what a farm's SIGTERM does, less the stray file). A signal the host handles or ignores
 * keeps its disposition. Returns how many of the three now have the handler. Every write also
 * removes, first, the temporary files in its folder whose writer was killed (SIGKILL, a crash):
 * their process is gone from this host. */
SS_API int32_t ss_remove_temporary_files_on_signals(void);

/* GL context. `info_json` describes backend, renderer, GL version and limits. */
SS_API ss_status ss_context_create(ss_backend backend, ss_context** out);
/* Safe while an ss_render on the context runs on another thread: that render is cancelled at
   its next check (it returns SS_ERROR_CANCELLED) and destroy returns once it has. A call that
   starts on the context after destroy has begun is refused (or, after it returned, invalid).
   Never call it from a progress callback of a render on the same context: it would wait for
   itself. */
SS_API void ss_context_destroy(ss_context* context);
/* Cancels the renders running on the context now, from any thread (a progress callback too):
   each returns SS_ERROR_CANCELLED at its next check, as from ss_context_destroy, and the context
   stays usable; renders started once those returned run as usual. Does not wait. */
SS_API void ss_context_cancel_renders(ss_context* context);
SS_API ss_status ss_context_info(const ss_context* context, char* buffer, size_t buffer_size);
/* What the context's caches did over its life, as named counters (for tests and the benchmark):
   frames made (one per scene), meshes uploaded to the GPU, camera passes and shadow maps drawn
   (and how many only where meshes moved), milliseconds spent in them and in GL methods, Embree
   scenes and mesh BVHs built, and more. The counters are index 0 .. ss_cache_stat_count()-1:
   ss_cache_stat_name gives each one's name ("mesh_uploads", "camera_pass_ms", ...) and
   ss_cache_stat_doc what it counts (NULL for an index out of range); the list may grow between
   versions, so a caller looks counters up by name (docs/contracts.md).
   ss_context_cache_stat reads one by name into *out (counts are whole numbers); an unknown name
   fails with SS_ERROR_INVALID_ARGUMENT naming the valid ones. Each call reads the counters
   anew: read them while no render runs on the context for a consistent set. */
SS_API int32_t ss_cache_stat_count(void);
SS_API const char* ss_cache_stat_name(int32_t index);
SS_API const char* ss_cache_stat_doc(int32_t index);
SS_API ss_status ss_context_cache_stat(const ss_context* context, const char* name, double* out);
/* Joins every render thread the library started. Call from the host before it exits. */
SS_API void ss_shutdown(void);
/* The methods this library has, by name ("auto" is not one): index 0 .. ss_method_count()-1;
   NULL for an index out of range. */
SS_API int32_t ss_method_count(void);
SS_API const char* ss_method_name(int32_t index);
/* The settings a method (a name above, or "auto") takes in ss_render_options.settings, as a user
   sees them: index 0 .. ss_method_setting_count(method)-1, the method's own first, then the ones
   every method takes (estimate_rmse, refine_margin..., memory_limit_mb). Test switches ("debug." keys)
   are accepted by ss_render but not listed. The count is -1 for an unknown method (ss_last_error
   says why). The strings stay valid until the process exits. */
typedef struct ss_setting_info {
    const char* key;
    const char* type;          /* "int", "float", "bool", "choice" or "text" */
    const char* default_value; /* as written in settings ("8", "off", "sat"); "" where the render decides */
    const char* range;         /* "1..16", "0 or 16..8192", "on/off", "sat|mipmap|nbuffer"; "" for text */
    const char* doc;           /* one line */
} ss_setting_info;
SS_API int32_t ss_method_setting_count(const char* method);
SS_API ss_status ss_method_setting_info(const char* method, int32_t index, ss_setting_info* out);

/* Scenes. */
SS_API ss_status ss_scene_create(ss_scene** out);
SS_API void ss_scene_destroy(ss_scene* scene);
SS_API ss_status ss_scene_load(const char* path, ss_scene** out);
SS_API ss_status ss_scene_save(const ss_scene* scene, const char* path);
/* A mesh: `xyz` its vertices in object space, `triangles` 0-based vertex indices, placed in the
   world by `object_to_world` (column-major, affine: last row 0 0 0 1; NULL = the identity, for
   vertices given in world space). The library derives the world vertices and normals from the
   three (ss_scene_set_mesh_transform moves it later); a mirroring matrix (negative determinant)
   keeps the surface's outside outside, as Blender does. A non-finite or non-affine matrix, or one
   that sends a vertex to infinity, fails with SS_ERROR_INVALID_ARGUMENT naming the mesh; NaN
   coordinates and indices out of range with SS_ERROR_INVALID_SCENE. */
SS_API ss_status ss_scene_add_mesh(ss_scene* scene, const char* name, const float* xyz,
                                   uint32_t vertex_count, const uint32_t* triangles,
                                   uint32_t triangle_count, const float object_to_world[16], uint32_t flags,
                                   int32_t* out_index);
SS_API ss_status ss_scene_add_light(ss_scene* scene, const ss_light_desc* light, int32_t* out_index);
/* Incremental edits of a scene kept alive across renders (the preview's): each changes one mesh
   or light and leaves the others' cached GPU buffers and shadow maps in place (a mesh edit
   redraws the camera pass and the shadow maps, which see every mesh; a light edit redraws only
   that light's maps; a camera change only the camera pass). Indices out of range fail with
   SS_ERROR_INVALID_ARGUMENT; a refused edit leaves the scene as it was.
   update_mesh: new geometry and flags for mesh `index`; its name and transform are kept, and
   `xyz` is in the mesh's object space. */
SS_API ss_status ss_scene_update_mesh(ss_scene* scene, int32_t index, const float* xyz,
                                      uint32_t vertex_count, const uint32_t* triangles,
                                      uint32_t triangle_count, uint32_t flags);
/* Places mesh `index` at object_to_world (column-major, affine, as in ss_scene_add_mesh)
   applied to its object-space vertices: a move costs one matrix product per vertex, never a new
   adjacency. A refused matrix leaves the mesh where it was. */
SS_API ss_status ss_scene_set_mesh_transform(ss_scene* scene, int32_t index, const float object_to_world[16]);
/* What a mesh's materials let through on shadow rays, as Cycles' shadow rays see them: a
   surface transmits (1 - alpha) of the light, transmissions multiply along the ray, and an
   alpha of 1 blocks. Used by every method (the reference and refine exactly; each GL method as
   docs/methods/<method>.md says). A material is a constant alpha or an alpha texture sampled at
   the triangle's interpolated UV. */
typedef enum ss_alpha_wrap {
    SS_ALPHA_WRAP_REPEAT = 0, /* Blender's image extension REPEAT */
    SS_ALPHA_WRAP_EXTEND = 1, /* EXTEND: the border texels continue */
    SS_ALPHA_WRAP_CLIP = 2,   /* CLIP: alpha 0 outside [0, 1]^2 */
    SS_ALPHA_WRAP_RESERVED_MIN_ = -0x7fffffff - 1,
    SS_ALPHA_WRAP_RESERVED_MAX_ = 0x7fffffff
} ss_alpha_wrap;

typedef struct ss_alpha_material {
    float alpha;            /* 0 (transparent) .. 1 (opaque); used where `texture` is NULL */
    const float* texture;   /* NULL, or width * height alphas in [0, 1], row 0 at v = 0 (the
                               BOTTOM row, as Blender's image.pixels); texel centres at
                               ((i + 0.5) / width, (j + 0.5) / height) */
    int32_t width, height;
    ss_alpha_wrap wrap;
    int32_t closest;        /* 0: bilinear (Blender's Linear), 1: nearest texel (Closest) */
} ss_alpha_material;

/* Sets mesh `index`'s materials, copied: `corner_uvs` 6 floats (u, v per corner) per triangle,
   or NULL (every UV (0, 0)); `triangle_material` one index into `materials` per triangle, or NULL
   (material 0 everywhere); `material_count` >= 1 materials. material_count 0 clears them (the
   mesh is opaque again), as does a set whose materials all have alpha 1. Fails with
   SS_ERROR_INVALID_SCENE naming the mesh for a bad index, an alpha outside [0, 1] or a texture
   without texels, leaving the mesh as it was. A material change is a mesh edit (every cache of
   the mesh is redrawn); ss_scene_update_mesh clears the materials (set them again after it).
   Shadow rays through the mesh let 1 - alpha through; the camera sees through it where alpha
   is below 0.5 (a cut-out's holes: the pixel is what lies behind), and sees it elsewhere. */
SS_API ss_status ss_scene_set_mesh_materials(ss_scene* scene, int32_t index, const float* corner_uvs,
                                             const int32_t* triangle_material,
                                             const ss_alpha_material* materials, int32_t material_count);
/* Removal moves every later mesh (light) down one index. */
SS_API ss_status ss_scene_remove_mesh(ss_scene* scene, int32_t index);
SS_API ss_status ss_scene_update_light(ss_scene* scene, int32_t index, const ss_light_desc* light);
SS_API ss_status ss_scene_remove_light(ss_scene* scene, int32_t index);
/* Light and shadow linking (Blender 4.0+) of light `light`: the meshes that shadow it (its
   blocker collection) and the meshes it lights (its receiver collection), by mesh index. A count
   of -1 means every mesh, as an empty collection does (the pointer is ignored); 0..n exactly the
   listed meshes (NULL allowed for 0). A mesh outside the blockers casts no shadow of this light
   in any method (it still shadows the others); a mesh outside the receivers gets no light from
   it: its pixels are outside this light's mask, with V = 1 (the render there owes nothing to the
   light, so the pass leaves it as it is). SS_MESH_CAST and SS_MESH_RECEIVE apply on top.
   A change gives the light a new version (its shadow maps and prepared geometry are made again;
   setting the links it has changes nothing). A mesh added later is in neither list of a light
   that has lists; a removed mesh leaves them and later indices move down with it. Indices out
   of range fail with SS_ERROR_INVALID_ARGUMENT and leave the links as they were. */
SS_API ss_status ss_scene_set_light_links(ss_scene* scene, int32_t light, const int32_t* blocker_meshes,
                                          int32_t blocker_count, const int32_t* receiver_meshes,
                                          int32_t receiver_count);
/* The links as set: each count -1 for every mesh, else the sorted unique indices, written to the
   array when its capacity holds them (fails naming the room needed otherwise). */
SS_API ss_status ss_scene_get_light_links(const ss_scene* scene, int32_t light, int32_t* blocker_meshes,
                                          int32_t blocker_capacity, int32_t* blocker_count,
                                          int32_t* receiver_meshes, int32_t receiver_capacity,
                                          int32_t* receiver_count);
SS_API ss_status ss_scene_set_camera(ss_scene* scene, const ss_camera_desc* camera);
/* The scene camera (SS_ERROR_INVALID_SCENE when it has none); e.g. to change the resolution. */
SS_API ss_status ss_scene_get_camera(const ss_scene* scene, ss_camera_desc* out);
SS_API ss_status ss_scene_set_view_layer(ss_scene* scene, const char* name);
SS_API int32_t ss_scene_light_count(const ss_scene* scene);
SS_API const char* ss_scene_light_name(const ss_scene* scene, int32_t index);
/* A light as it was added (name points into the scene, valid while it lives). */
SS_API ss_status ss_scene_get_light(const ss_scene* scene, int32_t index, ss_light_desc* out);
/* The view layer name the EXR passes go under (default "ViewLayer"); valid while the scene lives. */
SS_API const char* ss_scene_view_layer(const ss_scene* scene);
SS_API int32_t ss_scene_mesh_count(const ss_scene* scene);
/* The mesh report (open/non-manifold edges, orientation, degenerate faces) as JSON. */
SS_API ss_status ss_scene_mesh_report(const ss_scene* scene, int32_t mesh, char* buffer,
                                      size_t buffer_size);

/* Render one light with one method. `method` may be "auto"; ss_result_method tells which ran. */
SS_API ss_status ss_render(ss_context* context, const ss_scene* scene, int32_t light_index,
                           const char* method, const ss_render_options* options, ss_result** out);
SS_API void ss_result_destroy(ss_result* result);
SS_API const char* ss_result_method(const ss_result* result);
SS_API const char* ss_result_light(const ss_result* result);
/* The result's expected RMSE of V against the reference (the `reference` method at its default
 * samples and the same seed), from a sparse exact check: the reference's ray tracer on one
 * pixel in 16 (4096 to 65536) spread over the image, over every checked pixel the light reaches
 * (V = 1 outside the method's own mask, as a composite uses it). Made for every "auto"
 * render (it is how auto chooses) and for a GL method whose settings hold "estimate_rmse=1";
 * NaN when none was made. Written to the EXR header attribute "softshadow/estimated_rmse"
 * ("<pass>=<rmse>;..."). */
SS_API double ss_result_estimated_rmse(const ss_result* result);
/* How many methods the render ran at full size: 1 for a named method; for "auto" the candidates
 * it rendered and scored (its prior and the sparse check's lower bounds leave the others out;
 * 1 where the check could not be made). 0 for a null result. */
SS_API int32_t ss_result_methods_rendered(const ss_result* result);
/* What the render left out, one line each ending in '\n' ("" when nothing): a mesh beyond the
 * scene range (docs/reliability.md) is skipped, named here, and the rest keeps its shadows.
 * NULL for a null result. */
SS_API const char* ss_result_warnings(const ss_result* result);
SS_API int32_t ss_result_layer_count(const ss_result* result);
/* Layer names: "V" (visibility), "mask", "umbra", "penumbra", and method debug layers. */
SS_API ss_status ss_result_layer(const ss_result* result, int32_t index, const char** name,
                                 const float** pixels, int32_t* width, int32_t* height);

/* Writes results as one multilayer EXR (atomically): channel
 * "<view_layer>.<light>_<method>[_<layer>].V" per layer, <method> as asked of ss_render (a light
 * rendered with "auto" keeps the pass name "<light>_auto" whatever ran); the header attribute
 * "softshadow/methods" lists "<pass>=<method that ran>;..." for the main passes, and
 * "softshadow/estimated_rmse" "<pass>=<rmse>;..." for those that carry an estimate. */
SS_API ss_status ss_write_exr(const char* path, const char* view_layer,
                              const ss_result* const* results, int32_t result_count);

/* The same EXR gathered result by result, in bounded memory: each added result's layers go to
 * an (unlinked) spool file beside `path`, so the caller can destroy the result at once, and
 * ss_exr_writer_finish writes the EXR (atomically) a band of rows at a time. Create checks the
 * output path and view layer; destroy without finish writes nothing and leaves no file. */
typedef struct ss_exr_writer ss_exr_writer;
SS_API ss_status ss_exr_writer_create(const char* path, const char* view_layer, ss_exr_writer** out);
SS_API ss_status ss_exr_writer_add(ss_exr_writer* writer, const ss_result* result);
SS_API ss_status ss_exr_writer_finish(ss_exr_writer* writer);
SS_API void ss_exr_writer_destroy(ss_exr_writer* writer);
/* Every layer added after this call also gets an 8-bit grayscale PNG preview in `folder` (which
 * must exist), named "<light>_<method that ran>[_<layer>].png" with '/', '\\', control
 * characters and a leading '.' made '_' (so no light name reaches outside the folder). Each
 * preview is written under a temporary name when its result is added and renamed into place by
 * ss_exr_writer_finish right after the EXR, so a failure before then leaves every old file as
 * it was. Adding a layer whose preview would have the name of an earlier one fails. */
SS_API ss_status ss_exr_writer_set_preview_folder(ss_exr_writer* writer, const char* folder);
/* Checks, before a long render, what an EXR at `path` could not hold: more than the passes one
 * EXR may have, or rows of `pass_count` passes `width` pixels wide past the row limit. Fails
 * with SS_ERROR_INVALID_ARGUMENT naming the path and the limit. */
SS_API ss_status ss_check_exr_shape(const char* path, int64_t pass_count, int32_t width);
/* Checks that an output could be written to `path`: it, or the file its symlinks lead to, is a
 * regular file or a new name, in an existing folder the process may write. Fails naming the
 * path (SS_ERROR_IO). */
SS_API ss_status ss_check_output_path(const char* path);
/* The pass name of one layer: "<light>_<method>[_<layer>]" (dots and spaces become '_'; the
 * layer "V" is the pass itself). Fails naming the size needed when the buffer is too small. */
SS_API ss_status ss_pass_name(const char* light, const char* method, const char* layer, char* buffer,
                              size_t buffer_size);
/* An 8-bit grayscale PNG of one layer (values in [0,1] -> 0..255, rows top first), written
 * atomically. */
SS_API ss_status ss_write_png_preview(const char* path, const float* pixels, int32_t width, int32_t height);
/* Compares the passes of one or two EXRs (path_b NULL: one file, each method against the
 * `against` method, default "reference"). mask: NULL or "" = the pixels both passes' own masks
 * hold, "none" = every pixel, else a pass name. Writes a JSON array of rows {"a", "b", "mask",
 * "pixels", "rmse", "mean", "p99", "max", "umbra_iou", "lit_iou"} into buffer; *length (may be
 * NULL) receives the bytes needed with the terminating zero, also when the buffer is too small. */
SS_API ss_status ss_compare_exr(const char* path_a, const char* path_b, const char* against, const char* mask,
                                char* buffer, size_t buffer_size, size_t* length);

/* The `sweep` method's shadow mesh for one light (CPU geometry, no GL context needed), so a host
 * can bring it in as geometry: triangles on the receiver plane, world-space vertices with a shadow
 * intensity each (0 lit .. 1 umbra; V = 1 - intensity, Gouraud-interpolated). Options as for
 * ss_render ("receiver=<mesh name>;fill=smooth|steps;border=0.25;weights=irradiance|equal;
 * clusters=1;memory_limit_mb=0"); extra_layers is ignored. With clusters > 1 (square/rectangle
 * lights cut into convex strips) the clusters' triangles overlap and their intensities ADD (already
 * weighted). A mesh over the memory limit (memory_limit_mb, default the machine's memory) is
 * refused (SS_ERROR_INVALID_ARGUMENT, both figures in the message) once its triangles are known,
 * before its irradiance weights are made. */
typedef struct ss_sweep_mesh ss_sweep_mesh;
SS_API ss_status ss_sweep_shadow_mesh(const ss_scene* scene, int32_t light_index,
                                      const ss_render_options* options, ss_sweep_mesh** out);
SS_API void ss_sweep_mesh_destroy(ss_sweep_mesh* mesh);
/* Arrays owned by the mesh: xyz (3 floats per vertex), intensity (1 per vertex), triangles
 * (3 uint32 per triangle, counter-clockwise seen from the light's side of the plane). */
SS_API ss_status ss_sweep_mesh_data(const ss_sweep_mesh* mesh, const float** xyz,
                                    const float** intensity, uint32_t* vertex_count,
                                    const uint32_t** triangles, uint32_t* triangle_count);
/* Index of the receiver mesh the shadow lies on, and the number of light samples used. */
SS_API ss_status ss_sweep_mesh_info(const ss_sweep_mesh* mesh, int32_t* receiver_mesh,
                                    int32_t* samples_used);

#ifdef __cplusplus
}
#endif
#endif /* SOFTSHADOW_H */
