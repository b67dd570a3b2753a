/*
 * test_robot_malformed.c - the robot model's refusals: malformed URDF
 * text and files, each one line naming what is wrong, no robot made
 * (tests/support/data/ holds the files).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "mpbench/robot.h"

/* ---- malformed input ---------------------------------------------------- */

/* Expect rc, "urdf: " and the needle in a one-line message. */
static void expect_error(const char *text, const char *base, const char *tip,
                         int rc_expected, const char *needle)
{
    mpb_robot *r = (mpb_robot *)1;
    char err[256];
    int rc = mpb_robot_open_urdf(text, base, tip, &r, err, sizeof err);
    if (rc != rc_expected)
        fail_msg("expected %s, got %s: %s", mpb_err_name(rc_expected),
                 mpb_err_name(rc), err);
    assert_null(r);
    if (strncmp(err, "urdf: ", 6) != 0 || !strstr(err, needle))
        fail_msg("message '%s' lacks 'urdf: ' or '%s'", err, needle);
    assert_null(strchr(err, '\n'));
    assert_true(strlen(err) > 12);
    printf("[ robot    ] %s: %s\n", mpb_err_name(rc), err);
}

#define JOINT(name, type, parent, child, extra)                              \
    "<joint name='" name "' type='" type "'><parent link='" parent "'/>"     \
    "<child link='" child "'/>" extra "</joint>"
#define LIMIT "<limit lower='-1' upper='1' effort='1' velocity='1'/>"

/* A robot with one link and n levels of <x> inside; the text is static. */
static const char *nested_xml(int n)
{
    static char *text;
    const char *head = "<robot name='r'><link name='a'/>";
    free(text);
    text = malloc(strlen(head) + (size_t)n * 7 + 16);
    assert_non_null(text);
    char *p = text + sprintf(text, "%s", head);
    for (int i = 0; i < n; i++)
        p += sprintf(p, "<x>");
    for (int i = 0; i < n; i++)
        p += sprintf(p, "</x>");
    sprintf(p, "</robot>");
    return text;
}

static void test_malformed(void **state)
{
    (void)state;
    expect_error("this is not XML", NULL, "b", MPB_EPARSE, "not XML");
    expect_error("", NULL, "b", MPB_EPARSE, "empty");
    expect_error("<robot name='r'><link name='a'></robot>", NULL, "a",
                 MPB_EPARSE, "XML");
    expect_error("<?xml version='1.0'?><model name='m'/>", NULL, "a",
                 MPB_EPARSE, "robot");
    /* A joint names a link that is not there. */
    expect_error("<robot name='r'><link name='a'/>"
                 JOINT("j", "revolute", "a", "b", LIMIT) "</robot>",
                 NULL, "b", MPB_EPARSE, "[b]");
    /* Base or tip not in the URDF. */
    const char *two = "<robot name='r'><link name='a'/><link name='b'/>"
                      "<link name='c'/>"
                      JOINT("j1", "revolute", "a", "b", LIMIT)
                      JOINT("j2", "revolute", "a", "c", LIMIT) "</robot>";
    expect_error(two, NULL, "hand", MPB_EPARSE, "tip link 'hand' not found");
    expect_error(two, "torso", "b", MPB_EPARSE, "base link 'torso' not found");
    /* Tip not below base: a sibling, the base itself, above it. */
    expect_error(two, "b", "c", MPB_EPARSE, "tip link 'c' is not below base link 'b'");
    expect_error(two, "b", "b", MPB_EPARSE, "not below");
    expect_error(two, "b", "a", MPB_EPARSE, "not below");
    /* Only fixed joints between them. */
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 JOINT("j", "fixed", "a", "b", "") "</robot>",
                 NULL, "b", MPB_EPARSE, "no revolute");
    /* A floating joint inside the chain. */
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 JOINT("j", "floating", "a", "b", "") "</robot>",
                 NULL, "b", MPB_EUNSUPPORTED, "floating");
    /* A bad number in a collision box: urdfdom would drop the shape. */
    expect_error("<robot name='r'><link name='a'/><link name='b'><collision>"
                 "<geometry><box size='1 x 2'/></geometry></collision></link>"
                 JOINT("j", "revolute", "a", "b", LIMIT) "</robot>",
                 NULL, "b", MPB_EPARSE, "collision");
    /* A negative radius. */
    expect_error("<robot name='r'><link name='a'/><link name='b'><collision>"
                 "<geometry><sphere radius='-1'/></geometry></collision></link>"
                 JOINT("j", "revolute", "a", "b", LIMIT) "</robot>",
                 NULL, "b", MPB_EPARSE, "link 'b': collision 0 (sphere)");
    /* A zero axis; limits upside down; a revolute joint without limits. */
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 JOINT("j", "revolute", "a", "b", LIMIT "<axis xyz='0 0 0'/>")
                 "</robot>", NULL, "b", MPB_EPARSE, "joint 'j': axis");
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 JOINT("j", "prismatic", "a", "b",
                       "<limit lower='1' upper='-1' effort='1' velocity='1'/>")
                 "</robot>", NULL, "b", MPB_EPARSE, "lower limit 1 is above");
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 JOINT("j", "revolute", "a", "b", "") "</robot>",
                 NULL, "b", MPB_EPARSE, "does not specify limits");
    /* Finite but far: links near 1e306 crash FCL's tree. */
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 JOINT("j", "revolute", "a", "b",
                       LIMIT "<origin xyz='1e308 0 0'/>") "</robot>",
                 NULL, "b", MPB_EPARSE, "joint 'j': origin xyz is beyond 100000 m");
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 JOINT("j", "prismatic", "a", "b",
                       "<limit lower='0' upper='1e300' effort='1' velocity='1'/>")
                 "</robot>", NULL, "b", MPB_EPARSE,
                 "joint 'j': a limit is beyond 100000 (m or rad)");
    expect_error("<robot name='r'><link name='a'/><link name='b'><collision>"
                 "<origin xyz='0 0 -2e5'/><geometry><sphere radius='1'/>"
                 "</geometry></collision></link>"
                 JOINT("j", "revolute", "a", "b", LIMIT) "</robot>",
                 NULL, "b", MPB_EPARSE,
                 "link 'b': collision 0 (sphere) has a size or origin beyond");
    expect_error("<robot name='r'><link name='a'/><link name='b'><collision>"
                 "<geometry><box size='1 1e200 1'/></geometry></collision></link>"
                 JOINT("j", "revolute", "a", "b", LIMIT) "</robot>",
                 NULL, "b", MPB_EPARSE, "link 'b': collision 0 (box) has a size");
    /* Not UTF-8: a sequence cut short by the end of the text (TinyXML
     * would read past it), a stray continuation byte, an overlong form. */
    expect_error("<robot name='r'><link name='a'/>\n</robot>\n \xe9", NULL, "a",
                 MPB_EPARSE, "line 3, column 2: not UTF-8");
    expect_error("<robot name='\x80'/>", NULL, "a", MPB_EPARSE,
                 "line 1, column 14: not UTF-8");
    expect_error("<robot name='\xc0\xaf'/>", NULL, "a", MPB_EPARSE, "not UTF-8");
    expect_error("<robot name='r\xc3\xa9'><link name='a'/></robot>", NULL, "a",
                 MPB_EPARSE, "is not below");     /* valid UTF-8 goes on */
    /* Joints that do not make a tree: urdfdom accepts them and the walk
     * from the root would recurse without end or copy a link twice. */
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 JOINT("j", "revolute", "a", "b", LIMIT)
                 JOINT("loop", "fixed", "b", "b", "") "</robot>",
                 NULL, "b", MPB_EPARSE, "the joints form a loop at link 'b'");
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 "<link name='c'/>"
                 JOINT("j1", "revolute", "a", "b", LIMIT)
                 JOINT("j2", "revolute", "b", "c", LIMIT)
                 JOINT("j3", "fixed", "a", "c", "") "</robot>",
                 NULL, "c", MPB_EPARSE, "link 'c' has two parent joints");
    expect_error("<robot name='r'><link name='a'/><link name='b'/>"
                 "<link name='c'/><link name='d'/>"
                 JOINT("j", "revolute", "a", "b", LIMIT)
                 JOINT("cd", "fixed", "c", "d", "")
                 JOINT("dc", "fixed", "d", "c", "") "</robot>",
                 NULL, "b", MPB_EPARSE, "the joints form a loop at link");
    /* Elements nested a hundred thousand deep: TinyXML would overflow the
     * stack, so a scan refuses them first; a thousand levels are fine. */
    expect_error(nested_xml(100000), NULL, "a", MPB_EPARSE,
                 "XML nested too deeply (more than 1000 levels)");
    expect_error(nested_xml(999), NULL, "a", MPB_EPARSE, "is not below");
    /* An internal DTD, which TinyXML cannot read (urdfdom would say it
     * found no robot element): refused at its place, as in an SRDF. */
    expect_error("<?xml version='1.0'?>\n<!DOCTYPE robot [ <!ENTITY l '0.5'> ]>\n"
                 "<robot name='r'><link name='a'/></robot>", NULL, "a",
                 MPB_EPARSE, "line 2, column 1: a <!DOCTYPE> with an internal "
                 "DTD ([...]) is not read: remove it");
    /* A DOCTYPE without one is read as before. */
    expect_error("<!DOCTYPE robot>\n<robot name='r'><link name='a'/></robot>",
                 NULL, "a", MPB_EPARSE, "is not below");
    /* A link twice. */
    expect_error("<robot name='r'><link name='a'/><link name='a'/></robot>",
                 NULL, "a", MPB_EPARSE, "not unique");

    /* NULL arguments. */
    mpb_robot *r = NULL;
    char err[128];
    assert_int_equal(mpb_robot_open_urdf(NULL, NULL, "b", &r, err, sizeof err),
                     MPB_EINVAL);
    /* No tip: the longest chain, the first of two equal ones. */
    assert_int_equal(mpb_robot_open_urdf(two, NULL, NULL, &r, err, sizeof err),
                     MPB_OK);
    assert_string_equal(mpb_robot_get_link(r, mpb_robot_tip_link(r))->name, "b");
    mpb_robot_close(r);
    r = NULL;
    assert_int_equal(mpb_robot_open_urdf(two, NULL, "b", NULL, err, sizeof err),
                     MPB_EINVAL);
    /* No err buffer is fine. */
    assert_int_equal(mpb_robot_open_urdf(two, NULL, "zz", &r, NULL, 0), MPB_EPARSE);

    /* Files: the message names the file. */
    char path[1024];
    snprintf(path, sizeof path, "%s/no_such_robot.urdf", MPB_TEST_DATA);
    assert_int_equal(mpb_robot_open_urdf_file(path, NULL, "b", &r, err, sizeof err),
                     MPB_EIO);
    assert_non_null(strstr(err, "no_such_robot.urdf: cannot open"));
    snprintf(path, sizeof path, "%s/fk3.urdf", MPB_TEST_DATA);
    assert_int_equal(mpb_robot_open_urdf_file(path, "base", "hand", &r, err,
                                              sizeof err), MPB_EPARSE);
    assert_non_null(strstr(err, "fk3.urdf: tip link 'hand' not found"));
    printf("[ robot    ] %s\n", err);
    assert_int_equal(mpb_robot_open_urdf_file(path, "base", "tool", &r, err,
                                              sizeof err), MPB_OK);
    assert_int_equal(mpb_robot_num_joints(r), 3);
    mpb_robot_close(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_malformed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
