/* tests/platform/test_evdev_dev.c: the device half of evdev.c (open by path or name, capability probe, grab, reading,
 * unplug, permission errors) against fake /dev/input devices: open/ioctl/read/opendir are wrapped at link time
 * (ld --wrap), each fake device is a pipe carrying recorded struct input_event streams. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>
#include <cmocka.h>
#include "evdev.h"
#include "fake_dir.h"

#define NDEV 5
static struct fakedev {
    const char *name;
    int rel_dial, rel_x, rel_y, btn_left, denied;
    int rd, wr, unplugged, grabbed, clock_set;
} devs[NDEV] = {
    { "AT Translated Set 2 keyboard", 0, 0, 0, 0, 0, -1, -1, 0, 0, 0 },
    { "Griffin PowerMate", 1, 0, 0, 0, 0, -1, -1, 0, 0, 0 },
    { "rotary@11", 0, 1, 0, 0, 0, -1, -1, 0, 0, 0 },
    { "Logitech USB Optical Mouse", 0, 1, 1, 1, 0, -1, -1, 0, 0, 0 },
    { "Locked Knob", 1, 0, 0, 0, 1, -1, -1, 0, 0, 0 },
};

static int dev_of_fd(int fd)
{
    for (int i = 0; i < NDEV; i++)
        if (devs[i].rd >= 0 && devs[i].rd == fd)
            return i;
    return -1;
}

int __real_open(const char *path, int flags, ...);
int __wrap_open(const char *path, int flags, ...)
{
    int n;
    char tail;
    if (sscanf(path, "/dev/input/event%d%c", &n, &tail) == 1) {
        if (n < 0 || n >= NDEV) {
            errno = ENOENT;
            return -1;
        }
        if (devs[n].denied) {
            errno = EACCES;
            return -1;
        }
        int p[2];
        if (pipe(p))
            return -1;
        for (int i = 0; i < NDEV; i++)
            if (devs[i].rd == p[0]) /* that device's fd was closed and the number reused */
                devs[i].rd = -1;
        devs[n].rd = p[0];
        devs[n].wr = p[1];
        if (flags & O_NONBLOCK) /* evdev.c opens non-blocking: a read with nothing queued must not wait */
            fcntl(p[0], F_SETFL, O_NONBLOCK);
        return p[0];
    }
    return __real_open(path, flags, 0);
}

static void set_bit(void *buf, size_t len, unsigned bit)
{
    if (bit / 8 < len)
        ((unsigned char *)buf)[bit / 8] |= (unsigned char)(1u << (bit % 8));
}

int __real_ioctl(int fd, unsigned long req, ...);
int __wrap_ioctl(int fd, unsigned long req, ...)
{
    va_list ap;
    va_start(ap, req);
    void *arg = va_arg(ap, void *);
    va_end(ap);
    int d = dev_of_fd(fd);
    if (d < 0)
        return __real_ioctl(fd, req, arg);
    size_t len = _IOC_SIZE(req);
    if (req == EVIOCGVERSION) {
        *(int *)arg = EV_VERSION;
        return 0;
    }
    if (_IOC_TYPE(req) == 'E' && _IOC_NR(req) == _IOC_NR(EVIOCGNAME(0))) {
        snprintf(arg, len, "%s", devs[d].name);
        return (int)strlen(devs[d].name) + 1;
    }
    if (_IOC_TYPE(req) == 'E' && _IOC_NR(req) == 0x20 + EV_KEY) {
        memset(arg, 0, len);
        if (devs[d].btn_left)
            set_bit(arg, len, BTN_LEFT);
        set_bit(arg, len, d == 0 ? KEY_LEFT : BTN_0);
        return (int)len;
    }
    if (_IOC_TYPE(req) == 'E' && _IOC_NR(req) == 0x20 + EV_REL) {
        memset(arg, 0, len);
        if (devs[d].rel_dial) set_bit(arg, len, REL_DIAL);
        if (devs[d].rel_x) set_bit(arg, len, REL_X);
        if (devs[d].rel_y) set_bit(arg, len, REL_Y);
        return (int)len;
    }
    if (req == EVIOCSCLOCKID) {
        devs[d].clock_set = 1;
        return 0;
    }
    if (req == EVIOCGRAB) {
        devs[d].grabbed = arg != NULL;
        return 0;
    }
    errno = ENOTTY;
    return -1;
}

ssize_t __real_read(int fd, void *buf, size_t n);
ssize_t __wrap_read(int fd, void *buf, size_t n)
{
    int d = dev_of_fd(fd);
    if (d >= 0 && devs[d].unplugged) {
        errno = ENODEV;
        return -1;
    }
    return __real_read(fd, buf, n);
}

/* /dev/input listing: event0..event4 plus entries that are not event devices. */
static const char *const input_names[] = {".", "..", "by-id", "mice", "event0", "event1", "event2", "event3",
                                          "event4"};
static const fake_dir dev_input = {"/dev/input", input_names, 9, NULL};

static void send(int d, uint16_t type, uint16_t code, int32_t value)
{
    struct input_event ev;
    memset(&ev, 0, sizeof ev);
    ev.input_event_sec = 7;
    ev.type = type;
    ev.code = code;
    ev.value = value;
    assert_int_equal(write(devs[d].wr, &ev, sizeof ev), (ssize_t)sizeof ev);
}

static int setup(void **state)
{
    (void)state;
    for (int i = 0; i < NDEV; i++) {
        devs[i].rd = devs[i].wr = -1;
        devs[i].unplugged = devs[i].grabbed = devs[i].clock_set = 0;
    }
    return 0;
}

static cu_evdev *open_spec(const char *s, int grab, char *err, size_t errlen)
{
    cu_input_spec sp;
    cu_evdev *e = NULL;
    assert_int_equal(cu_input_parse(s, &sp, err, errlen), 0);
    if (cu_evdev_open(&e, &sp, grab, err, errlen))
        return NULL;
    return e;
}

static void test_open_by_path_read_and_unplug(void **state)
{
    (void)state;
    char err[512];
    cu_evdev *e = open_spec("evdev:/dev/input/event1", 1, err, sizeof err);
    assert_non_null(e);
    assert_string_equal(cu_evdev_name(e), "Griffin PowerMate");
    assert_int_equal(devs[1].grabbed, 1);
    assert_int_equal(devs[1].clock_set, 1);
    send(1, EV_REL, REL_DIAL, 2);
    send(1, EV_SYN, SYN_REPORT, 0);
    send(1, EV_KEY, BTN_0, 1);
    send(1, EV_SYN, SYN_REPORT, 0);
    cu_action a[8];
    int n;
    assert_int_equal(cu_evdev_read(e, a, 8, &n, err, sizeof err), 0);
    assert_int_equal(n, 2);
    assert_int_equal(a[0].kind, CU_ACT_TURN);
    assert_int_equal(a[0].detents, 2);
    assert_int_equal(a[1].kind, CU_ACT_TOGGLE);
    assert_int_equal(cu_evdev_read(e, a, 8, &n, err, sizeof err), 0); /* nothing pending: no wait */
    assert_int_equal(n, 0);
    devs[1].unplugged = 1;
    assert_int_equal(cu_evdev_read(e, a, 8, &n, err, sizeof err), 1);
    assert_non_null(strstr(err, "/dev/input/event1 ('Griffin PowerMate') was unplugged"));
    cu_evdev_close(e);
    close(devs[1].wr);
}

static void test_open_by_name(void **state)
{
    (void)state;
    char err[512];
    cu_evdev *e = open_spec("evdev:name=rotary@11", 0, err, sizeof err);
    assert_non_null(e);
    assert_int_equal(devs[2].grabbed, 0);
    /* The rotary-encoder overlay's REL_X counts as a knob; it is not a mouse. */
    send(2, EV_REL, REL_X, -1);
    send(2, EV_SYN, SYN_REPORT, 0);
    cu_action a[4];
    int n;
    assert_int_equal(cu_evdev_read(e, a, 4, &n, err, sizeof err), 0);
    assert_int_equal(n, 1);
    assert_int_equal(a[0].detents, -1);
    cu_evdev_close(e);
    close(devs[2].wr);

    /* A part of the name finds the device; the mouse's REL_X is not a knob. */
    e = open_spec("evdev:name=Optical Mouse", 0, err, sizeof err);
    assert_non_null(e);
    assert_string_equal(cu_evdev_name(e), "Logitech USB Optical Mouse");
    send(3, EV_REL, REL_X, 5);
    send(3, EV_SYN, SYN_REPORT, 0);
    assert_int_equal(cu_evdev_read(e, a, 4, &n, err, sizeof err), 0);
    assert_int_equal(n, 0);
    cu_evdev_close(e);
    for (int i = 0; i < NDEV; i++)
        if (devs[i].wr >= 0)
            close(devs[i].wr);
}

static void test_open_errors(void **state)
{
    (void)state;
    char err[512];
    assert_null(open_spec("evdev:/dev/input/event4", 0, err, sizeof err));
    assert_non_null(strstr(err, "evdev: /dev/input/event4: permission denied: add the user to group 'input'"));
    assert_null(open_spec("evdev:/dev/input/event9", 0, err, sizeof err));
    assert_non_null(strstr(err, "no such device: is it plugged in?"));
    assert_null(open_spec("evdev:name=Contour ShuttleXpress", 0, err, sizeof err));
    assert_non_null(strstr(err, "no device named 'Contour ShuttleXpress'"));
    assert_non_null(strstr(err, "some devices were not readable")); /* event4 was denied while searching */
    for (int i = 0; i < NDEV; i++)
        if (devs[i].wr >= 0)
            close(devs[i].wr);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_open_by_path_read_and_unplug, setup),
        cmocka_unit_test_setup(test_open_by_name, setup),
        cmocka_unit_test_setup(test_open_errors, setup),
    };
    fake_dir_use(&dev_input);
    return cmocka_run_group_tests(tests, NULL, NULL);
}
