/*
 * test_tool.h - for a unit test that runs a built program as a user runs
 * it: a temporary folder, the program's path in the build tree, and its
 * output captured. Include it after <cmocka.h>.
 */
#ifndef MPB_TEST_TOOL_H
#define MPB_TEST_TOOL_H

#include <libgen.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* A new empty folder /tmp/mpb_test_NAME_XXXXXX into dir (size >= 64). */
static inline void test_make_dir(char *dir, size_t size, const char *name)
{
    snprintf(dir, size, "/tmp/mpb_test_%s_XXXXXX", name);
    assert_non_null(mkdtemp(dir));
}

/* The folder removed, with all it holds. */
static inline void test_remove_dir(const char *dir)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

/*
 * The path of a program of the build tree, BUILD/rel (e.g. "tools/mpb"):
 * BUILD is $MPB_BUILD, else the folder above this test's own (tests are
 * BUILD/tests/NAME). 0, or -1 after one line on stderr when it is not
 * there to run.
 */
static inline int test_built_program(const char *rel, char *out, size_t size)
{
    const char *build = getenv("MPB_BUILD");
    if (build != NULL) {
        snprintf(out, size, "%s/%s", build, rel);
    } else {
        char self[2048];
        ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
        if (n <= 0) {
            fprintf(stderr, "cannot find this test's own path; set MPB_BUILD\n");
            return -1;
        }
        self[n] = '\0';
        snprintf(out, size, "%s/../%s", dirname(self), rel);
    }
    if (access(out, X_OK) != 0) {
        fprintf(stderr, "no %s (build it first)\n", out);
        return -1;
    }
    return 0;
}

typedef struct test_output {
    char text[32768];
    int  status;                /* exit status */
} test_output;

/* Run `PROGRAM ARGS` with the shell; keep stdout, stderr or both (which:
 * "stdout", "stderr", "both"). */
static inline void test_run(test_output *o, const char *program,
                            const char *which, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static inline void test_run(test_output *o, const char *program,
                            const char *which, const char *fmt, ...)
{
    char args[2048], cmd[8192];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    snprintf(cmd, sizeof cmd, "'%s' %s %s", program, args,
             strcmp(which, "stdout") == 0   ? "2>/dev/null"
             : strcmp(which, "stderr") == 0 ? "2>&1 >/dev/null"
                                            : "2>&1");
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t n = fread(o->text, 1, sizeof o->text - 1, p);
    o->text[n] = '\0';
    int st = pclose(p);
    assert_true(WIFEXITED(st));
    o->status = WEXITSTATUS(st);
}

#endif
