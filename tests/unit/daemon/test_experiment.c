/*
 * test_experiment.c - the daemon's experiment loader on small files written
 * here: numbers read as they are written (a seed beyond 2^53 exactly, no
 * hex, no "inf"), and errors that point at the line at fault. The files of
 * the paper's suite are read in test_paper_scenes.c; the daemon's refusals,
 * database untouched, in tests/integration/test_bad_experiment.sh. The
 * planning group named as a group of the Panda's SRDF (the Panda of
 * tools/robot_data.sh, fetched if missing).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "test_octree_box.h"

#include "experiment.h"
#include "test_files.h"

/* One joint, one empty scene, one query: the smallest valid experiment,
 * with the experiment's settings and the scene's source to fill in. */
#define ROBOT "robot: {format: planar, text: \"link_radius 0.01\\njoint a -1 1 0.5\\n\"}\n"
#define PLANNERS "planners: [{planner: null, algorithms: [a]}]\n"
#define QUERIES "queries: [{name: q, start: [0], goal: [0.5]}]"

static char dir[64];
static char err[512];

static int make_dir(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/mpb-test-experiment-XXXXXX");
    return mkdtemp(dir) == NULL ? -1 : 0;
}

static int remove_dir(void **state)
{
    char cmd[128];
    (void)state;
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* Write text as dir/e.yaml and load it; NULL with err set if refused. */
static mpbd_experiment *load_text(const char *text)
{
    char path[128];
    FILE *f;
    snprintf(path, sizeof path, "%s/e.yaml", dir);
    assert_non_null(f = fopen(path, "w"));
    assert_int_equal(fputs(text, f) >= 0, 1);
    assert_int_equal(fclose(f), 0);
    err[0] = '\0';
    return mpbd_experiment_load(path, err, sizeof err);
}

/* An experiment whose settings mapping is {name: x, <settings>}. */
static mpbd_experiment *load_settings(const char *settings)
{
    char text[1024];
    snprintf(text, sizeof text,
             "experiment: {name: x, %s}\n" ROBOT
             "scenes: [{name: s, format: planar, text: \"\", " QUERIES "}]\n"
             PLANNERS, settings);
    return load_text(text);
}

/* err is "<dir>/e.yaml:<where>: <what>" */
static void assert_error(const char *where, const char *what)
{
    char want[2600];
    snprintf(want, sizeof want, "%s/e.yaml:%s: %s", dir, where, what);
    assert_string_equal(err, want);
}

static void seed_keeps_every_digit(void **state)
{
    mpbd_experiment *e;
    (void)state;
    /* 2^53 + 1: through a double it became 2^53. */
    assert_non_null(e = load_settings("time_limit: 1, seed: 9007199254740993"));
    assert_true(e->seed == UINT64_C(9007199254740993));
    mpbd_experiment_free(e);
    assert_non_null(e = load_settings("time_limit: 1, seed: 9223372036854775807"));
    assert_true(e->seed == UINT64_C(9223372036854775807));
    mpbd_experiment_free(e);
    assert_non_null(e = load_settings("time_limit: 1, seed: -1"));
    assert_true(e->seed == UINT64_MAX);
    mpbd_experiment_free(e);
}

static void seed_must_be_a_decimal_integer(void **state)
{
    static const char *const bad[] = {"0x10", "1.5", "1e3", "9223372036854775808",
                                      "seven", "' 7'", NULL};
    char settings[128], what[256];
    (void)state;
    for (int i = 0; bad[i]; i++) {
        snprintf(settings, sizeof settings, "time_limit: 1, seed: %s", bad[i]);
        assert_null(load_settings(settings));
        snprintf(what, sizeof what, "seed must be an integer in digits (no "
                 "point or exponent) from -9223372036854775808 to "
                 "9223372036854775807, not '%s'",
                 bad[i][0] == '\'' ? " 7" : bad[i]);
        assert_error("1:44", what);
    }
}

static void numbers_are_decimal(void **state)
{
    static const char *const good[] = {"2", "+2", "0.5", ".5", "5.", "1e-1",
                                       "2E+0", "1e-310", NULL};
    static const double value[] = {2, 2, 0.5, 0.5, 5, 0.1, 2, 1e-310};
    static const char *const bad[] = {"0x1p0", "inf", "nan", "1e", "-", ".",
                                      "1.2.3", "' 1'", "1e999", NULL};
    char settings[128], what[128];
    mpbd_experiment *e;
    (void)state;
    for (int i = 0; good[i]; i++) {
        snprintf(settings, sizeof settings, "time_limit: %s", good[i]);
        assert_non_null(e = load_settings(settings));
        assert_true(e->time_limit == value[i]);
        mpbd_experiment_free(e);
    }
    for (int i = 0; bad[i]; i++) {
        snprintf(settings, sizeof settings, "time_limit: %s", bad[i]);
        assert_null(load_settings(settings));
        snprintf(what, sizeof what, "time_limit must be a number, not '%s'",
                 bad[i][0] == '\'' ? " 1" : bad[i]);
        assert_error("1:35", what);
    }
    /* Counts are whole and decimal too: strtol() read "0x10" as 0. */
    assert_null(load_settings("time_limit: 1, runs: 0x10"));
    assert_error("1:44", "runs must be a positive integer, not '0x10'");
    /* A joint value in hex was read as 0. */
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n" ROBOT
                          "scenes: [{name: s, format: planar, text: \"\", "
                          "queries: [{name: q, start: [0x0], goal: [0.5]}]}]\n"
                          PLANNERS));
    assert_error("3:74", "start must be a number, not '0x0'");
}

/* memory_limit: MB, 0 (none) when absent; a bad one has its line. */
static void memory_limit_is_mb_above_0(void **state)
{
    mpbd_experiment *e;
    (void)state;
    assert_non_null(e = load_settings("time_limit: 1"));
    assert_true(e->memory_limit == 0);
    mpbd_experiment_free(e);
    assert_non_null(e = load_settings("time_limit: 1, memory_limit: 512.5"));
    assert_true(e->memory_limit == 512.5);
    mpbd_experiment_free(e);
    assert_null(load_settings("time_limit: 1, memory_limit: 0"));
    assert_error("1:52", "memory_limit must be MB above 0 and at most "
                 "1048576 (1 TB), not '0'");
    assert_null(load_settings("time_limit: 1, memory_limit: 1GB"));
    assert_error("1:52", "memory_limit must be a number, not '1GB'");
}

static void a_scene_without_queries_has_a_line(void **state)
{
    (void)state;
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n" ROBOT
                          "scenes:\n"
                          "  - {name: s, format: planar, text: \"\"}\n"
                          PLANNERS));
    assert_error("4:5", "scene 's' needs a non-empty list 'queries'");
}

static void an_unknown_format_is_pointed_at(void **state)
{
    (void)state;
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n"
                          "robot: {format: zzz, text: \"x\"}\n"
                          "scenes: [{name: s, format: planar, text: \"\", "
                          QUERIES "}]\n" PLANNERS));
    assert_error("2:17", "robot format 'zzz' is not supported "
                         "(known: 'planar', 'urdf')");
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n" ROBOT
                          "scenes: [{name: s, format: moveit-scene, text: \"\", "
                          QUERIES "}]\n" PLANNERS));
    assert_error("3:28", "scene format 'moveit-scene' does not go with robot "
                         "format 'planar' (expected 'planar')");
}

/* A robot fault the world calls unsupported that is no format (a mesh
 * URI's scheme) is the robot file's, named at the robot's key, not the
 * scene's format's nor the scene's. */
static void an_unsupported_robot_is_not_a_format(void **state)
{
    char path[128], text[1024], want[512];
    FILE *f;
    (void)state;
    snprintf(path, sizeof path, "%s/r.urdf", dir);
    assert_non_null(f = fopen(path, "w"));
    fputs("<robot name='r'><link name='a'/><link name='b'><collision><geometry>"
          "<mesh filename='http://example.com/x.stl'/></geometry></collision>"
          "</link><joint name='j' type='revolute'><parent link='a'/>"
          "<child link='b'/><limit lower='-1' upper='1' effort='1' "
          "velocity='1'/></joint></robot>\n", f);
    assert_int_equal(fclose(f), 0);
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
             "robot: {format: urdf, file: r.urdf, joints: [j]}\n"
             "scenes: [{name: s, format: moveit-scene, text: \"\", " QUERIES
             "}]\n" PLANNERS);
    assert_null(load_text(text));
    snprintf(want, sizeof want, "%s/e.yaml:2:29: robot: %s: ", dir, path);
    if (strncmp(err, want, strlen(want)) != 0 || !strstr(err, "http"))
        fail_msg("'%s' does not start '%s'", err, want);
}

/* A fault in the robot file is reported at the robot's key (line 2), not
 * at the scene it was first loaded with; the file's binary bytes are
 * escaped, never echoed; in the scene file, at the scene. */
static void faults_are_where_their_file_is_named(void **state)
{
    char path[128], text[1024], want[512];
    FILE *f;
    (void)state;
    snprintf(path, sizeof path, "%s/bin.robot", dir);
    assert_non_null(f = fopen(path, "w"));
    fputs("link_radius 0.1\njoint a -1 1 1\nbogus\x02\xfe\x1b[2J 1\n", f);
    assert_int_equal(fclose(f), 0);
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
             "robot: {format: planar, file: bin.robot}\n"
             "scenes: [{name: s, format: planar, text: \"\", " QUERIES
             "}]\n" PLANNERS);
    assert_null(load_text(text));
    snprintf(want, sizeof want, "%s/e.yaml:2:31: robot: %s: robot line 3: "
             "unknown item 'bogus\\x02\\xfe\\x1b[2J'", dir, path);
    if (strncmp(err, want, strlen(want)) != 0)
        fail_msg("'%s' does not start '%s'", err, want);
    /* UTF-8 is text: kept as it is. */
    snprintf(path, sizeof path, "%s/utf8.scene", dir);
    assert_non_null(f = fopen(path, "w"));
    fputs("circle 0 0 S\xc3\xa4ule\n", f);
    assert_int_equal(fclose(f), 0);
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
             ROBOT "scenes: [{name: s, format: planar, file: utf8.scene, "
             QUERIES "}]\n" PLANNERS);
    assert_null(load_text(text));
    snprintf(want, sizeof want, "%s/e.yaml:3:10: scene 's': %s: scene line 1",
             dir, path);
    if (strncmp(err, want, strlen(want)) != 0 || !strstr(err, "S\xc3\xa4ule"))
        fail_msg("'%s' does not start '%s'", err, want);
}

static void a_directory_is_not_a_file(void **state)
{
    char text[1024], what[256];
    (void)state;
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n" ROBOT
             "scenes: [{name: s, format: planar, file: %s, " QUERIES "}]\n"
             PLANNERS, dir);
    assert_null(load_text(text));
    snprintf(what, sizeof what, "cannot read scene file %s: Is a directory",
             dir);
    assert_error("3:42", what);
    assert_null(mpbd_experiment_load(dir, err, sizeof err));
    snprintf(what, sizeof what, "%s: cannot read: Is a directory", dir);
    assert_string_equal(err, what);
}

/* A family no planner id can hold is refused at its line, not waited for. */
static void a_planner_family_must_fit_an_id(void **state)
{
    char text[1024], what[256], long_name[94];
    mpbd_experiment *e;
    (void)state;
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n" ROBOT
                          "scenes: [{name: s, format: planar, text: \"\", "
                          QUERIES "}]\n"
                          "planners:\n"
                          "  - {planner: 'py planner', algorithms: [a]}\n"));
    assert_error("5:15", "planner 'py planner' can never announce itself: a "
                         "planner id (name@host:pid) holds only letters, "
                         "digits and '_' '.' ':' '@' '-'");
    memset(long_name, 'p', sizeof long_name - 1);
    long_name[sizeof long_name - 1] = '\0';
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n" ROBOT
             "scenes: [{name: s, format: planar, text: \"\", " QUERIES "}]\n"
             "planners: [{planner: %s, algorithms: [a]}]\n", long_name);
    assert_null(load_text(text));
    snprintf(what, sizeof what, "planner '%.40s...' is longer than 47 "
             "characters: no planner id (name@host:pid, at most 51) can hold "
             "it", long_name);
    assert_error("4:22", what);
    /* 47 characters and every character an id may hold are fine. */
    long_name[47] = '\0';
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n" ROBOT
             "scenes: [{name: s, format: planar, text: \"\", " QUERIES "}]\n"
             "planners: [{planner: %s, algorithms: [a]}, "
             "{planner: 'A-z_0.9:@', algorithms: [a]}]\n", long_name);
    assert_non_null(e = load_text(text));
    mpbd_experiment_free(e);
}

/* approach: on a planners entry is the kind of planner of each of its
 * algorithms; none (NULL) where it is not given; a word that is none of
 * the four is refused at its line and column. */
static void a_planner_entry_names_its_approach(void **state)
{
    mpbd_experiment *e;
    (void)state;
    assert_non_null(e = load_text(
        "experiment: {name: x, time_limit: 1}\n" ROBOT
        "scenes: [{name: s, format: planar, text: \"\", " QUERIES "}]\n"
        "planners:\n"
        "  - {planner: srmp, algorithms: [wAstar, ARAstar], approach: search}\n"
        "  - {planner: drake, algorithms: [KTO], approach: optimisation}\n"
        "  - {planner: ompl, algorithms: [RRTConnect]}\n"));
    assert_int_equal(e->num_configs, 4);
    assert_string_equal(e->configs[0].approach, "search");
    assert_string_equal(e->configs[1].approach, "search");
    assert_string_equal(e->configs[2].approach, "optimisation");
    assert_null(e->configs[3].approach);
    mpbd_experiment_free(e);
    static const char *const words[] = {"sampling", "search", "optimisation",
                                        "hybrid"};
    for (size_t i = 0; i < sizeof words / sizeof *words; i++) {
        char text[1024];
        snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
                 ROBOT "scenes: [{name: s, format: planar, text: \"\", "
                 QUERIES "}]\n"
                 "planners: [{planner: p, algorithms: [a], approach: %s}]\n",
                 words[i]);
        assert_non_null(e = load_text(text));
        assert_string_equal(e->configs[0].approach, words[i]);
        mpbd_experiment_free(e);
    }
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n" ROBOT
                          "scenes: [{name: s, format: planar, text: \"\", "
                          QUERIES "}]\n"
                          "planners:\n"
                          "  - {planner: p, algorithms: [a],\n"
                          "     approach: optimization}\n"));
    assert_error("6:16", "approach 'optimization' is none of sampling, "
                         "search, optimisation or hybrid");
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n" ROBOT
                          "scenes: [{name: s, format: planar, text: \"\", "
                          QUERIES "}]\n"
                          "planners: [{planner: p, algorithms: [a], "
                          "approach: [search]}]\n"));
    assert_error("4:52", "approach must be one word: sampling, search, "
                         "optimisation or hybrid");
}

/* `set:` on a scene entry names its problem set; without it the store's
 * default stands (NULL here); a value that is no name is refused at its
 * line and column. */
static void a_scene_entry_names_its_set(void **state)
{
    mpbd_experiment *e;
    (void)state;
    assert_non_null(e = load_text(
        "experiment: {name: x, time_limit: 1}\n" ROBOT
        "scenes:\n"
        "  - {name: s1, set: shelves, format: planar, text: \"\", " QUERIES "}\n"
        "  - {name: t/1, format: planar, text: \"\", " QUERIES "}\n"
        PLANNERS));
    assert_int_equal(e->num_scenes, 2);
    assert_string_equal(e->scenes[0].problem_set, "shelves");
    assert_null(e->scenes[1].problem_set);
    mpbd_experiment_free(e);
    static const char *const bad[] = {"[a, b]", "{a: 1}", "''", "\"a\\tb\"",
                                      NULL};
    for (int i = 0; bad[i]; i++) {
        char text[1024];
        snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
                 ROBOT "scenes:\n"
                 "  - {name: s, format: planar, text: \"\", set: %s,\n"
                 "     " QUERIES "}\n" PLANNERS, bad[i]);
        assert_null(load_text(text));
        assert_error("4:46", "set must be a problem set's name: a non-empty "
                             "string of at most 255 bytes, no control "
                             "characters");
    }
    char text[2048], name[300];
    memset(name, 'a', 256);
    name[256] = '\0';
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
             ROBOT "scenes:\n"
             "  - {name: s, format: planar, text: \"\", set: %s,\n"
             "     " QUERIES "}\n" PLANNERS, name);
    assert_null(load_text(text));
    assert_error("4:46", "set must be a problem set's name: a non-empty "
                         "string of at most 255 bytes, no control "
                         "characters");
    name[255] = '\0';
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
             ROBOT "scenes:\n"
             "  - {name: s, format: planar, text: \"\", set: %s,\n"
             "     " QUERIES "}\n" PLANNERS, name);
    assert_non_null(e = load_text(text));
    assert_string_equal(e->scenes[0].problem_set, name);
    mpbd_experiment_free(e);
}

/* An experiment of the Panda with its SRDF, the robot's extra keys and
 * the query as given. */
static mpbd_experiment *load_panda(const char *robot_keys, const char *query)
{
    char text[8192];
    const char *d = test_robot_data_dir();
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
             "robot:\n"
             "  format: urdf\n"
             "  file: %.1000s/panda/panda.urdf\n"
             "  srdf: %.1000s/panda/panda.srdf\n"
             "%.1000s"
             "scenes:\n"
             "  - name: s\n"
             "    format: moveit-scene\n"
             "    text: \"(empty)\\n.\\n\"\n"
             "    queries:\n"
             "      - %.1000s\n" PLANNERS, d, d, robot_keys, query);
    return load_text(text);
}

#define PANDA_Q "{name: q, start: [0, -0.785, 0, -2.356, 0, 1.571, 0.785], " \
                "goal: [0, 0, 0, -1.5, 0, 1.571, 0.785]}"

/* group: names a group of the SRDF: its active joints, base first. */
static void a_group_of_the_srdf(void **state)
{
    char want[2048];
    (void)state;
    mpbd_experiment *e = load_panda("  group: panda_arm\n", PANDA_Q);
    if (e == NULL)
        fail_msg("%s", err);
    assert_string_equal(e->group_name, "panda_arm");
    assert_int_equal(e->num_joints, 7);
    assert_int_equal(e->num_group, 7);
    for (int j = 0; j < 7; j++) {
        char name[32];
        snprintf(name, sizeof name, "panda_joint%d", j + 1);
        assert_string_equal(e->joint_names[j], name);
        assert_string_equal(e->group[j], name);
    }
    mpbd_experiment_free(e);
    /* Joints listed: no group name. */
    e = load_panda("  joints: [panda_joint1, panda_joint2, panda_joint3, "
                   "panda_joint4, panda_joint5, panda_joint6, panda_joint7]\n",
                   PANDA_Q);
    assert_non_null(e);
    assert_null(e->group_name);
    mpbd_experiment_free(e);

    assert_null(load_panda("  group: arm\n", PANDA_Q));
    snprintf(want, sizeof want, "%.1000s/panda/panda.srdf has no group 'arm' (its "
             "groups: panda_arm, hand, panda_arm_hand)", test_robot_data_dir());
    assert_error("6:10", want);
    assert_null(load_panda("  group: hand\n", PANDA_Q));
    assert_error("6:10", "group 'hand' has no joint to plan: its joints are "
                 "fixed, mimic, passive or virtual");
    assert_null(load_panda("  group: panda_arm\n  joints: [panda_joint1]\n",
                           PANDA_Q));
    assert_error("6:10", "give the planning group as joints or as group, not "
                 "both");
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n"
                          "robot: {format: planar, text: \"link_radius 0.01\\n"
                          "joint a -1 1 0.5\\n\", group: arm}\n"
                          "scenes: [{name: s, format: planar, text: \"\", "
                          QUERIES "}]\n" PLANNERS));
    assert_error("2:78", "group 'arm' names a group of the robot's SRDF: give "
                 "it as srdf");
}

/* With group:, a start or goal may name one of the group's states. */
static void a_group_state_by_name(void **state)
{
    (void)state;
    mpbd_experiment *e = load_panda("  group: panda_arm\n",
                                    "{name: q, start: ready, goal: extended}");
    if (e == NULL)
        fail_msg("%s", err);
    /* The SRDF's values, as written. */
    const double ready[7] = {0, -0.785, 0, -2.356, 0, 1.571, 0.785};
    const double extended[7] = {0, 0, 0, 0, 0, 1.571, 0.785};
    assert_int_equal(e->num_queries, 1);
    for (int j = 0; j < 7; j++) {
        assert_true(e->queries[0].start[j] == ready[j]);
        assert_true(e->queries[0].goal[j] == extended[j]);
    }
    mpbd_experiment_free(e);
    /* A list still works beside a name. */
    e = load_panda("  group: panda_arm\n", "{name: q, start: [0, 0, 0, -1.5, "
                   "0, 1.571, 0.785], goal: ready}");
    if (e == NULL)
        fail_msg("%s", err);
    assert_true(e->queries[0].start[3] == -1.5);
    assert_true(e->queries[0].goal[3] == -2.356);
    mpbd_experiment_free(e);

    assert_null(load_panda("  group: panda_arm\n",
                           "{name: q, start: redy, goal: extended}"));
    assert_error("12:26", "start: group 'panda_arm' has no group_state 'redy' "
                 "(it has ready, extended, transport)");
    assert_null(load_panda("  group: panda_arm\n",
                           "{name: q, start: ready, goal: open}"));
    assert_error("12:39", "goal: group_state 'open' is for group 'hand', not "
                 "'panda_arm'");
    /* Listed joints: no states to name. */
    assert_null(load_panda("  joints: [panda_joint1, panda_joint2, panda_joint3, "
                           "panda_joint4, panda_joint5, panda_joint6, "
                           "panda_joint7]\n",
                           "{name: q, start: ready, goal: extended}"));
    assert_error("12:26", "start must be a list of 7 numbers");
}

/* An arm j that carries a finger on a slide k (0 .. 1, outside the
 * group): held at 0.5 the finger reaches the box at x = 1 when the arm
 * points along x. */
static void write_slide_robot(void)
{
    char path[128];
    FILE *f;
    snprintf(path, sizeof path, "%s/slide.urdf", dir);
    assert_non_null(f = fopen(path, "w"));
    fputs("<robot name='r'><link name='a'/>"
          "<link name='b'><collision><geometry><box size='0.2 0.2 0.2'/>"
          "</geometry></collision></link>"
          "<link name='f'><collision><geometry><sphere radius='0.1'/>"
          "</geometry></collision></link>"
          "<joint name='j' type='revolute'><parent link='a'/><child link='b'/>"
          "<axis xyz='0 0 1'/><limit lower='-2' upper='2' effort='1' "
          "velocity='1'/></joint>"
          "<joint name='k' type='prismatic'><parent link='b'/><child link='f'/>"
          "<origin xyz='0.5 0 0'/><axis xyz='1 0 0'/><limit lower='0' "
          "upper='1' effort='1' velocity='1'/></joint></robot>\n", f);
    assert_int_equal(fclose(f), 0);
}

#define SLIDE_SCENE "\"s\\n* box\\n1 0 0\\n0 0 0 1\\n1\\nbox\\n0.2 0.2 0.2\\n" \
                    "0 0 0\\n0 0 0 1\\n0 0 0 0\\n0\\n.\\n\""

static mpbd_experiment *load_slide(const char *robot_extra, const char *queries)
{
    char text[2048];
    write_slide_robot();
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"
             "robot: {format: urdf, file: slide.urdf, joints: [j]%s}\n"
             "scenes: [{name: s, format: moveit-scene, text: " SLIDE_SCENE
             ",\n  queries: [%s]}]\n" PLANNERS, robot_extra, queries);
    return load_text(text);
}

static void joints_outside_the_group_hold_values(void **state)
{
    mpbd_experiment *e;
    (void)state;
    /* Held at 0 (the default) the finger is clear of the box. */
    assert_non_null(e = load_slide("", "{name: q, start: [0], goal: [1]}"));
    assert_int_equal(e->num_held, 0);
    mpbd_experiment_free(e);
    /* The robot's value, and a query's own. */
    assert_non_null(e = load_slide(", joint_values: {k: 0.5}",
                                   "{name: q, start: [1.5], goal: [1]},\n"
                                   "  {name: r, start: [0], goal: [1], "
                                   "joint_values: {k: 0.1}}"));
    assert_int_equal(e->num_held, 1);
    assert_string_equal(e->held_names[0], "k");
    assert_true(e->held_default[0] == 0.5);
    assert_true(e->queries[0].held[0] == 0.5);
    assert_true(e->queries[1].held[0] == 0.1);
    mpbd_experiment_free(e);
    /* Held at 0.5 the finger is in the box at j = 0. */
    assert_null(load_slide(", joint_values: {k: 0.5}",
                           "{name: q, start: [0], goal: [1]}"));
    assert_non_null(strstr(err, "start is in collision"));
    /* A joint only a later query names holds its default in the others. */
    assert_non_null(e = load_slide("", "{name: q, start: [0], goal: [1]},\n"
                                   "  {name: r, start: [1.5], goal: [1], "
                                   "joint_values: {k: 0.5}}"));
    assert_int_equal(e->num_held, 1);
    assert_true(e->queries[0].held[0] == 0.0 && e->queries[1].held[0] == 0.5);
    mpbd_experiment_free(e);

    assert_null(load_slide(", joint_values: {kk: 0.5}", "{name: q, start: [0], goal: [1]}"));
    assert_error("2:69", "joint 'kk' is not a joint of the robot");
    assert_null(load_slide(", joint_values: {j: 0.5}", "{name: q, start: [0], goal: [1]}"));
    assert_error("2:69", "joint 'j' is in the planning group: its value "
                 "belongs in the start, not held");
    assert_null(load_slide(", joint_values: {k: 1.5}", "{name: q, start: [0], goal: [1]}"));
    assert_error("2:72", "joint 'k' = 1.5 is outside its limits [0, 1]");
    assert_null(load_slide(", joint_values: {k: nan}", "{name: q, start: [0], goal: [1]}"));
    assert_error("2:72", "a joint value must be a number, not 'nan'");
}

/* A scene file beside the experiment names an octree file beside it:
 * the daemon reads it into the scene's text (what planners get) and
 * checks starts against its cells. */
static void a_scene_file_names_its_octree(void **state)
{
    (void)state;
    char *bt = test_box_bt(dir), path[160], text[1024];
    free(bt);
    snprintf(path, sizeof path, "%s/oct.scene", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    /* the box's cells from x 0.5, lowered to z -0.2 .. 0.2: the finger
       (at x 0.5, radius 0.1, when j = 0) is in them */
    fputs("oct\n.\noctree cells file box.bt 0 0 -0.4 0 0 0 1\n", f);
    assert_int_equal(fclose(f), 0);
    write_slide_robot();
#define OCT_EXPERIMENT(start) "experiment: {name: x, time_limit: 1}\n" \
        "robot: {format: urdf, file: slide.urdf, joints: [j]}\n" \
        "scenes: [{name: s, format: moveit-scene, file: oct.scene,\n" \
        "  queries: [{name: q, start: [" start "], goal: [1.5]}]}]\n" PLANNERS
    snprintf(text, sizeof text, "%s", OCT_EXPERIMENT("1.5"));
    mpbd_experiment *e = load_text(text);
    if (!e)
        fail_msg("%s", err);
    assert_non_null(strstr(e->scenes[0].scene, "\noctree cells binary 0.01 "));
    mpbd_experiment_free(e);
    snprintf(text, sizeof text, "%s", OCT_EXPERIMENT("0"));
    assert_null(load_text(text));
    assert_non_null(strstr(err, "start is in collision"));
    /* inline text names its octree beside the experiment file */
    assert_null(load_text("experiment: {name: x, time_limit: 1}\n"
                          "robot: {format: urdf, file: slide.urdf, joints: [j]}\n"
                          "scenes: [{name: s, format: moveit-scene, text: "
                          "\"t\\n.\\noctree cells file box.bt 0 0 -0.4 0 0 0 1\\n\",\n"
                          "  queries: [{name: q, start: [0], goal: [1.5]}]}]\n" PLANNERS));
    assert_non_null(strstr(err, "start is in collision"));
    /* a missing octree file: at the scene's file key, both files named */
    f = fopen(path, "w");
    fputs("oct\n.\noctree cells file gone.bt\n", f);
    fclose(f);
    snprintf(text, sizeof text, "%s", OCT_EXPERIMENT("1.5"));
    assert_null(load_text(text));
    assert_non_null(strstr(err, "oct.scene: scene line 3: "));
    assert_non_null(strstr(err, "gone.bt: cannot open"));
}

/* A scene entry's `seen:`: what its planners are given instead of the
 * scene. A file of its own, or what cameras see of the scene (the same
 * bytes for the same seed, others for another); its world opened for
 * judging on it; bad settings refused at their place. */
static void a_scene_may_be_planned_on_what_was_seen(void **state)
{
    (void)state;
    char text[2048], path[160];
    write_slide_robot();
    snprintf(path, sizeof path, "%s/phantom.scene", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("seen\n* phantom\n0 1 0\n0 0 0 1\n1\nbox\n0.2 0.2 0.2\n0 0 0\n"
          "0 0 0 1\n0 0 0 0\n0\n.\n", f);
    assert_int_equal(fclose(f), 0);
#define SEEN_EXPERIMENT(seen) "experiment: {name: x, time_limit: 1}\n" \
        "robot: {format: urdf, file: slide.urdf, joints: [j]}\n" \
        "scenes: [{name: s, format: moveit-scene, text: " SLIDE_SCENE ",\n" \
        "  seen: " seen ",\n" \
        "  queries: [{name: q, start: [1.5], goal: [-1.5]}]}]\n" PLANNERS
    snprintf(text, sizeof text, "%s",
             SEEN_EXPERIMENT("{format: moveit-scene, file: phantom.scene}"));
    mpbd_experiment *e = load_text(text);
    if (!e)
        fail_msg("%s", err);
    const mpbd_scene *sc = &e->scenes[0];
    assert_non_null(sc->seen);
    assert_non_null(strstr(sc->seen, "* phantom"));
    assert_null(strstr(sc->scene, "phantom"));
    assert_string_equal(mpbd_scene_given(sc), sc->seen);
    assert_non_null(sc->seen_world);
    assert_non_null(strstr(sc->seen_how, "phantom.scene"));
    mpbd_experiment_free(e);

    /* sensed: a seed gives the same bytes, another seed others */
    char hash[3][MPB_HASH_SIZE];
    const char *const sensed[] = {
        "{sense: {seed: 7, resolution: 0.02, noise: 0.001}}",
        "{sense: {seed: 7, resolution: 0.02, noise: 0.001}}",
        "{sense: {seed: 8, resolution: 0.02, noise: 0.001}}",
    };
    for (int i = 0; i < 3; i++) {
        snprintf(text, sizeof text,
                 "experiment: {name: x, time_limit: 1}\n"
                 "robot: {format: urdf, file: slide.urdf, joints: [j]}\n"
                 "scenes: [{name: s, format: moveit-scene, text: " SLIDE_SCENE ",\n"
                 "  seen: %s,\n"
                 "  queries: [{name: q, start: [1.5], goal: [-1.5]}]}]\n" PLANNERS,
                 sensed[i]);
        assert_non_null(e = load_text(text));
        assert_non_null(strstr(e->scenes[0].seen, "\noctree "));
        assert_non_null(strstr(e->scenes[0].seen_how, "sensed: 2 cameras"));
        assert_non_null(e->scenes[0].seen_world);
        memcpy(hash[i], e->scenes[0].seen_hash, MPB_HASH_SIZE);
        mpbd_experiment_free(e);
    }
    assert_memory_equal(hash[0], hash[1], MPB_HASH_SIZE);
    assert_memory_not_equal(hash[0], hash[2], MPB_HASH_SIZE);

    /* bad settings, at their place */
    snprintf(text, sizeof text, "%s", SEEN_EXPERIMENT("{sense: {fov: 200}}"));
    assert_null(load_text(text));
    assert_non_null(strstr(err, "e.yaml:4:17: sense: "));
    assert_non_null(strstr(err, "fov"));
    snprintf(text, sizeof text, "%s", SEEN_EXPERIMENT("{sense: {lens: 3}}"));
    assert_null(load_text(text));
    assert_non_null(strstr(err, "lens"));
    snprintf(text, sizeof text, "%s", SEEN_EXPERIMENT("{format: moveit-scene}"));
    assert_null(load_text(text));
    assert_non_null(strstr(err, "exactly one of 'file' and 'text'"));
    snprintf(text, sizeof text, "%s", SEEN_EXPERIMENT("phantom.scene"));
    assert_null(load_text(text));
    assert_error("4:9", "seen must be a mapping: a scene (format and file or "
                 "text) or sense: {camera settings}");
#undef SEEN_EXPERIMENT
}

/* A MoveIt scene file with requests (moveit.h), on the slide robot: the
 * scene's and the start's values of k are held, the request's start
 * wins, the tightest tolerance rules, pose goals name a link, and the
 * scene's allowed pairs travel in its robot text. */
static void moveit_files_become_scenes_and_queries(void **state)
{
    char text[2048], p[160];
    FILE *f;
    mpbd_experiment *e;
    (void)state;
    write_slide_robot();
    static const struct { const char *name, *text; } files[] = {
        {"s.yaml", "robot_state: {joint_state: {name: [j, k], position: [0, 0.2]}}\n"
                   "allowed_collision_matrix: {entry_names: [b, f], "
                   "entry_values: [[false, true], [true, false]]}\n"
                   "world: {collision_objects: [{id: box, primitives: [{type: box, "
                   "dimensions: [0.2, 0.2, 0.2]}], primitive_poses: [{position: [1, 0, 0], "
                   "orientation: [0, 0, 0, 1]}]}]}\n"},
        {"r1.yaml", "group_name: arm\nallowed_planning_time: 5\n"
                    "start_state: {joint_state: {name: [j], position: [1.5]}}\n"
                    "goal_constraints: [{joint_constraints: [{joint_name: j, "
                    "position: 1.4, tolerance_above: 0.01, tolerance_below: 0.03}]}]\n"},
        {"r2.yaml", "start_state: {joint_state: {name: [j, k], position: [1.5, 1.5]}}\n"
                    "goal_constraints: [{position_constraints: [{link_name: f, "
                    "constraint_region: {primitives: [{type: box, dimensions: [0.1, 0.1, 0.1]}], "
                    "primitive_poses: [{position: [0, 0.7, 0], orientation: [0, 0, 0, 1]}]}}]}]\n"},
        {"r3.yaml", "goal_constraints: [{position_constraints: [{link_name: g, "
                    "constraint_region: {primitives: [{type: box, dimensions: [0.1, 0.1, 0.1]}], "
                    "primitive_poses: [{position: [0, 0.7, 0], orientation: [0, 0, 0, 1]}]}}]}]\n"},
    };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, files[i].name);
        assert_non_null(f = fopen(p, "w"));
        fputs(files[i].text, f);
        assert_int_equal(fclose(f), 0);
    }
#define MOVEIT_EXP(requests, extra)                                          \
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"    \
             "robot: {format: urdf, file: slide.urdf, joints: [j]}\n"        \
             "scenes: [{name: m, moveit_scene: s.yaml, requests: [%s]%s}]\n" \
             PLANNERS, requests, extra)
    MOVEIT_EXP("r1.yaml, r2.yaml", ", clamp_joint_values: true, set: slides");
    assert_non_null(e = load_text(text));
    assert_int_equal(e->num_scenes, 1);
    assert_string_equal(e->scenes[0].problem_set, "slides");
    assert_int_equal(e->num_queries, 2);
    assert_string_equal(e->queries[0].name, "r1");
    assert_true(e->queries[0].start[0] == 1.5);
    assert_true(e->queries[0].goal[0] == 1.4);
    assert_true(e->queries[0].tolerance == 0.01);
    assert_string_equal(e->queries[0].moveit_group, "arm");
    assert_true(e->queries[0].planning_time == 5);
    assert_int_equal(e->num_held, 1);
    assert_true(e->queries[0].held[0] == 0.2);   /* the scene's */
    assert_true(e->queries[1].held[0] == 1.0);   /* 1.5, clamped */
    assert_int_equal(e->held_clamped, 1);
    assert_int_equal(e->queries[1].goal_kind, MPB_GOAL_POSE_REGION);
    assert_string_equal(e->queries[1].goal_link, "f");
    assert_true(e->queries[1].position_tolerance[0] == 0.05);
    assert_non_null(strstr(e->scenes[0].robot, "<disable_collisions link1=\"b\" "
                           "link2=\"f\" reason=\"Scene\"/>"));
    assert_non_null(strstr(e->scenes[0].scene, "* box\n"));
    mpbd_experiment_free(e);

    /* Without clamping, 1.5 is outside k's limits: at its place. */
    MOVEIT_EXP("r2.yaml", "");
    assert_null(load_text(text));
    snprintf(p, sizeof p, "%s/r2.yaml:1:39: joint 'k' = 1.5 is outside its "
             "limits [0, 1]", dir);
    assert_string_equal(err, p);
    /* An unknown link in a pose goal, at its name. */
    MOVEIT_EXP("r3.yaml", "");
    assert_null(load_text(text));
    snprintf(p, sizeof p, "%s/r3.yaml:1:56: ", dir);
    if (strncmp(err, p, strlen(p)) != 0 || !strstr(err, "'g'"))
        fail_msg("%s", err);
#undef MOVEIT_EXP
}

/*
 * MoveIt files made for a fuller model of the robot (MotionBenchMaker's
 * Fetch and UR5 with VAMP's URDFs): allowed pairs naming links the robot
 * lacks are skipped, as MoveIt does, and said in one warning; with
 * clamp_joint_values a state's joints the robot lacks are skipped, a start
 * just outside a limit and a goal whose tolerance reaches inside one are
 * moved onto it, all counted; without it they are refused. A pair naming
 * an object of the scene is refused (such contacts are not read).
 */
static void moveit_files_of_a_fuller_model_fit_the_robot(void **state)
{
    char text[2048], p[400];
    FILE *f;
    mpbd_experiment *e;
    (void)state;
    write_slide_robot();
    static const struct { const char *name, *text; } files[] = {
        {"f.yaml", "robot_state: {joint_state: {name: [j, wheel, k], "
                   "position: [0, 3, 0.2]}}\n"
                   "allowed_collision_matrix: {entry_names: [b, f, pedestal], "
                   "entry_values: [[false, true, true], [true, false, false], "
                   "[true, false, false]]}\n"},
        {"fr.yaml", "allowed_planning_time: 1\n"
                    "start_state: {joint_state: {name: [j], position: [2.03]}}\n"
                    "goal_constraints: [{joint_constraints: [{joint_name: j, "
                    "position: -2.0004, tolerance_above: 0.001, "
                    "tolerance_below: 0.001}]}]\n"},
        {"fo.yaml", "allowed_collision_matrix: {entry_names: [b, box], "
                    "entry_values: [[false, true], [true, false]]}\n"
                    "world: {collision_objects: [{id: box, primitives: [{type: box, "
                    "dimensions: [0.2, 0.2, 0.2]}], primitive_poses: [{position: [1, 0, 0], "
                    "orientation: [0, 0, 0, 1]}]}]}\n"},
    };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, files[i].name);
        assert_non_null(f = fopen(p, "w"));
        fputs(files[i].text, f);
        assert_int_equal(fclose(f), 0);
    }
#define FIT_EXP(scene, extra)                                                \
    snprintf(text, sizeof text, "experiment: {name: x, time_limit: 1}\n"    \
             "robot: {format: urdf, file: slide.urdf, joints: [j]}\n"        \
             "scenes: [{name: m, moveit_scene: %s, requests: [fr.yaml]%s}]\n" \
             PLANNERS, scene, extra)
    FIT_EXP("f.yaml", ", clamp_joint_values: true");
    assert_non_null(e = load_text(text));
    assert_true(e->queries[0].start[0] == 2.0);        /* 2.03 */
    assert_true(e->queries[0].goal[0] == -2.0);        /* -2.0004 */
    /* The region stays within the file's: -2.0004 + 0.001. */
    assert_true(fabs(e->queries[0].tolerance - 0.0006) < 1e-12);
    assert_true(e->queries[0].held[0] == 0.2);
    assert_int_equal(e->held_unknown, 1);
    assert_int_equal(e->start_clamped, 1);
    assert_int_equal(e->goal_clamped, 1);
    assert_non_null(strstr(e->scenes[0].robot, "<disable_collisions link1=\"b\" "
                           "link2=\"f\" reason=\"Scene\"/>"));
    assert_null(strstr(e->scenes[0].robot, "pedestal"));
    char note[1024];
    assert_int_equal(mpbd_experiment_moveit_note(e, note, sizeof note), 1);
    assert_string_equal(note, "1 MoveIt queries: 0 joint values moved into "
                        "their limits and 0 of fixed joints ignored, 1 of "
                        "joints the robot lacks ignored (wheel), 1 start "
                        "values within 0.05 of a limit and 1 goal values "
                        "within their tolerance of one moved onto it "
                        "(clamp_joint_values); 0 ask for an "
                        "allowed_planning_time other than the time_limit (up "
                        "to 0 s), which rules (1 s)");
    assert_int_equal(mpbd_experiment_scene_acm_note(e, note, sizeof note), 1);
    snprintf(p, sizeof p, "1 allowed_collision_matrix pairs in 1 MoveIt scene "
             "name links the robot lacks (pedestal) and are skipped, as MoveIt "
             "does; the first at %s/f.yaml:2:48", dir);
    assert_string_equal(note, p);
    mpbd_experiment_free(e);

    /* Without clamp_joint_values: the joint the robot lacks is refused,
     * at its name; the pair is skipped all the same. */
    FIT_EXP("f.yaml", "");
    assert_null(load_text(text));
    snprintf(p, sizeof p, "%s/f.yaml:1:39: joint 'wheel' is not a joint of the "
             "robot", dir);
    assert_string_equal(err, p);

    /* A pair naming an object of the scene: refused, at the name. */
    FIT_EXP("fo.yaml", ", clamp_joint_values: true");
    assert_null(load_text(text));
    snprintf(p, sizeof p, "%s/fo.yaml:1:45: allowed_collision_matrix: 'box' "
             "is an object of the scene; allowed contacts with objects are not "
             "read", dir);
    assert_string_equal(err, p);
#undef FIT_EXP
}

/* A NUL byte or a byte that is not UTF-8 is placed at its line and
 * column. */
static void bytes_are_placed_at_their_line(void **state)
{
    char path[128], text[256];
    (void)state;
    snprintf(path, sizeof path, "%s/e.yaml", dir);
    int n = snprintf(text, sizeof text, "# one\n# two\nexperiment: {name: "
                     "xy}\n");
    for (int k = 0; k < 2; k++) {
        FILE *f;
        text[30] = k == 0 ? '\0' : (char)0xfe;
        assert_non_null(f = fopen(path, "wb"));
        assert_int_equal(fwrite(text, 1, (size_t)n, f), (size_t)n);
        assert_int_equal(fclose(f), 0);
        assert_null(mpbd_experiment_load(path, err, sizeof err));
        assert_error("3:19", k == 0 ? "a NUL byte: not a text file"
                                    : "YAML: invalid leading UTF-8 octet");
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(seed_keeps_every_digit),
        cmocka_unit_test(seed_must_be_a_decimal_integer),
        cmocka_unit_test(numbers_are_decimal),
        cmocka_unit_test(memory_limit_is_mb_above_0),
        cmocka_unit_test(a_scene_without_queries_has_a_line),
        cmocka_unit_test(an_unknown_format_is_pointed_at),
        cmocka_unit_test(an_unsupported_robot_is_not_a_format),
        cmocka_unit_test(joints_outside_the_group_hold_values),
        cmocka_unit_test(a_scene_file_names_its_octree),
        cmocka_unit_test(a_scene_may_be_planned_on_what_was_seen),
        cmocka_unit_test(moveit_files_become_scenes_and_queries),
        cmocka_unit_test(moveit_files_of_a_fuller_model_fit_the_robot),
        cmocka_unit_test(faults_are_where_their_file_is_named),
        cmocka_unit_test(a_directory_is_not_a_file),
        cmocka_unit_test(a_planner_family_must_fit_an_id),
        cmocka_unit_test(a_planner_entry_names_its_approach),
        cmocka_unit_test(a_scene_entry_names_its_set),
        cmocka_unit_test(a_group_of_the_srdf),
        cmocka_unit_test(a_group_state_by_name),
        cmocka_unit_test(bytes_are_placed_at_their_line),
    };
    return cmocka_run_group_tests(tests, make_dir, remove_dir);
}
