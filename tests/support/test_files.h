/*
 * test_files.h - a unit test's data file, read whole: NUL-terminated, the
 * caller frees it; the test fails if the file cannot be read. Include it
 * after <cmocka.h>.
 */
#ifndef MPB_TEST_FILES_H
#define MPB_TEST_FILES_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *test_read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        fail_msg("cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = calloc((size_t)n + 1, 1);
    assert_non_null(s);
    assert_int_equal(fread(s, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    return s;
}

/* A robot text as the daemon sends it: the URDF, then its SRDF. */
static inline char *test_read_robot(const char *urdf_path, const char *srdf_path)
{
    char *u = test_read_file(urdf_path);
    char *s = test_read_file(srdf_path);
    char *text = malloc(strlen(u) + strlen(s) + 1);
    assert_non_null(text);
    strcpy(text, u);
    strcat(text, s);
    free(u);
    free(s);
    return text;
}

/*
 * The folder tools/robot_data.sh unpacks the field's robots to (Panda,
 * UR5, Fetch, Baxter), fetched once if missing; never committed.
 */
static inline const char *test_robot_data_dir(void)
{
    static char dir[4096];
    if (dir[0])
        return dir;
    const char *script = MPB_TEST_DATA "/../../../tools/robot_data.sh";
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "sh '%s' --check || sh '%s' >/dev/null", script,
             script);
    if (system(cmd) != 0)
        fail_msg("tools/robot_data.sh could not fetch the robots");
    snprintf(cmd, sizeof cmd, "sh '%s'", script);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    if (!fgets(dir, sizeof dir, p))
        fail_msg("tools/robot_data.sh printed no folder");
    pclose(p);
    dir[strcspn(dir, "\n")] = '\0';
    return dir;
}

/* <robot>/<robot>.urdf and .srdf of the robot data, read whole. */
static inline void test_read_robot_data(const char *name, char **urdf,
                                        char **srdf)
{
    char path[4200];
    const char *dir = test_robot_data_dir();
    snprintf(path, sizeof path, "%s/%s/%s.urdf", dir, name, name);
    *urdf = test_read_file(path);
    snprintf(path, sizeof path, "%s/%s/%s.srdf", dir, name, name);
    *srdf = test_read_file(path);
}

#endif
