/* test_robot_text.c - mpb_robot_text_split() (world.h): where a robot
 * text's URDF ends and its SRDF begins. The Python kit's test
 * (tests/python/test_kit.py) asks the same of it through ctypes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/world.h"

#define URDF "<robot name=\"r\">\n  <link name=\"a\"/>\n</robot>\n"
#define SRDF "<robot name=\"r\">\n  <group name=\"g\"/>\n</robot>\n"

/* text splits into its first urdf_len bytes and, if srdf is not NULL, an
 * SRDF equal to srdf. */
static void splits(const char *text, size_t urdf_len, const char *srdf)
{
    size_t len = 0, at = 0;
    assert_int_equal(mpb_robot_text_split(text, &len, &at), MPB_OK);
    assert_int_equal(len, urdf_len);
    if (srdf == NULL)
        assert_int_equal(at, strlen(text));
    else
        assert_string_equal(text + at, srdf);
}

static void a_urdf_alone_has_no_srdf(void **state)
{
    (void)state;
    splits(URDF, strlen(URDF), NULL);
    splits(URDF "\n  <!-- the end -->\n", strlen(URDF), NULL);
}

static void the_srdf_begins_on_the_line_after_the_urdf(void **state)
{
    (void)state;
    splits(URDF SRDF, strlen(URDF), SRDF);
    splits(URDF "<!-- then -->\n" SRDF, strlen(URDF), "<!-- then -->\n" SRDF);
}

static void an_end_tag_in_a_comment_is_not_the_end(void **state)
{
    (void)state;
    const char *u = "<robot name=\"r\"><!-- </robot> -->\n</robot>\n";
    char text[256];
    snprintf(text, sizeof text, "%s%s", u, SRDF);
    splits(text, strlen(u), SRDF);
}

static void more_on_the_end_tags_line_begins_the_srdf(void **state)
{
    (void)state;
    const char *u = "<robot name=\"r\"></robot >";
    char text[256];
    snprintf(text, sizeof text, "%s%s", u, SRDF);
    splits(text, strlen(u), SRDF);
}

static void a_text_without_the_end_tag_is_all_urdf(void **state)
{
    (void)state;
    splits("<robot name=\"r\">", strlen("<robot name=\"r\">"), NULL);
    splits("", 0, NULL);
    size_t len, at;
    assert_int_equal(mpb_robot_text_split(NULL, &len, &at), MPB_EINVAL);
    assert_int_equal(mpb_robot_text_split("x", NULL, &at), MPB_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_urdf_alone_has_no_srdf),
        cmocka_unit_test(the_srdf_begins_on_the_line_after_the_urdf),
        cmocka_unit_test(an_end_tag_in_a_comment_is_not_the_end),
        cmocka_unit_test(more_on_the_end_tags_line_begins_the_srdf),
        cmocka_unit_test(a_text_without_the_end_tag_is_all_urdf),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
