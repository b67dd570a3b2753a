/* test_store_open.c - opening the database: what is refused and why, and
 * that reading leaves nothing behind, not even where nothing can be
 * written. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(another_programs_database_is_refused_untouched, setup, teardown),
        cmocka_unit_test_setup_teardown(each_error_names_the_file_and_what_is_wrong, setup, teardown),
        cmocka_unit_test_setup_teardown(reading_leaves_no_wal_or_shm_behind, setup, teardown),
        cmocka_unit_test_setup_teardown(a_database_in_a_read_only_folder_is_read, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
