/* tests/platform/fake_dir.c: the wrapped opendir/readdir/closedir behind fake_dir.h. */
#include "fake_dir.h"
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>

static const fake_dir *current;
static int token, pos;
static struct dirent entry;

void fake_dir_use(const fake_dir *d)
{
    current = d;
}

DIR *__real_opendir(const char *path);
DIR *__wrap_opendir(const char *path)
{
    if (!current || strcmp(path, current->path) != 0)
        return __real_opendir(path);
    if (current->missing && current->missing()) {
        errno = ENOENT;
        return NULL;
    }
    pos = 0;
    return (DIR *)&token;
}

struct dirent *__real_readdir(DIR *d);
struct dirent *__wrap_readdir(DIR *d)
{
    if (d != (DIR *)&token)
        return __real_readdir(d);
    if (pos >= current->count)
        return NULL;
    snprintf(entry.d_name, sizeof entry.d_name, "%s", current->names[pos++]);
    return &entry;
}

int __real_closedir(DIR *d);
int __wrap_closedir(DIR *d)
{
    return d == (DIR *)&token ? 0 : __real_closedir(d);
}
