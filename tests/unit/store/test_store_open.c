/* test_store_open.c - opening the database: what is refused and why, and
 * that reading leaves nothing behind, not even where nothing can be
 * written. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>
#include <sqlite3.h>

#include "mpbench/mpbench.h"
#include "test_store.h"

typedef struct fixture {
    char dir[64], db[96], other[96], wal[104], shm[104];
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    strcpy(f->dir, "/tmp/mpb_test_store_open_XXXXXX");
    assert_non_null(mkdtemp(f->dir));
    snprintf(f->db, sizeof f->db, "%s/results.db", f->dir);
    snprintf(f->other, sizeof f->other, "%s/other.db", f->dir);
    snprintf(f->wal, sizeof f->wal, "%s-wal", f->db);
    snprintf(f->shm, sizeof f->shm, "%s-shm", f->db);

    mpb_store *s;
    int64_t id;
    mpb_experiment_info e = {"exp", "exp.yaml", "h1", "text", 2, 1.5, NULL, 0};
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    assert_int_equal(mpb_store_experiment_create(s, &e, &id), MPB_OK);
    mpb_store_close(s);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    char cmd[128];
    chmod(f->dir, 0700);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", f->dir);
    assert_int_equal(system(cmd), 0);
    free(f);
    return 0;
}

static int present(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* The whole file, to compare before and after. */
static char *slurp(const char *path, long *len)
{
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    fseek(fp, 0, SEEK_END);
    *len = ftell(fp);
    rewind(fp);
    char *buf = malloc((size_t)*len + 1);
    assert_int_equal(fread(buf, 1, (size_t)*len, fp), (size_t)*len);
    fclose(fp);
    return buf;
}

static void another_programs_database_is_refused_untouched(void **state)
{
    fixture *f = *state;
    sqlite3 *db;
    assert_int_equal(sqlite3_open(f->other, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "CREATE TABLE notes(t TEXT);"
                                      " INSERT INTO notes VALUES ('mine')",
                                  NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    long before_len, after_len;
    char *before = slurp(f->other, &before_len);

    mpb_store *s;
    assert_int_equal(mpb_store_open(f->other, 0, &s), MPB_EDB);
    char want[256];
    snprintf(want, sizeof want, "%s is not an mpbench database (it holds other"
             " tables; give a new file)", f->other);
    assert_string_equal(mpb_store_errmsg(s), want);
    mpb_store_close(s);

    /* Not a byte changed: not even the journal mode (WAL would be). */
    char *after = slurp(f->other, &after_len);
    assert_int_equal(after_len, before_len);
    assert_memory_equal(after, before, (size_t)before_len);
    free(before);
    free(after);
}

static void each_error_names_the_file_and_what_is_wrong(void **state)
{
    fixture *f = *state;
    mpb_store *s;
    char want[256];

    /* Text where a database should be. */
    FILE *fp = fopen(f->other, "w");
    fputs("not a database at all, just some text, long enough to look at\n", fp);
    fclose(fp);
    assert_int_equal(mpb_store_open(f->other, 0, &s), MPB_EDB);
    snprintf(want, sizeof want, "%s is not an mpbench database: not an SQLite "
             "file", f->other);
    assert_string_equal(mpb_store_errmsg(s), want);
    mpb_store_close(s);

    /* A database cut short: the first pages say more pages follow. */
    long len;
    char *whole = slurp(f->db, &len);
    assert_true(len > 8192);
    fp = fopen(f->other, "wb");
    fwrite(whole, 1, 4096, fp);
    fclose(fp);
    free(whole);
    assert_int_not_equal(mpb_store_open(f->other, 1, &s), MPB_OK);
    snprintf(want, sizeof want, "%s is damaged: ", f->other);
    assert_memory_equal(mpb_store_errmsg(s), want, strlen(want));
    mpb_store_close(s);

    /* An empty database is no report's input. */
    unlink(f->other);
    sqlite3 *db;
    assert_int_equal(sqlite3_open(f->other, &db), SQLITE_OK);
    sqlite3_close(db);
    assert_int_equal(mpb_store_open(f->other, 1, &s), MPB_EDB);
    snprintf(want, sizeof want, "%s is not an mpbench database", f->other);
    assert_string_equal(mpb_store_errmsg(s), want);
    mpb_store_close(s);
}

static void reading_leaves_no_wal_or_shm_behind(void **state)
{
    fixture *f = *state;
    mpb_store *s;
    assert_false(present(f->wal));
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    int64_t id;
    assert_int_equal(mpb_store_experiment_latest(s, &id), MPB_OK);
    mpb_store_close(s);
    assert_false(present(f->wal));
    assert_false(present(f->shm));
}

/* Read as a user who may write neither the file nor its folder. As root
 * (CI) that is a child turned into nobody; as anyone else, the folder made
 * read-only is enough. */
static void a_database_in_a_read_only_folder_is_read(void **state)
{
    fixture *f = *state;
    assert_int_equal(chmod(f->db, 0444), 0);
    assert_int_equal(chmod(f->dir, geteuid() == 0 ? 0755 : 0555), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0))
            _exit(3);
        mpb_store *s;
        int64_t id;
        int ok = mpb_store_open(f->db, 1, &s) == MPB_OK &&
                 mpb_store_experiment_latest(s, &id) == MPB_OK && id == 1;
        if (!ok)
            fprintf(stderr, "%s\n", mpb_store_errmsg(s));
        mpb_store_close(s);
        _exit(ok ? 0 : 1);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    /* Nothing of the reader's stays to keep the owner from writing. */
    assert_false(present(f->shm));
    assert_false(present(f->wal));
}

static int run_ids(void *ud, const mpb_run_row *row)
{
    ((int64_t *)ud)[row->repetition] = row->id;
    return 0;
}

static void exec_sql(const char *path, const char *sql)
{
    sqlite3 *db;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    char *msg = NULL;
    if (sqlite3_exec(db, sql, NULL, NULL, &msg) != SQLITE_OK)
        fail_msg("%s: %s", sql, msg);
    sqlite3_close(db);
}

static char *column_text(const char *path, const char *sql)
{
    sqlite3 *db;
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
    assert_int_equal(sqlite3_prepare_v2(db, sql, -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    const unsigned char *t = sqlite3_column_text(st, 0);
    char *out = strdup(t ? (const char *)t : "NULL");
    sqlite3_finalize(st);
    sqlite3_close(db);
    return out;
}

/*
 * A database made before runs.outcome, runs.in_time and
 * planner_configs.approach (the columns dropped, as an older mpbench
 * left it) gets them when a writer opens it: each finished run's outcome
 * by mpb_run_outcome() from what it kept, in_time 0 only where a claimed
 * run with a valid final stage was no success; the approach NULL. Its
 * runs keep their place, and a new run's outcome is written as usual.
 */
static void an_older_database_gets_its_runs_outcomes(void **state)
{
    fixture *f = *state;
    mpb_store *s;
    int64_t cfg, scene, query, ids[5];
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    /* status, claimed, final stage valid, success: verified, refused,
     * late, unclaimed valid, unclaimed. */
    static const struct { const char *status; int claimed, valid, success; }
        kinds[5] = {{"solved", 1, 1, 1}, {"solved", 1, 0, 0},
                    {"solved", 1, 1, 0}, {"failed", 0, 1, 0},
                    {"timeout", 0, 0, 0}};
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, 1, "p/a", "p", "a", "",
                                                  &cfg), MPB_OK);
    mpb_scene_info sc = {"s", "planar", "r", "r", "planar", "x", "x"};
    assert_int_equal(mpb_store_scene_add(s, 1, &sc, &scene), MPB_OK);
    mpb_query_info q = {"q", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    for (int i = 0; i < 6; i++)
        assert_int_equal(mpb_store_run_add(s, 1, cfg, query, i, i), MPB_OK);
    int64_t all[6];
    assert_int_equal(mpb_store_runs_unfinished(s, 1, run_ids, all), MPB_OK);
    memcpy(ids, all, sizeof ids);
    for (int i = 0; i < 5; i++) {
        char uid[16];
        snprintf(uid, sizeof uid, "u%d", i);
        assert_int_equal(mpb_store_run_sent(s, ids[i], uid, "p@h:1"), MPB_OK);
        mpb_stage_record st = {.name = "raw", .valid = kinds[i].valid,
                               .verdict = kinds[i].valid ? "valid"
                                                         : "collision",
                               .verdict_segment = -1};
        mpb_run_record rec = {
            .run_id = ids[i], .attempt_id = uid, .planner_id = "p@h:1",
            .status = kinds[i].status, .message = "",
            .claimed_success = kinds[i].claimed, .success = kinds[i].success,
            .late = i == 2, .time_total = 1, .time_raw = 1, .time_other = 0,
            .wall_time = 1, .num_stages = 1, .stages = &st,
            .verify_time = 0.1, .memory = 1,
        };
        assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
    }
    mpb_store_close(s);
    char *now = column_text(f->db, "SELECT group_concat(outcome || ':' || "
                            "in_time, ' ') FROM (SELECT outcome, in_time "
                            "FROM runs WHERE state = 'done' ORDER BY id)");
    static const char want[] = "verified:1 refused:1 late:0 "
                               "unclaimed_valid:1 unclaimed:1";
    assert_string_equal(now, want);
    free(now);

    exec_sql(f->db, "DROP VIEW results; DROP VIEW run_summary;"
             " ALTER TABLE runs DROP COLUMN outcome;"
             " ALTER TABLE runs DROP COLUMN in_time;"
             " ALTER TABLE planner_configs DROP COLUMN approach");
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    mpb_store_close(s);
    now = column_text(f->db, "SELECT group_concat(outcome || ':' || "
                      "in_time, ' ') FROM (SELECT outcome, in_time FROM runs"
                      " WHERE state = 'done' ORDER BY id)");
    assert_string_equal(now, want);
    free(now);
    now = column_text(f->db, "SELECT count(*) || ' ' || count(outcome) || "
                      "' ' || coalesce(max(p.approach), 'none') FROM runs r"
                      " JOIN planner_configs p ON p.id = r.planner_config_id");
    assert_string_equal(now, "6 5 none");     /* the pending run has none */
    free(now);
    now = column_text(f->db, "SELECT group_concat(outcome, ' ') FROM results");
    assert_string_equal(now, "verified refused late unclaimed_valid "
                             "unclaimed");
    free(now);
}

typedef struct sets_seen {
    char text[512];
} sets_seen;

static int on_scene_set(void *ud, const mpb_scene_row *row)
{
    sets_seen *x = ud;
    size_t n = strlen(x->text);
    snprintf(x->text + n, sizeof x->text - n, "%s%s=%s", n ? " " : "",
             row->name, row->problem_set);
    return 0;
}

/*
 * Problem sets (scenes.problem_set): a scene is added in its default set
 * (its name before the last '/', else the name), an experiment file's
 * `set:` is written over it, and a database made before the column is
 * read with the default sets and, opened by a writer, gets the column
 * filled by the same rule (in SQL, here checked against the C one on
 * names with several '/', a trailing one, UTF-8) and the run_summary
 * view.
 */
/* A run not yet done as mpb_store_runs_unfinished() gives it. */
typedef struct unfinished {
    int     n;
    int64_t id[4];
    int     sent[4];
    char    attempt[4][40];
} unfinished;

static int collect_unfinished(void *ud, const mpb_run_row *row)
{
    unfinished *u = ud;
    if (u->n < 4) {
        u->id[u->n] = row->id;
        u->sent[u->n] = row->sent;
        snprintf(u->attempt[u->n], sizeof u->attempt[u->n], "%s",
                 row->attempt_id != NULL ? row->attempt_id : "NULL");
    }
    u->n++;
    return 0;
}

/*
 * A database made before attempt_id (its attempts' ids in runs.run_uid,
 * as an older mpbench left it) opens for writing with the column renamed
 * and every value kept: its run in flight resumes under its attempt id,
 * the other still pending, and the run finishes under that id alone.
 */
static void an_older_database_gets_attempt_id(void **state)
{
    fixture *f = *state;
    mpb_store *s;
    int64_t cfg, scene, query, ids[2];
    static const char uid[] = "0123456789abcdef0123456789abcdef";
    static const char *const joints[] = {"j"};
    static const double zero[] = {0.0}, one[] = {1.0};
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    assert_int_equal(mpb_store_planner_config_add(s, 1, "p/a", "p", "a", "",
                                                  &cfg), MPB_OK);
    mpb_scene_info sc = {"s", "planar", "r", "r", "planar", "x", "x"};
    assert_int_equal(mpb_store_scene_add(s, 1, &sc, &scene), MPB_OK);
    mpb_query_info q = {"q", 1, joints, zero, MPB_GOAL_JOINTS, one, 0.01,
                        NULL, NULL};
    assert_int_equal(mpb_store_query_add(s, scene, &q, &query), MPB_OK);
    for (int i = 0; i < 2; i++)
        assert_int_equal(mpb_store_run_add(s, 1, cfg, query, i, i), MPB_OK);
    assert_int_equal(mpb_store_runs_unfinished(s, 1, run_ids, ids), MPB_OK);
    assert_int_equal(mpb_store_run_sent(s, ids[0], uid, "p@h:1"), MPB_OK);
    mpb_store_close(s);

    exec_sql(f->db, "ALTER TABLE runs RENAME COLUMN attempt_id TO run_uid");
    char *now = column_text(f->db, "SELECT count(run_uid) FROM runs");
    assert_string_equal(now, "1");           /* as an older mpbench left it */
    free(now);

    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    unfinished u = {0};
    assert_int_equal(mpb_store_runs_unfinished(s, 1, collect_unfinished, &u),
                     MPB_OK);
    assert_int_equal(u.n, 2);
    assert_true(u.id[0] == ids[0] && u.sent[0] == 1);
    assert_string_equal(u.attempt[0], uid);
    assert_true(u.id[1] == ids[1] && u.sent[1] == 0);
    assert_string_equal(u.attempt[1], "NULL");
    mpb_stage_record st = {.name = "raw", .valid = 1, .verdict = "valid",
                           .verdict_segment = -1};
    mpb_run_record rec = {
        .run_id = ids[0], .attempt_id = "fedcba9876543210fedcba9876543210",
        .planner_id = "p@h:1", .status = "solved", .message = "",
        .claimed_success = 1, .success = 1, .time_total = 1, .time_raw = 1,
        .wall_time = 1, .num_stages = 1, .stages = &st, .verify_time = 0.1,
        .memory = 1,
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_ENOTFOUND);
    rec.attempt_id = uid;
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
    mpb_store_close(s);
    now = column_text(f->db, "SELECT group_concat(coalesce(attempt_id, 'NULL')"
                      " || ' ' || state, ', ') FROM (SELECT * FROM runs"
                      " ORDER BY id)");
    char want[96];
    snprintf(want, sizeof want, "%s done, NULL pending", uid);
    assert_string_equal(now, want);
    free(now);
    /* Opened again: nothing left to rename, nothing changed. */
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    mpb_store_close(s);
    now = column_text(f->db, "SELECT count(attempt_id) FROM runs");
    assert_string_equal(now, "1");
    free(now);
}

static void an_older_database_gets_its_problem_sets(void **state)
{
    fixture *f = *state;
    static const char *const names[] = {"box_panda/0001", "KITCHEN",
                                        "a/b/c", "\u53f0\u6240/7\u00e4",
                                        "x/", "mine"};
    static const char want[] =
        "box_panda/0001=box_panda KITCHEN=KITCHEN a/b/c=a/b "
        "\u53f0\u6240/7\u00e4=\u53f0\u6240 x/=x mine=mine";
    mpb_store *s;
    int64_t scene = 0;
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        mpb_scene_info sc = {names[i], "planar", "r", "r", "planar", "x", "x"};
        assert_int_equal(mpb_store_scene_add(s, 1, &sc, &scene), MPB_OK);
    }
    assert_int_equal(mpb_store_scene_set_problem_set(s, scene, "shelves"),
                     MPB_OK);
    assert_int_equal(mpb_store_scene_set_problem_set(s, scene + 1, "x"),
                     MPB_ENOTFOUND);
    sets_seen seen = {""};
    assert_int_equal(mpb_store_scenes(s, 1, on_scene_set, &seen), MPB_OK);
    char want_set[600];
    snprintf(want_set, sizeof want_set, "%.*s=shelves",
             (int)(sizeof want - 1 - strlen("=mine")), want);
    assert_string_equal(seen.text, want_set);
    mpb_store_close(s);

    /* As an older mpbench left it. */
    exec_sql(f->db, "DROP VIEW run_summary;"
             " ALTER TABLE scenes DROP COLUMN problem_set");
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    seen.text[0] = '\0';
    assert_int_equal(mpb_store_scenes(s, 1, on_scene_set, &seen), MPB_OK);
    assert_string_equal(seen.text, want);
    mpb_store_close(s);

    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    mpb_store_close(s);
    char *now = column_text(f->db, "SELECT group_concat(name || '=' || "
                            "problem_set, ' ') FROM (SELECT name, problem_set"
                            " FROM scenes ORDER BY id)");
    assert_string_equal(now, want);
    free(now);
    now = column_text(f->db, "SELECT count(*) FROM sqlite_master WHERE "
                      "type = 'view' AND name = 'run_summary'");
    assert_string_equal(now, "1");
    free(now);
}

typedef struct seen_walk {
    char text[512];
} seen_walk;

static int on_seen_scene(void *ud, const mpb_scene_row *row)
{
    seen_walk *x = ud;
    size_t n = strlen(x->text);
    snprintf(x->text + n, sizeof x->text - n, "%s%s:%s/%s/%s/%s", n ? " " : "",
             row->name, row->seen_format ? row->seen_format : "-",
             row->seen_hash ? row->seen_hash : "-",
             row->seen ? row->seen : "-", row->seen_how ? row->seen_how : "-");
    return 0;
}

static int on_judgement(void *ud, const mpb_seen_judgement *j)
{
    seen_walk *x = ud;
    size_t n = strlen(x->text);
    snprintf(x->text + n, sizeof x->text - n, "%s%lld:%d%d%d:%s:%s",
             n ? " " : "", (long long)j->run_id, j->claimed, j->success,
             j->seen_success, j->verdict ? j->verdict : "-",
             j->seen_verdict ? j->seen_verdict : "-");
    return 0;
}

/*
 * Seen scenes (scenes.seen*, runs.seen_*): a scene keeps what its
 * planners were given beside itself, a run its judgement on that beside
 * the truth's, and only runs so judged are walked; a database made before
 * the columns reads as having none and, opened by a writer, gets them.
 */
static void a_scene_keeps_what_its_planners_saw(void **state)
{
    fixture *f = *state;
    mpb_store *s;
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    int64_t truth = test_store_scene(s, 1, "truth", "h-t", "t");
    int64_t plain = test_store_scene(s, 1, "plain", "h-p", "p");
    mpb_seen_scene seen = {"planar", "h-s", "s", "given: s.scene"};
    assert_int_equal(mpb_store_scene_set_seen(s, truth, &seen), MPB_OK);
    assert_int_equal(mpb_store_scene_set_seen(s, plain + 1, &seen),
                     MPB_ENOTFOUND);
    mpb_seen_scene none = {"planar", NULL, "s", NULL};
    assert_int_equal(mpb_store_scene_set_seen(s, truth, &none), MPB_EINVAL);
    seen_walk w = {""};
    assert_int_equal(mpb_store_scenes(s, 1, on_seen_scene, &w), MPB_OK);
    assert_string_equal(w.text, "truth:planar/h-s/s/given: s.scene plain:-/-/-/-");

    int64_t cfg = test_store_config(s, 1, "p", "a", "");
    int64_t qt = test_store_query(s, truth, "q"), qp = test_store_query(s, plain, "q");
    int64_t r1 = test_store_run(s, 1, cfg, qt, 0, 1);
    int64_t r2 = test_store_run(s, 1, cfg, qp, 0, 2);
    assert_int_equal(mpb_store_run_sent(s, r1, "u1", "p-1"), MPB_OK);
    mpb_stage_record st = {.name = "raw", .valid = 0, .verdict = "collision",
                           .verdict_detail = "touches post",
                           .verdict_segment = 0};
    mpb_run_record rec = {
        .run_id = r1, .attempt_id = "u1", .planner_id = "p-1",
        .status = "solved", .claimed_success = 1, .success = 0,
        .time_total = 0.5, .time_raw = 0.5, .num_stages = 1, .stages = &st,
        .verify_time = NAN, .memory = NAN, .seen_verdict = "valid",
        .seen_detail = "valid", .seen_success = 1,
    };
    assert_int_equal(mpb_store_run_finish(s, &rec), MPB_OK);
    test_store_finish(s, r2, 1, 0.5, 1.0);
    w.text[0] = '\0';
    assert_int_equal(mpb_store_seen_judgements(s, 1, on_judgement, &w), MPB_OK);
    char want[64];
    snprintf(want, sizeof want, "%lld:101:collision:valid", (long long)r1);
    assert_string_equal(w.text, want);
    mpb_store_close(s);
    char *now = column_text(f->db, "SELECT count(*) FROM runs WHERE seen_success IS NULL");
    assert_string_equal(now, "1");
    free(now);

    /* As an older mpbench left it. */
    exec_sql(f->db, "ALTER TABLE scenes DROP COLUMN seen_format;"
             " ALTER TABLE scenes DROP COLUMN seen_hash;"
             " ALTER TABLE scenes DROP COLUMN seen;"
             " ALTER TABLE scenes DROP COLUMN seen_how;"
             " ALTER TABLE runs DROP COLUMN seen_verdict;"
             " ALTER TABLE runs DROP COLUMN seen_detail;"
             " ALTER TABLE runs DROP COLUMN seen_success");
    assert_int_equal(mpb_store_open(f->db, 1, &s), MPB_OK);
    w.text[0] = '\0';
    assert_int_equal(mpb_store_scenes(s, 1, on_seen_scene, &w), MPB_OK);
    assert_string_equal(w.text, "truth:-/-/-/- plain:-/-/-/-");
    w.text[0] = '\0';
    assert_int_equal(mpb_store_seen_judgements(s, 1, on_judgement, &w), MPB_OK);
    assert_string_equal(w.text, "");
    mpb_store_close(s);
    assert_int_equal(mpb_store_open(f->db, 0, &s), MPB_OK);
    mpb_store_close(s);
    now = column_text(f->db, "SELECT count(*) FROM pragma_table_info('runs')"
                      " WHERE name LIKE 'seen_%'");
    assert_string_equal(now, "3");
    free(now);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(another_programs_database_is_refused_untouched, setup, teardown),
        cmocka_unit_test_setup_teardown(each_error_names_the_file_and_what_is_wrong, setup, teardown),
        cmocka_unit_test_setup_teardown(reading_leaves_no_wal_or_shm_behind, setup, teardown),
        cmocka_unit_test_setup_teardown(a_database_in_a_read_only_folder_is_read, setup, teardown),
        cmocka_unit_test_setup_teardown(an_older_database_gets_its_runs_outcomes, setup, teardown),
        cmocka_unit_test_setup_teardown(an_older_database_gets_its_problem_sets, setup, teardown),
        cmocka_unit_test_setup_teardown(an_older_database_gets_attempt_id, setup, teardown),
        cmocka_unit_test_setup_teardown(a_scene_keeps_what_its_planners_saw, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
