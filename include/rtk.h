/* rtk.h — rtk 0.5.0: a ray tracing kernel whose renders are bitwise reproducible.

   rtk renders scenes of the CSE457 ray-tracer format (YAML scene graphs with cameras,
   lights, spheres, cylinders, boxes, planes and PLY meshes) and gives the same image
   bytes on every machine: any thread count, tile order, compiler, optimisation level
   and CPU. This header is the whole public API and this comment is its manual. Link
   with `pkg-config --cflags --libs rtk` (static: add --static).

   ---- 1. Rendering a scene file (the hosted API: files, malloc, threads) -------------

       #include <rtk.h>
       #include <stdio.h>
       #include <stdlib.h>

       int main(void)
       {
           char err[RTK_ERROR_SIZE];
           rtk_options opt = rtk_default_options();  // the file's own settings
           opt.width = 256;                            // optional overrides (0 keeps the file's)
           opt.height = 256;
           rtk_scene *scene;
           if (rtk_open("scene.yaml", &opt, &scene, err, sizeof err) != RTK_OK) {
               fprintf(stderr, "%s\n", err);            // one line: file:line:col: what was wrong
               return 1;
           }
           uint32_t w, h;
           rtk_scene_size(scene, &w, &h);
           uint8_t *rgb = malloc((size_t)w * h * 3);    // RGB bytes, row 0 at the top
           rtk_render(scene, 0, rgb);                   // 0 threads: one per core
           char hash[RTK_HASH_SIZE];
           rtk_render_hash(rgb, w, h, hash);            // what `rtk render --hash` prints
           puts(hash);
           if (rtk_write_image("out.png", rgb, w, h, err, sizeof err) != RTK_OK) fprintf(stderr, "%s\n", err);
           free(rgb);
           rtk_close(scene);
           return 0;
       }

   Assets (meshes, textures) are found as the `rtk` command finds them: from the folder
   that holds `assets/` above the scene file, or opt.assets. rtk_render_region renders
   any rectangle instead of the whole frame, on the caller's own threads.

   ---- 2. The kernel alone (the freestanding API: no libc, no malloc, no files) -------

   The kernel (rtk_scene_from_blob, rtk_scene_size, rtk_render_region, rtk_render_hash,
   rtk_version, rtk_build, rtk_status_name) needs nothing from the C library but memcpy,
   memset and memmove, and never allocates: it works in memory the caller hands it. Its
   input is a scene blob, made from a scene file by `rtk pack SCENE.yaml -o S.rtscene`
   or by rtk_pack, holding the scene with its meshes and textures:

       extern const uint8_t blob[];          // e.g. linked in with objcopy
       extern const size_t blob_size;
       static uint8_t memory[16 << 20];     // the arena: the scene lives here
       static uint8_t rgb[64 * 64 * 3];

       const rtk_scene *scene;
       size_t needed;
       rtk_status st = rtk_scene_from_blob(blob, blob_size, memory, sizeof memory, &scene, &needed);
       if (st == RTK_ERR_NOMEM) { ... retry with at least `needed` bytes ... }
       uint32_t w, h;
       rtk_scene_size(scene, &w, &h);       // must fit rgb
       rtk_render_region(scene, 0, 0, w, h, rgb);

   A blob holds the scalar type of the build that wrote it (rtk_build(): "double" or
   "fixed"); the other build refuses it (RTK_ERR_INVALID).

   ---- 3. The rules -------------------------------------------------------------------

   Errors are values. Every fallible function returns an rtk_status; the hosted ones also
   write one line (no newline) into err, naming the file, the place in it and what was
   wrong, as the `rtk` command prints it. Nothing is half done: on failure the outputs
   are unset and nothing needs freeing.

   Memory. The kernel allocates nothing: a scene from rtk_scene_from_blob lives in the
   caller's memory until the caller reuses it; it needs no close. When the memory is too
   small the call returns RTK_ERR_NOMEM and sets *needed to a size to retry with (retry
   until RTK_OK: the size needed is only known once the build gets that far). The hosted
   rtk_open allocates, up to opt.max_memory (default 4 GiB), and rtk_close frees.

   Threads. A scene is read-only once made. Any number of threads may call
   rtk_render_region on one scene at once, on disjoint rectangles of one buffer or on
   different buffers; each pixel depends only on the scene, so the image is the same
   bytes whatever the split. rtk_render does that split over its own threads.

   Determinism. Same scene file, same settings, same build => same bytes, on every
   machine. The render hash (rtk_render_hash) is the SHA-256 of the image as a binary
   PPM file (P6), so `sha256sum out.ppm` checks it without rtk.

   Debugging a pixel. rtk_debug_pixel_json gives every ray behind one pixel — camera,
   reflection, refraction and shadow rays, each hit's point, normal, material and light
   terms, and the colour each returns — as the JSON `rtk debug --json` prints.

   Names. Everything public starts with rtk_ (RTK_ for macros); rt_ and rtp_ names
   inside the library are internal and may change in any release. */
#ifndef RTK_H
#define RTK_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RTK_VERSION_MAJOR 0
#define RTK_VERSION_MINOR 5
#define RTK_VERSION_PATCH 0
#define RTK_VERSION_STRING "0.5.0"

/* Sizes of the buffers the API fills: an error line, a hash in hex with its NUL. */
#define RTK_ERROR_SIZE 1024
#define RTK_HASH_SIZE 65

typedef enum {
    RTK_OK = 0,
    RTK_ERR_NOMEM = 1,       /* the memory given (or opt.max_memory) is too small */
    RTK_ERR_INVALID = 2,     /* a value or blob the kernel does not accept */
    RTK_ERR_RANGE = 3,       /* a value the fixed build cannot represent */
    RTK_ERR_INPUT = 4,       /* hosted: a scene, mesh or texture missing, unreadable or invalid */
    RTK_ERR_OUTPUT = 5,      /* hosted: a file that cannot be written */
    RTK_ERR_INTERRUPTED = 6, /* hosted: rtk_render was cancelled */
} rtk_status;

/* A scene ready to render. Opaque; made by rtk_open or rtk_scene_from_blob. */
typedef struct rtk_scene rtk_scene;

/* ---- The kernel (freestanding) ---- */

/* "0.5.0", RTK_VERSION_STRING of the library actually linked. */
const char *rtk_version(void);
/* "double" or "fixed": the scalar type the kernel was built with. */
const char *rtk_build(void);
/* "ok", "out of memory", ...: a short English name of a status. */
const char *rtk_status_name(rtk_status status);

/* Reads a scene blob and builds the scene in memory[0 .. capacity). On RTK_ERR_NOMEM,
 * *needed (if not NULL) is a size worth retrying with. */
rtk_status rtk_scene_from_blob(const void *blob, size_t blob_size, void *memory, size_t capacity, const rtk_scene **out,
                               size_t *needed);
/* The image size the scene renders at. */
void rtk_scene_size(const rtk_scene *scene, uint32_t *width, uint32_t *height);
/* Renders columns [x0, x1) of rows [y0, y1) into rgb, the whole frame's buffer
 * (width * height * 3 bytes, row 0 at the top); other pixels are left as they are. */
void rtk_render_region(const rtk_scene *scene, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint8_t *rgb);
/* The render hash of an image: SHA-256 of its binary PPM bytes, in lowercase hex. */
void rtk_render_hash(const uint8_t *rgb, uint32_t width, uint32_t height, char hash[RTK_HASH_SIZE]);

/* ---- The hosted API (libc, malloc, POSIX threads, files) ---- */

typedef struct {
    const char *assets; /* the folder that contains assets/; NULL: found from the scene's path */
    size_t max_memory;  /* cap on the scene's memory in bytes */
    uint32_t width;     /* 0, or the image width to render at (overrides the file) */
    uint32_t height;    /* 0, or the image height */
    int32_t depth;      /* -1, or Maximum Recursion Depth 0..64 */
    int32_t aa;         /* -1, or Samples Per Pixel as an index: 4^aa samples, 0..7 */
    uint32_t threads;   /* threads for building the BVH; 0: one per core */
} rtk_options;

/* The file's settings kept, a 4 GiB memory cap, all cores. */
rtk_options rtk_default_options(void);
/* Loads a scene file with its meshes and textures and builds it. */
rtk_status rtk_open(const char *path, const rtk_options *options, rtk_scene **out, char *err, size_t err_size);
/* Frees a scene from rtk_open (NULL is fine). */
void rtk_close(rtk_scene *scene);
/* Renders the whole frame into rgb (width * height * 3 bytes) on `threads` threads (0: one
 * per core). The bytes do not depend on the thread count. */
rtk_status rtk_render(const rtk_scene *scene, uint32_t threads, uint8_t *rgb);
/* The scene of rtk_open as a blob for rtk_scene_from_blob (malloc'd; release with free). */
rtk_status rtk_pack(const rtk_scene *scene, void **blob, size_t *blob_size);
/* Writes an image as PNG when path ends in .png, else binary PPM, atomically: on failure
 * nothing is left at path. */
rtk_status rtk_write_image(const char *path, const uint8_t *rgb, uint32_t width, uint32_t height, char *err,
                           size_t err_size);
/* Every ray behind pixel (x, y) (column, row from the top left) of a scene from rtk_open,
 * for one sample (0 .. samples per pixel - 1) or RTK_ALL_SAMPLES, as the JSON document
 * `rtk debug --json --pixel X,Y [--sample K]` prints: malloc'd, NUL-terminated, release
 * with free. NULL with one line in err when the pixel or sample does not exist, the scene
 * came from a blob (it has no names to show), or memory runs out. */
#define RTK_ALL_SAMPLES UINT32_MAX
char *rtk_debug_pixel_json(const rtk_scene *scene, uint32_t x, uint32_t y, uint32_t sample, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif
