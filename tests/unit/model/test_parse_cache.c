/*
 * test_parse_cache.c - URDF and SRDF texts parsed once per process
 * (model/parse_cache.h): the same text is parsed once however many worlds
 * are opened with it; a text changed by one number or one element is
 * parsed again and the worlds show the change (joint limits, the allowed
 * collisions of the SRDF); a caller's copy is its own; a text that does
 * not parse fails the same way every time; threads opening worlds of two
 * texts at once each get their own text's. The robot is the PR2 right arm
 * of tests/support/data with its SRDF.
 */
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "model/parse_cache.h"
#include "test_files.h"

static const char *const joints[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint",
    "r_elbow_flex_joint", "r_forearm_roll_joint", "r_wrist_flex_joint",
    "r_wrist_roll_joint"};

static const char empty_scene[] = "empty\n.\n";

static char *urdf, *srdf;

static int setup(void **state)
{
    (void)state;
    urdf = test_read_file(MPB_TEST_DATA "/pr2_right_arm.urdf");
    srdf = test_read_file(MPB_TEST_DATA "/pr2_right_arm.srdf");
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    free(urdf);
    free(srdf);
    mpb__parse_cache_forget();
    return 0;
}

/* urdf + srdf with the first `from` in either replaced by `to`. */
static char *robot_text(const char *u, const char *s, const char *from,
                        const char *to)
{
    size_t n = strlen(u) + strlen(s) + (to ? strlen(to) : 0) + 1;
    char *t = malloc(n);
    assert_non_null(t);
    snprintf(t, n, "%s%s", u, s);
    if (from) {
        char *at = strstr(t, from);
        assert_non_null(at);
        size_t tail = strlen(at + strlen(from));
        memmove(at + strlen(to), at + strlen(from), tail + 1);
        memcpy(at, to, strlen(to));
    }
    return t;
}

static mpb_world *open_world(const char *robot)
{
    mpb_world *w = NULL;
    char err[256];
    if (mpb_world_open_group("urdf", robot, "moveit-scene", empty_scene,
                             joints, 7, &w, err, sizeof err) != MPB_OK)
        fail_msg("open: %s", err);
    return w;
}

/* Is the pair (a, b) in the world's allowed-collision matrix? */
static int allows(const mpb_world *w, const char *a, const char *b)
{
    int n = mpb_world_num_allowed_pairs(w);
    for (int i = 0; i < n; i++) {
        mpb_world_acm_pair p;
        assert_int_equal(mpb_world_allowed_pair(w, i, &p), MPB_OK);
        if ((strcmp(p.link1, a) == 0 && strcmp(p.link2, b) == 0) ||
            (strcmp(p.link1, b) == 0 && strcmp(p.link2, a) == 0))
            return 1;
    }
    return 0;
}

static void the_same_text_is_parsed_once(void **state)
{
    (void)state;
    mpb__parse_cache_forget();
    char *robot = robot_text(urdf, srdf, NULL, NULL);
    long before = mpb__parse_cache_parses();
    mpb_world *w[3];
    for (int i = 0; i < 3; i++)
        w[i] = open_world(robot);
    /* The URDF and the SRDF, once each. */
    assert_int_equal(mpb__parse_cache_parses() - before, 2);
    double lo0, hi0, lo2, hi2;
    mpb_world_joint_limits(w[0], 5, &lo0, &hi0);
    mpb_world_joint_limits(w[2], 5, &lo2, &hi2);
    assert_true(lo0 == lo2 && hi0 == hi2);
    assert_int_equal(mpb_world_num_allowed_pairs(w[0]),
                     mpb_world_num_allowed_pairs(w[2]));
    for (int i = 0; i < 3; i++)
        mpb_world_close(w[i]);
    free(robot);
}

static void a_changed_urdf_is_parsed_again(void **state)
{
    (void)state;
    char *robot = robot_text(urdf, srdf, NULL, NULL);
    /* r_wrist_flex_joint's lower limit, -2.18, made -2.17. */
    char *changed = robot_text(urdf, srdf, "lower=\"-2.18\"", "lower=\"-2.17\"");
    mpb_world *a = open_world(robot);
    long before = mpb__parse_cache_parses();
    mpb_world *b = open_world(changed);
    assert_int_equal(mpb__parse_cache_parses() - before, 1);   /* the URDF */
    mpb_world *c = open_world(robot);
    assert_int_equal(mpb__parse_cache_parses() - before, 1);
    double lo, hi;
    mpb_world_joint_limits(a, 5, &lo, &hi);
    assert_true(lo == -2.18);
    mpb_world_joint_limits(b, 5, &lo, &hi);
    assert_true(lo == -2.17);
    mpb_world_joint_limits(c, 5, &lo, &hi);
    assert_true(lo == -2.18);
    mpb_world_close(a);
    mpb_world_close(b);
    mpb_world_close(c);
    free(robot);
    free(changed);
}

static void a_changed_srdf_is_parsed_again(void **state)
{
    (void)state;
    char *robot = robot_text(urdf, srdf, NULL, NULL);
    /* One pair the SRDF allows, taken out by renaming its element. */
    static const char pair[] =
        "<disable_collisions link1=\"r_shoulder_pan_link\" "
        "link2=\"r_upper_arm_link\" reason=\"User\"/>";
    char *changed = robot_text(urdf, srdf, pair, "<!-- no pair here -->");
    mpb_world *a = open_world(robot);
    long before = mpb__parse_cache_parses();
    mpb_world *b = open_world(changed);
    assert_int_equal(mpb__parse_cache_parses() - before, 1);   /* the SRDF */
    mpb_world *c = open_world(robot);
    assert_true(allows(a, "r_shoulder_pan_link", "r_upper_arm_link"));
    assert_false(allows(b, "r_shoulder_pan_link", "r_upper_arm_link"));
    assert_true(allows(c, "r_shoulder_pan_link", "r_upper_arm_link"));
    assert_int_equal(mpb_world_num_allowed_pairs(b) + 1,
                     mpb_world_num_allowed_pairs(a));
    mpb_world_close(a);
    mpb_world_close(b);
    mpb_world_close(c);
    free(robot);
    free(changed);
}

static void a_copy_is_the_callers_own(void **state)
{
    (void)state;
    char err[256];
    mpb__urdf_model m1, m2;
    assert_int_equal(mpb__urdf_parse_cached(urdf, &m1, err, sizeof err), MPB_OK);
    assert_true(m1.num_links > 1);
    /* Spoil the copy; the next one is as parsed. */
    m1.links[1].name[0] = '#';
    m1.links[1].lo = 99.0;
    assert_int_equal(mpb__urdf_parse_cached(urdf, &m2, err, sizeof err), MPB_OK);
    assert_int_not_equal(m2.links[1].name[0], '#');
    assert_true(m2.links[1].lo != 99.0);
    mpb__urdf_model_clear(&m1);
    mpb__urdf_model_clear(&m2);

    mpb__srdf s1, s2;
    assert_int_equal(mpb__srdf_parse_cached(srdf, &s1, err, sizeof err), MPB_OK);
    assert_true(s1.num_pairs > 0);
    s1.pairs[0].link1[0] = '#';
    assert_int_equal(mpb__srdf_parse_cached(srdf, &s2, err, sizeof err), MPB_OK);
    assert_int_not_equal(s2.pairs[0].link1[0], '#');
    assert_int_equal(s1.num_pairs, s2.num_pairs);
    mpb__srdf_clear(&s1);
    mpb__srdf_clear(&s2);
}

static void a_copy_equals_a_fresh_parse(void **state)
{
    (void)state;
    char err[256];
    mpb__urdf_model fresh, cached;
    assert_int_equal(mpb__urdf_parse(urdf, &fresh, err, sizeof err), MPB_OK);
    assert_int_equal(mpb__urdf_parse_cached(urdf, &cached, err, sizeof err), MPB_OK);
    assert_string_equal(fresh.name, cached.name);
    assert_int_equal(fresh.num_links, cached.num_links);
    for (int i = 0; i < fresh.num_links; i++) {
        const mpb__urdf_link *a = &fresh.links[i], *b = &cached.links[i];
        assert_string_equal(a->name, b->name);
        assert_int_equal(a->parent, b->parent);
        assert_true((a->joint == NULL) == (b->joint == NULL));
        if (a->joint)
            assert_string_equal(a->joint, b->joint);
        assert_true(a->lo == b->lo && a->hi == b->hi);
        assert_int_equal(a->num_geoms, b->num_geoms);
        for (int k = 0; k < a->num_geoms; k++) {
            assert_int_equal(a->geoms[k].type, b->geoms[k].type);
            assert_memory_equal(a->geoms[k].dims, b->geoms[k].dims,
                                sizeof a->geoms[k].dims);
        }
    }
    mpb__urdf_model_clear(&fresh);
    mpb__urdf_model_clear(&cached);
}

static void a_bad_text_fails_every_time(void **state)
{
    (void)state;
    char err1[256], err2[256];
    mpb__urdf_model m;
    const char *bad = "<robot name=\"r\"><link name=\"a\"/><link name=\"a\"/></robot>";
    int rc1 = mpb__urdf_parse_cached(bad, &m, err1, sizeof err1);
    int rc2 = mpb__urdf_parse_cached(bad, &m, err2, sizeof err2);
    assert_int_equal(rc1, MPB_EPARSE);
    assert_int_equal(rc2, MPB_EPARSE);
    assert_string_equal(err1, err2);
    mpb__srdf s;
    rc1 = mpb__srdf_parse_cached("<robot><group", &s, err1, sizeof err1);
    rc2 = mpb__srdf_parse_cached("<robot><group", &s, err2, sizeof err2);
    assert_int_equal(rc1, MPB_EPARSE);
    assert_int_equal(rc2, MPB_EPARSE);
    assert_string_equal(err1, err2);
}

/* Threads that open worlds of two texts in turn, more texts than the
 * cache keeps among them, and check each world's limit. */
enum { THREADS = 4, OPENS = 12 };

typedef struct opener {
    char *texts[6];
    double lows[6];
    int    wrong;
} opener;

static void *open_many(void *arg)
{
    opener *o = arg;
    for (int i = 0; i < OPENS; i++) {
        int k = i % 6;
        mpb_world *w = NULL;
        char err[256];
        if (mpb_world_open_group("urdf", o->texts[k], "moveit-scene",
                                 empty_scene, joints, 7, &w, err,
                                 sizeof err) != MPB_OK) {
            o->wrong++;
            continue;
        }
        double lo, hi;
        mpb_world_joint_limits(w, 5, &lo, &hi);
        o->wrong += lo != o->lows[k];
        mpb_world_close(w);
    }
    return NULL;
}

static void threads_get_their_own_texts(void **state)
{
    (void)state;
    static const char *const lows[6] = {"-2.18", "-2.17", "-2.16", "-2.15",
                                        "-2.14", "-2.13"};
    opener o[THREADS];
    memset(o, 0, sizeof o);
    char *texts[6];
    for (int k = 0; k < 6; k++) {
        char to[64];
        snprintf(to, sizeof to, "lower=\"%s\"", lows[k]);
        texts[k] = robot_text(urdf, srdf, "lower=\"-2.18\"", to);
    }
    pthread_t t[THREADS];
    for (int i = 0; i < THREADS; i++) {
        for (int k = 0; k < 6; k++) {
            /* Each thread starts at another text. */
            o[i].texts[k] = texts[(k + i) % 6];
            o[i].lows[k] = strtod(lows[(k + i) % 6], NULL);
        }
        assert_int_equal(pthread_create(&t[i], NULL, open_many, &o[i]), 0);
    }
    for (int i = 0; i < THREADS; i++) {
        assert_int_equal(pthread_join(t[i], NULL), 0);
        assert_int_equal(o[i].wrong, 0);
    }
    for (int k = 0; k < 6; k++)
        free(texts[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_same_text_is_parsed_once),
        cmocka_unit_test(a_changed_urdf_is_parsed_again),
        cmocka_unit_test(a_changed_srdf_is_parsed_again),
        cmocka_unit_test(a_copy_is_the_callers_own),
        cmocka_unit_test(a_copy_equals_a_fresh_parse),
        cmocka_unit_test(a_bad_text_fails_every_time),
        cmocka_unit_test(threads_get_their_own_texts),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
