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

#endif
