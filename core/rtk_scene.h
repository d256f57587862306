/* What the public rtk_scene handle (include/rtk.h) is: a built scene, and for a scene the
 * hosted API opened from a file, the hosted side's record of it. Library-internal. */
#ifndef RT_RTK_SCENE_H
#define RT_RTK_SCENE_H

#include "rtk.h"
#include "scene.h"

struct rtk_scene {
    const rt_scene *scene;
    void *host; /* NULL for scenes made from blobs */
};

#endif
