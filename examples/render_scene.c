/* Renders a scene file to an image through rtk's hosted API and prints its render hash:
 *   render_scene SCENE.yaml OUT.png [WIDTH HEIGHT]
 * The hash is the one `rtk render SCENE.yaml --hash` prints for the same size. */
#include <rtk.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 3 && argc != 5) {
        fprintf(stderr, "usage: %s SCENE.yaml OUT.png [WIDTH HEIGHT]\n", argv[0]);
        return 2;
    }
    char err[RTK_ERROR_SIZE];
    rtk_options opt = rtk_default_options();
    if (argc == 5) {
        opt.width = (uint32_t)strtoul(argv[3], NULL, 10);
        opt.height = (uint32_t)strtoul(argv[4], NULL, 10);
    }
    rtk_scene *scene;
    if (rtk_open(argv[1], &opt, &scene, err, sizeof err) != RTK_OK) {
        fprintf(stderr, "%s\n", err);
        return 3;
    }
    uint32_t w, h;
    rtk_scene_size(scene, &w, &h);
    uint8_t *rgb = malloc((size_t)w * h * 3);
    int status = 0;
    if (!rgb || rtk_render(scene, 0, rgb) != RTK_OK) {
        fprintf(stderr, "%s: out of memory\n", argv[1]);
        status = 5;
    } else if (rtk_write_image(argv[2], rgb, w, h, err, sizeof err) != RTK_OK) {
        fprintf(stderr, "%s\n", err);
        status = 4;
    } else {
        char hash[RTK_HASH_SIZE];
        rtk_render_hash(rgb, w, h, hash);
        printf("%s\n", hash);
    }
    free(rgb);
    rtk_close(scene);
    return status;
}
