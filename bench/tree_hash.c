/* tree-hash: the SHA-256 of each scene's built BVH (platform/debug/bvh_hash.h), one
 * line "HASH  SCENE" per scene, built on --threads threads (default 1); --assets as for
 * rtk render. A change to the build that must not change the tree is checked by
 * comparing these lines before and after it, in both builds; tests/tree_hash.sh and
 * tests/golden/tree-*.sha256 pin them for `make check`. */
#include "debug/bvh_hash.h"
#include "load/scene_open.h"
#include <stdio.h>
#include <string.h>

int main(int argc, char **argv)
{
    rtp_scene_options opt = rtp_scene_default_options();
    opt.threads = 1;
    int i = 1;
    for (; i + 1 < argc && argv[i][0] == '-'; i += 2) {
        if (!strcmp(argv[i], "--assets"))
            opt.assets_root = argv[i + 1];
        else if (strcmp(argv[i], "--threads") || sscanf(argv[i + 1], "%u", &opt.threads) != 1 || !opt.threads)
            i = argc;
    }
    if (i >= argc) {
        fputs("usage: tree-hash [--threads N] [--assets DIR] SCENE...\n", stderr);
        return 2;
    }
    int rc = 0;
    for (; i < argc; i++) {
        char err[RTP_ERR_SIZE], hex[65];
        rtp_scene built;
        int r = rtp_scene_open(argv[i], &opt, &built, err, sizeof err);
        if (r != 0) {
            fprintf(stderr, "tree-hash: %s\n", err);
            rc = r;
            continue;
        }
        rtp_bvh_hash(&built.scene.bvh, built.scene.prim_count, hex);
        printf("%s  %s\n", hex, argv[i]);
        rtp_scene_close(&built);
    }
    return rc;
}
