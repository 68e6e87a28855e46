/* tests/platform/test_input_set.c: the inputs of one run through the back-end table (input_set.c): --input values in
 * and out of the set, stdin read through poll with each action's source, the end of a script, and a device that does
 * not open (logged, left closed, the run told that no requested input opened). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "input_set.h"

static char logged[4][512];
static int nlogged;

static void log_line(void *user, const char *msg)
{
    (void)user;
    if (nlogged < 4)
        snprintf(logged[nlogged], sizeof logged[0], "%s", msg);
    nlogged++;
}

static void test_table(void **state)
{
    (void)state;
    assert_non_null(cu_input_find(CU_INPUT_STDIN));
    assert_string_equal(cu_input_find(CU_INPUT_STDIN)->name, "stdin");
    assert_string_equal(cu_input_find(CU_INPUT_EVDEV)->name, "evdev");
    for (int i = 0; cu_input_backends[i]; i++)
        assert_ptr_equal(cu_input_find(cu_input_backends[i]->kind), cu_input_backends[i]);
    assert_non_null(strstr(cu_input_missing(CU_INPUT_GPIO), "built without libgpiod"));
}

static void test_add(void **state)
{
    (void)state;
    cu_input_set s = {0};
    char err[512];
    assert_int_equal(cu_input_set_add(&s, "stdin", err, sizeof err), 0);
    cu_input_set_add_stdin(&s); /* already there: not added twice */
    assert_int_equal(s.n, 1);
    assert_int_equal(s.nrequired, 1);
    assert_int_not_equal(cu_input_set_add(&s, "joystick:0", err, sizeof err), 0);
    assert_non_null(strstr(err, "unknown input kind"));
    for (int i = 1; i < CU_INPUT_SET_MAX; i++)
        assert_int_equal(cu_input_set_add(&s, "evdev:/dev/input/event0", err, sizeof err), 0);
    assert_int_not_equal(cu_input_set_add(&s, "stdin", err, sizeof err), 0);
    assert_string_equal(err, "at most 8 --input options");
    cu_input_set empty = {0};
    cu_input_set_add_stdin(&empty);
    assert_int_equal(empty.n, 1);
    assert_int_equal(empty.nrequired, 0); /* stdin by default is not asked for */
}

/* stdin by default over a pipe on fd 0, as a script feeds `cumulo run`. */
static void test_stdin_script(void **state)
{
    (void)state;
    int p[2], saved = dup(0), open_, ended;
    assert_int_equal(pipe(p), 0);
    assert_int_equal(dup2(p[0], 0), 0);
    close(p[0]);
    cu_input_set s = {0};
    cu_input_opts opts = { .log = log_line };
    nlogged = 0;
    cu_input_set_add_stdin(&s);
    assert_int_equal(cu_input_set_open(&s, &opts), 0); /* opened, but not a required one */
    assert_int_equal(nlogged, 0);
    char desc[256];
    cu_input_set_describe(&s, desc, sizeof desc);
    assert_string_equal(desc, "stdin");
    cu_action acts[8];
    const char *src[8];
    assert_int_equal(cu_input_set_poll(&s, 0, acts, src, 8), 0); /* nothing yet: returns at once */
    const char *cmds = "sun 1 2\nstatus\nnope\n";
    assert_int_equal(write(p[1], cmds, strlen(cmds)), (int)strlen(cmds));
    assert_int_equal(cu_input_set_poll(&s, 1000, acts, src, 8), 2);
    assert_int_equal(acts[0].kind, CU_ACT_SET_SUN);
    assert_int_equal(acts[1].kind, CU_ACT_STATUS);
    assert_string_equal(src[0], "stdin");
    assert_int_equal(nlogged, 1);
    assert_non_null(strstr(logged[0], "stdin: unknown command 'nope'"));
    close(p[1]);
    assert_int_equal(cu_input_set_poll(&s, 1000, acts, src, 8), 0);
    assert_int_equal(cu_input_set_left(&s, &open_, &ended), 0);
    assert_int_equal(open_, 0); /* closed at the end of the script... */
    assert_int_equal(ended, 1); /* ...which is an ending, not a failure */
    cu_input_set_describe(&s, desc, sizeof desc);
    assert_string_equal(desc, "");
    cu_input_set_close(&s);
    dup2(saved, 0);
    close(saved);
}

static void test_device_missing(void **state)
{
    (void)state;
    cu_input_set s = {0};
    cu_input_opts opts = { .log = log_line };
    char err[512];
    int open_, ended;
    nlogged = 0;
    assert_int_equal(cu_input_set_add(&s, "evdev:/dev/input/event99", err, sizeof err), 0);
    assert_int_equal(cu_input_set_open(&s, &opts), 0);
    assert_int_equal(nlogged, 1);
    assert_non_null(strstr(logged[0], "evdev: /dev/input/event99: no such device"));
    const char *tail = "; continuing without it";
    assert_string_equal(logged[0] + strlen(logged[0]) - strlen(tail), tail);
    assert_int_equal(cu_input_set_left(&s, &open_, &ended), 0);
    assert_int_equal(open_, 0);
    cu_input_set_close(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table),
        cmocka_unit_test(test_add),
        cmocka_unit_test(test_stdin_script),
        cmocka_unit_test(test_device_missing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
