/* src/core/datadir.c: where the library finds its tables when cu_desc.data_dir is NULL, and the version string. */
#include "cumulo.h"
#include "paths.h" /* CU_INSTALLED_DATA_DIR, written by ./configure from --datadir */
#include <stdlib.h>

const char *cu_default_data_dir(void)
{
    /* The environment wins so that an uninstalled build tree, a test or a relocated install can point elsewhere. */
    const char *env = getenv("CUMULO_DATA_DIR");
    return env && *env ? env : CU_INSTALLED_DATA_DIR;
}

const char *cu_version(void)
{
    return CU_LIB_VERSION;
}
