/* platform/display/display.c: the table of display back ends compiled into this binary, and lookup by name. */
#include "display.h"
#include "config.h"
#include <string.h>

extern const cu_display_backend cu_display_egl;
#if CU_HAVE_OSMESA
extern const cu_display_backend cu_display_osmesa;
#endif
#if CU_HAVE_DRM
extern const cu_display_backend cu_display_drm;
#endif
#if CU_HAVE_X11
extern const cu_display_backend cu_display_x11;
#endif
#if CU_HAVE_WAYLAND
extern const cu_display_backend cu_display_wayland;
#endif

const cu_display_backend *const cu_display_backends[] = {
    &cu_display_egl,
#if CU_HAVE_OSMESA
    &cu_display_osmesa,
#endif
#if CU_HAVE_DRM
    &cu_display_drm,
#endif
#if CU_HAVE_X11
    &cu_display_x11,
#endif
#if CU_HAVE_WAYLAND
    &cu_display_wayland,
#endif
    NULL,
};

const cu_display_backend *cu_display_find(const char *name)
{
    /* "headless" is the user-facing name of the default headless back end. */
    if (!name || strcmp(name, "headless") == 0)
        name = "egl";
    for (int i = 0; cu_display_backends[i]; i++)
        if (strcmp(cu_display_backends[i]->name, name) == 0)
            return cu_display_backends[i];
    return NULL;
}
