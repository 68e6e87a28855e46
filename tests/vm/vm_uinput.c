/* tests/vm/vm_uinput.c: virtual USB input devices through /dev/uinput for the evdev test, driven by commands on
 * stdin, one a line:
 *   knob NAME        create a rotary knob (EV_REL REL_DIAL, like a USB volume knob) called NAME
 *   keys NAME        create a keyboard (arrows, +/-, Enter) called NAME
 *   dial N           turn the knob N detents (negative: the other way)
 *   key CODE         press and release a key (LEFT RIGHT UP DOWN PLUS MINUS ENTER or a number)
 *   unplug knob|keys destroy that device (as pulling the USB plug does)
 *   sleep MS
 * After each create it prints "created NAME /dev/input/eventN" once the node exists; after each other command "ok". */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <linux/uinput.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static int knob = -1, keys = -1;

static void die(const char *what)
{
    fprintf(stderr, "vm_uinput: %s: %s\n", what, strerror(errno));
    exit(1);
}

static void emit(int fd, int type, int code, int value)
{
    struct input_event ev;
    memset(&ev, 0, sizeof ev);
    ev.type = (unsigned short)type;
    ev.code = (unsigned short)code;
    ev.value = value;
    if (write(fd, &ev, sizeof ev) != (ssize_t)sizeof ev)
        die("write");
}

static void msleep(long ms)
{
    struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };
    nanosleep(&ts, NULL);
}

static int create(const char *name, int is_knob)
{
    int fd = open("/dev/uinput", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        die("/dev/uinput");
    if (is_knob) {
        ioctl(fd, UI_SET_EVBIT, EV_REL);
        ioctl(fd, UI_SET_RELBIT, REL_DIAL);
        ioctl(fd, UI_SET_EVBIT, EV_KEY);
        ioctl(fd, UI_SET_KEYBIT, BTN_0); /* the knob's push button */
    } else {
        static const int k[] = { KEY_LEFT, KEY_RIGHT, KEY_UP, KEY_DOWN, KEY_KPPLUS, KEY_KPMINUS, KEY_EQUAL,
                                 KEY_MINUS, KEY_ENTER, KEY_A, KEY_SPACE };
        ioctl(fd, UI_SET_EVBIT, EV_KEY);
        for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
            ioctl(fd, UI_SET_KEYBIT, k[i]);
    }
    struct uinput_setup us;
    memset(&us, 0, sizeof us);
    us.id.bustype = BUS_USB;
    us.id.vendor = 0x1209;
    us.id.product = is_knob ? 0x0001 : 0x0002;
    snprintf(us.name, sizeof us.name, "%s", name);
    if (ioctl(fd, UI_DEV_SETUP, &us) || ioctl(fd, UI_DEV_CREATE))
        die("create");
    char sys[64], path[300] = "";
    if (ioctl(fd, UI_GET_SYSNAME(sizeof sys), sys) < 0)
        die("UI_GET_SYSNAME");
    char dir[200];
    snprintf(dir, sizeof dir, "/sys/devices/virtual/input/%s", sys);
    for (int tries = 0; tries < 200 && !path[0]; tries++) {
        DIR *d = opendir(dir);
        struct dirent *de;
        while (d && (de = readdir(d)))
            if (!strncmp(de->d_name, "event", 5)) {
                struct stat st;
                snprintf(path, sizeof path, "/dev/input/%s", de->d_name);
                if (stat(path, &st))
                    path[0] = 0;
            }
        if (d)
            closedir(d);
        if (!path[0])
            msleep(10);
    }
    printf("created %s %s\n", name, path[0] ? path : "(no event node)");
    fflush(stdout);
    return fd;
}

static int keycode(const char *s)
{
    static const struct { const char *n; int c; } t[] = {
        { "LEFT", KEY_LEFT }, { "RIGHT", KEY_RIGHT }, { "UP", KEY_UP }, { "DOWN", KEY_DOWN },
        { "PLUS", KEY_KPPLUS }, { "MINUS", KEY_KPMINUS }, { "ENTER", KEY_ENTER }, { "A", KEY_A },
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
        if (!strcmp(s, t[i].n))
            return t[i].c;
    return atoi(s);
}

int main(void)
{
    char line[256];
    while (fgets(line, sizeof line, stdin)) {
        line[strcspn(line, "\r\n")] = 0;
        char *arg = strchr(line, ' ');
        if (arg)
            *arg++ = 0;
        else
            arg = line + strlen(line);
        if (!strcmp(line, "knob"))
            knob = create(arg, 1);
        else if (!strcmp(line, "keys"))
            keys = create(arg, 0);
        else if (!strcmp(line, "dial") && knob >= 0) {
            emit(knob, EV_REL, REL_DIAL, atoi(arg));
            emit(knob, EV_SYN, SYN_REPORT, 0);
        } else if (!strcmp(line, "key") && keys >= 0) {
            emit(keys, EV_KEY, keycode(arg), 1);
            emit(keys, EV_SYN, SYN_REPORT, 0);
            emit(keys, EV_KEY, keycode(arg), 0);
            emit(keys, EV_SYN, SYN_REPORT, 0);
        } else if (!strcmp(line, "unplug")) {
            int *fd = !strcmp(arg, "knob") ? &knob : &keys;
            if (*fd >= 0) {
                ioctl(*fd, UI_DEV_DESTROY);
                close(*fd);
                *fd = -1;
            }
        } else if (!strcmp(line, "sleep")) {
            msleep(atol(arg));
        } else if (line[0]) {
            fprintf(stderr, "vm_uinput: bad command '%s'\n", line);
            return 2;
        }
        if (strcmp(line, "knob") && strcmp(line, "keys")) {
            printf("ok %s\n", line);
            fflush(stdout);
        }
    }
    return 0;
}
