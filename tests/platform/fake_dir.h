/* tests/platform/fake_dir.h: one faked directory listing for the platform tests (/dev/dri/by-path, /dev/input):
 * opendir/readdir/closedir are wrapped at link time (-Wl,--wrap=opendir,--wrap=readdir,--wrap=closedir). */
#ifndef CU_TEST_FAKE_DIR_H
#define CU_TEST_FAKE_DIR_H

typedef struct fake_dir {
    const char *path;          /* the directory faked; every other path goes to libc */
    const char *const *names;  /* its entries, in readdir order */
    int count;
    int (*missing)(void);      /* NULL, or returns 1 when opendir should fail with ENOENT right now */
} fake_dir;

/* The listing the wrapped functions serve from now on (NULL: none). */
void fake_dir_use(const fake_dir *d);
#endif
