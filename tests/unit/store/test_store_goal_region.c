/*
 * test_store_goal_region.c - pose-region goals in the database: a query's
 * region is stored number for number and read back, a joint goal leaves
 * the region columns NULL, and a database made before the region columns
 * still reads (read-only: NULLs) and gets them when a writer opens it.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <sqlite3.h>

#include "mpbench/mpbench.h"

static const char *const names[] = {"a", "b"};
static const double start[] = {0.5, -0.25};
static const double goal[] = {1, 2};

typedef struct fixture {
    char     path[64];
    mpb_store *s;
    int64_t  scene;
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    strcpy(f->path, "/tmp/mpb-test-region-XXXXXX");
    int fd = mkstemp(f->path);
    assert_true(fd >= 0);
    close(fd);
    unlink(f->path);
    assert_int_equal(mpb_store_open(f->path, 0, &f->s), MPB_OK);
    mpb_experiment_info e = {.name = "x", .config_file = "x.yaml",
                             .config_hash = "h", .config_text = "t",
                             .runs_per_query = 1, .time_limit = 1};
    mpb_scene_info sc = {.name = "s", .robot_format = "urdf",
                         .robot_hash = "r", .robot = "r",
                         .scene_format = "moveit-scene", .scene_hash = "c",
                         .scene = "c"};
    int64_t exp;
    assert_int_equal(mpb_store_begin(f->s), MPB_OK);
    assert_int_equal(mpb_store_experiment_create(f->s, &e, &exp), MPB_OK);
    assert_int_equal(mpb_store_scene_add(f->s, exp, &sc, &f->scene), MPB_OK);
    /* A region goal and a joint goal. */
    const double region[12] = {0.625, -0.25, 0.875, 0.01, 0.02, 0.03,
                               0.5, -0.25, 1.5, 0.05, 0.05, 3.25};
    mpb_query_info qr = {.name = "region", .num_joints = 2,
                         .joint_names = names, .start = start,
                         .goal_kind = MPB_GOAL_POSE_REGION,
                         .goal_tolerance = 0.001,
                         .goal_link = "r_gripper_tool_frame",
                         .goal_region = region};
    mpb_query_info qj = {.name = "joints", .num_joints = 2,
                         .joint_names = names, .start = start,
                         .goal_kind = MPB_GOAL_JOINTS, .goal_joints = goal,
                         .goal_tolerance = 0.01};
    int64_t id;
    assert_int_equal(mpb_store_query_add(f->s, f->scene, &qr, &id), MPB_OK);
    assert_int_equal(mpb_store_query_add(f->s, f->scene, &qj, &id), MPB_OK);
    assert_int_equal(mpb_store_commit(f->s), MPB_OK);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    char side[80];
    mpb_store_close(f->s);
    unlink(f->path);
    snprintf(side, sizeof side, "%s-wal", f->path);
    unlink(side);
    snprintf(side, sizeof side, "%s-shm", f->path);
    unlink(side);
    free(f);
    return 0;
}

/* What mpb_store_queries() gave, copied (its strings live per row). */
typedef struct seen {
    int  n;
    int  kind[2];
    char link[2][64], region[2][256], joints[2][64];
} seen;

static void copy(char *dst, const char *src)
{
    snprintf(dst, 64, "%s", src ? src : "(null)");
}

static int on_query(void *ud, const mpb_query_row *q)
{
    seen *s = ud;
    assert_true(s->n < 2);
    s->kind[s->n] = q->goal_kind;
    copy(s->link[s->n], q->goal_link);
    snprintf(s->region[s->n], sizeof s->region[0], "%s",
             q->goal_region ? q->goal_region : "(null)");
    copy(s->joints[s->n], q->goal_joints);
    s->n++;
    return 0;
}

static void test_region_is_stored_and_read_back(void **state)
{
    fixture *f = *state;
    seen s = {0};
    assert_int_equal(mpb_store_queries(f->s, f->scene, on_query, &s), MPB_OK);
    assert_int_equal(s.n, 2);
    assert_int_equal(s.kind[0], MPB_GOAL_POSE_REGION);
    assert_string_equal(s.link[0], "r_gripper_tool_frame");
    /* %.17g: exactly the doubles given, in order. */
    double v[12];
    int used = 0, off = 0;
    for (int i = 0; i < 12; i++, off += used)
        assert_int_equal(sscanf(s.region[0] + off, "%lf%n", &v[i], &used), 1);
    const double want[12] = {0.625, -0.25, 0.875, 0.01, 0.02, 0.03,
                             0.5, -0.25, 1.5, 0.05, 0.05, 3.25};
    assert_memory_equal(v, want, sizeof want);
    assert_string_equal(s.joints[0], "(null)");
    /* The joint goal has no region. */
    assert_int_equal(s.kind[1], MPB_GOAL_JOINTS);
    assert_string_equal(s.link[1], "(null)");
    assert_string_equal(s.region[1], "(null)");
    assert_string_equal(s.joints[1], "1 2");
}

static void test_older_database_reads_and_upgrades(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    mpb_store *ro, *rw;
    seen s = {0};
    /* Make it an older database: no region columns. */
    mpb_store_close(f->s);
    f->s = NULL;
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "ALTER TABLE queries DROP COLUMN goal_region;"
                                      "ALTER TABLE queries DROP COLUMN goal_link;",
                                  NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);

    assert_int_equal(mpb_store_open(f->path, 1, &ro), MPB_OK);
    assert_int_equal(mpb_store_queries(ro, f->scene, on_query, &s), MPB_OK);
    assert_int_equal(s.n, 2);
    assert_string_equal(s.link[0], "(null)");
    assert_string_equal(s.region[0], "(null)");
    assert_string_equal(s.joints[1], "1 2");
    mpb_store_close(ro);

    /* A writer adds the columns back (empty for the old rows). */
    assert_int_equal(mpb_store_open(f->path, 0, &rw), MPB_OK);
    f->s = rw;
    assert_int_equal(sqlite3_open(f->path, &db), SQLITE_OK);
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_prepare_v2(db, "SELECT count(*) FROM queries"
                                            " WHERE goal_link IS NULL AND"
                                            " goal_region IS NULL",
                                        -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    assert_int_equal(sqlite3_column_int(st, 0), 2);
    sqlite3_finalize(st);
    sqlite3_close(db);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_region_is_stored_and_read_back,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(test_older_database_reads_and_upgrades,
                                        setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
