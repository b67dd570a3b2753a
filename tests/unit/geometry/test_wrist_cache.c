/*
 * test_wrist_cache.c - the wrist tables' cache on disk (wrist_cache.h),
 * on the Panda with its SRDF and meshes (tools/robot_data.sh; skipped
 * when they are not fetched): a second process (here: a second world
 * after the process-wide cache is emptied) reads the tables instead of
 * building them, and they answer exactly as the built ones at many
 * random joint values, as do the world's verdicts. A corrupt, truncated
 * or foreign file, one whose checksum is right but whose tree is not,
 * and a directory that cannot be made, all mean a build with the same
 * answers, never a failed world. Processes writing one file at once
 * leave one whole copy, and a reader meanwhile gets a miss or a whole
 * payload. Every cache here is a fresh directory under /tmp; the user's
 * own is never touched.
 */
#include <dirent.h>
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "mpbench/mpbench.h"
#include "model/world_provider.h"
#include "geometry/wrist_cache.h"
#include "geometry/wrist_table.h"
#include "test_files.h"

#define SRC MPB_TEST_DATA "/../../.."
#define PANDA SRC "/.cache/robots/vamp-planner-0.6.4/panda"
#define NJ 7
#define SAMPLES 20000   /* joint values a table is asked about */
#define STATES 500      /* states the world is asked about */

static const char *const joints[NJ] = {
    "panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4",
    "panda_joint5", "panda_joint6", "panda_joint7"};

static const char empty_scene[] = "empty\n.\n";

static int have_panda(void)
{
    return access(PANDA "/panda.urdf", R_OK) == 0;
}

/* The Panda in an empty scene, its tables from the disk cache in dir or
 * built: a fresh process's first world. */
static mpb_world *open_panda(const char *dir)
{
    char root[4096], urdf[4200], srdf[4200];
    assert_non_null(realpath(PANDA, root));
    snprintf(urdf, sizeof urdf, "%s/panda.urdf", root);
    snprintf(srdf, sizeof srdf, "%s/panda.srdf", root);
    strcat(root, "/");
    assert_int_equal(setenv("MPB_CACHE_DIR", dir, 1), 0);
    mpb__wrist_forget();
    char *robot = test_read_robot(urdf, srdf);
    mpb_world *w = NULL;
    char err[512];
    int rc = mpb_world_open_group_in("urdf", robot, root, "moveit-scene",
                                     empty_scene, joints, NJ, &w, err, sizeof err);
    free(robot);
    if (rc != MPB_OK)
        fail_msg("%s", err);
    assert_true(mpb__urdf_num_wrists(w) > 0);
    return w;
}

static double rnd(uint64_t *x)
{
    *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*x >> 11) / 9007199254740992.0;
}

/* What a world's tables and verdicts say: per table SAMPLES answers at
 * joint values over the range and a little beyond it, then STATES
 * verdicts. The same seed each time. The caller frees. */
static unsigned char *answers(mpb_world *w, size_t *len)
{
    int n = mpb__urdf_num_wrists(w);
    *len = (size_t)n * SAMPLES + STATES;
    unsigned char *a = malloc(*len), *p = a;
    assert_non_null(a);
    uint64_t x = 11;
    for (int i = 0; i < n; i++) {
        int near, far, jt[2];
        const mpb__wrist_table *t;
        double lo[2] = {0, 0}, hi[2] = {0, 0};
        assert_int_equal(mpb__urdf_wrist(w, i, &near, &far, jt, &t), MPB_OK);
        for (int k = 0; k < 2; k++)
            if (jt[k] >= 0)
                mpb_world_joint_limits(w, jt[k], &lo[k], &hi[k]);
        for (int s = 0; s < SAMPLES; s++) {
            double v0 = lo[0] - 0.01 + rnd(&x) * (hi[0] - lo[0] + 0.02);
            double v1 = lo[1] - 0.01 + rnd(&x) * (hi[1] - lo[1] + 0.02);
            *p++ = (unsigned char)mpb__wrist_table_apart(t, v0, v1);
        }
    }
    for (int s = 0; s < STATES; s++) {
        double q[NJ];
        for (int j = 0; j < NJ; j++) {
            double lo, hi;
            mpb_world_joint_limits(w, j, &lo, &hi);
            q[j] = lo + rnd(&x) * (hi - lo);
        }
        *p++ = (unsigned char)mpb_world_in_collision(w, q);
    }
    return a;
}

/*
 * The tables built once, into a directory under /tmp, with the answers
 * of that first world; each test gets a copy of that directory to spoil.
 */
typedef struct fixture {
    char           master[64];
    char           dir[64];
    char           cache[128];      /* dir/wrist: where the files go */
    unsigned char *built;
    size_t         len;
    int            tables;
} fixture;

static void remove_dir(const char *dir)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

static int group_setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    *state = f;
    if (!have_panda())
        return 0;
    strcpy(f->master, "/tmp/mpb-wrist-cache-XXXXXX");
    assert_non_null(mkdtemp(f->master));
    long builds = mpb__wrist_builds(), loads = mpb__wrist_loads();
    mpb_world *w = open_panda(f->master);
    f->tables = mpb__urdf_num_wrists(w);
    assert_int_equal(mpb__wrist_builds() - builds, f->tables);
    assert_int_equal(mpb__wrist_loads(), loads);
    f->built = answers(w, &f->len);
    mpb_world_close(w);
    return 0;
}

static int group_teardown(void **state)
{
    fixture *f = *state;
    if (f->master[0])
        remove_dir(f->master);
    mpb__wrist_forget();
    free(f->built);
    free(f);
    return 0;
}

static int setup(void **state)
{
    fixture *f = *state;
    if (!f->master[0])
        return 0;
    char cmd[160];
    strcpy(f->dir, "/tmp/mpb-wrist-cache-XXXXXX");
    assert_non_null(mkdtemp(f->dir));
    snprintf(f->cache, sizeof f->cache, "%s/wrist", f->dir);
    snprintf(cmd, sizeof cmd, "cp -r '%s/wrist' '%s'", f->master, f->dir);
    assert_int_equal(system(cmd), 0);
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    if (f->dir[0])
        remove_dir(f->dir);
    f->dir[0] = '\0';
    return 0;
}

#define SKIP_WITHOUT_PANDA()                                                  \
    do {                                                                      \
        if (!have_panda()) {                                                  \
            print_message("Panda data not fetched (tools/robot_data.sh): "  \
                          "skipped\n");                                       \
            skip();                                                           \
        }                                                                     \
    } while (0)

static long file_size(const char *path)
{
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    fclose(fp);
    return n;
}

/* Smaller files first (cheaper tables to build again), then by name. */
static int by_size(const void *a, const void *b)
{
    long d = file_size(a) - file_size(b);
    return d < 0 ? -1 : d > 0 ? 1 : strcmp(a, b);
}

/* The cache's files, smallest first, into names (at most 16). */
static int table_files(const fixture *f, char names[16][256])
{
    DIR *d = opendir(f->cache);
    assert_non_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        size_t l = strlen(e->d_name);
        if (e->d_name[0] == '.' || l < 5 || strcmp(e->d_name + l - 4, ".tbl"))
            continue;
        assert_true(n < 16);
        /* A name that does not fit would name another file: refuse it. */
        int w = snprintf(names[n++], 256, "%.127s/%.120s", f->cache, e->d_name);
        assert_true(w > 0 && w < 256);
    }
    closedir(d);
    qsort(names, (size_t)n, 256, by_size);
    return n;
}

/* A world from dir: `builds` tables built, the rest read, and the
 * answers of the tables that were built when the fixture began. */
static void reopen_expect(const fixture *f, const char *dir, int builds)
{
    long b0 = mpb__wrist_builds(), l0 = mpb__wrist_loads();
    mpb_world *w = open_panda(dir);
    assert_int_equal(mpb__wrist_builds() - b0, builds);
    assert_int_equal(mpb__wrist_loads() - l0, f->tables - builds);
    int cached = 0;
    for (int i = 0; i < mpb__urdf_num_wrists(w); i++) {
        int near, far, jt[2];
        const mpb__wrist_table *t;
        mpb__wrist_stats st;
        assert_int_equal(mpb__urdf_wrist(w, i, &near, &far, jt, &t), MPB_OK);
        mpb__wrist_table_stats(t, &st);
        cached += st.cached;
        assert_true(st.apart_leaves > 0);
    }
    assert_int_equal(cached, f->tables - builds);
    size_t len;
    unsigned char *a = answers(w, &len);
    assert_int_equal(len, f->len);
    assert_memory_equal(a, f->built, len);
    free(a);
    mpb_world_close(w);
}

static void a_second_process_reads_the_same_tables(void **state)
{
    fixture *f = *state;
    SKIP_WITHOUT_PANDA();
    char names[16][256];
    assert_int_equal(table_files(f, names), f->tables);
    reopen_expect(f, f->dir, 0);
    reopen_expect(f, f->dir, 0);
}

/* Overwrite n bytes of a file at offset at. */
static void poke(const char *path, long at, const void *bytes, size_t n)
{
    int fd = open(path, O_WRONLY);
    assert_true(fd >= 0);
    assert_int_equal(pwrite(fd, bytes, n, at), (ssize_t)n);
    close(fd);
}

/* One flipped bit in a payload, then in a header: that table is built
 * again, and written again, so that the next world reads it. */
static void a_corrupt_file_is_rebuilt(void **state)
{
    fixture *f = *state;
    SKIP_WITHOUT_PANDA();
    char names[16][256];
    int n = table_files(f, names);
    assert_true(n >= 2);
    unsigned char c;
    FILE *fp = fopen(names[0], "rb");
    long at = file_size(names[0]) - 3;
    fseek(fp, at, SEEK_SET);
    assert_int_equal(fread(&c, 1, 1, fp), 1);
    fclose(fp);
    c ^= 0x10;
    poke(names[0], at, &c, 1);
    reopen_expect(f, f->dir, 1);
    reopen_expect(f, f->dir, 0);
    poke(names[1], 0, "MPBWRIsT", 8);               /* magic */
    reopen_expect(f, f->dir, 1);
    uint32_t version = MPB__WRIST_CACHE_VERSION + 1;
    poke(names[1], 12, &version, 4);                /* another version */
    reopen_expect(f, f->dir, 1);
}

/* Cut short anywhere, emptied, or a byte too long: built again. */
static void a_truncated_file_is_rebuilt(void **state)
{
    fixture *f = *state;
    SKIP_WITHOUT_PANDA();
    char names[16][256];
    table_files(f, names);
    long size = file_size(names[0]);
    long cuts[] = {size - 1, size / 2, 96, 40, 0};
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        assert_int_equal(truncate(names[0], cuts[i]), 0);
        reopen_expect(f, f->dir, 1);
    }
    FILE *fp = fopen(names[0], "ab");
    fputc(0, fp);
    fclose(fp);
    reopen_expect(f, f->dir, 1);
}

/*
 * Another table's file under a table's name (another pair, another
 * robot: another key), a file in the other byte order, and one whose
 * header and checksum are right but whose tree is not (a node that is
 * its own child): all built again.
 */
static void a_foreign_file_is_rebuilt(void **state)
{
    fixture *f = *state;
    SKIP_WITHOUT_PANDA();
    char names[16][256];
    int n = table_files(f, names);
    char *other = test_read_file(names[1]);
    long size = file_size(names[1]);
    FILE *fp = fopen(names[0], "wb");
    assert_int_equal(fwrite(other, 1, (size_t)size, fp), (size_t)size);
    fclose(fp);
    free(other);
    reopen_expect(f, f->dir, 1);

    uint32_t swapped = 0x04030201u;
    poke(names[n - 1], 8, &swapped, 4);
    reopen_expect(f, f->dir, 1);

    /* The hash is the file's name; the key's length is in its header. */
    char *bytes = test_read_file(names[0]), hash[33];
    uint64_t key_len;
    memcpy(&key_len, bytes + 16, 8);
    memcpy(hash, strrchr(names[0], '/') + 1, 32);
    hash[32] = '\0';
    size = file_size(names[0]);
    unsigned char *payload = (unsigned char *)bytes + 96;
    uint32_t loop = 0u << 2 | 1u;           /* node 0's child: node 0 */
    memcpy(payload + 52, &loop, 4);
    assert_int_equal(mpb__wrist_cache_write(hash, (size_t)key_len, payload,
                                            (size_t)size - 96), MPB_OK);
    free(bytes);
    reopen_expect(f, f->dir, 1);
}

/* A cache that cannot be made (its parent is a file), and no HOME nor
 * any variable to find one: the tables are built, the world opens. */
static void no_cache_builds_in_memory(void **state)
{
    fixture *f = *state;
    SKIP_WITHOUT_PANDA();
    char file[128], dir[160];
    snprintf(file, sizeof file, "%s/a-file", f->dir);
    FILE *fp = fopen(file, "w");
    assert_non_null(fp);
    fclose(fp);
    snprintf(dir, sizeof dir, "%s/cache", file);
    reopen_expect(f, dir, f->tables);

    char *home = getenv("HOME") ? strdup(getenv("HOME")) : NULL;
    unsetenv("HOME");
    unsetenv("XDG_CACHE_HOME");
    reopen_expect(f, "", f->tables);
    if (home) {
        setenv("HOME", home, 1);
        free(home);
    }
}

/*
 * Four processes write the same table's file over and over, each its own
 * payload, while this one reads it: every read is a miss (before the
 * first rename) or one writer's payload, whole; never a mix, never torn.
 * No temporary file is left.
 */
static void concurrent_writers_leave_one_whole_file(void **state)
{
    (void)state;
    enum { WRITERS = 4, WRITES = 100, LEN = 65536 };
    char dir[] = "/tmp/mpb-wrist-cache-XXXXXX", hash[MPB__WRIST_HASH_SIZE];
    assert_non_null(mkdtemp(dir));
    assert_int_equal(setenv("MPB_CACHE_DIR", dir, 1), 0);
    mpb__wrist_cache_hash("key", 3, hash);
    pid_t pids[WRITERS];
    for (int k = 0; k < WRITERS; k++) {
        pids[k] = fork();
        assert_true(pids[k] >= 0);
        if (pids[k] == 0) {
            static unsigned char p[LEN];
            memset(p, 'a' + k, sizeof p);
            for (int i = 0; i < WRITES; i++)
                if (mpb__wrist_cache_write(hash, 3, p, sizeof p) != MPB_OK)
                    _exit(1);
            _exit(0);
        }
    }
    int reads = 0, bad = 0, live = WRITERS, failed = 0;
    while (live > 0) {
        unsigned char *p;
        size_t len;
        if (mpb__wrist_cache_read(hash, 3, &p, &len) == MPB_OK) {
            reads++;
            bad += len != LEN;
            for (size_t i = 1; i < len && !bad; i++)
                bad += p[i] != p[0];
            free(p);
        }
        int status;
        pid_t done = waitpid(-1, &status, WNOHANG);
        if (done > 0) {
            live--;
            failed += !WIFEXITED(status) || WEXITSTATUS(status) != 0;
        }
    }
    assert_int_equal(failed, 0);
    assert_int_equal(bad, 0);
    unsigned char *p;
    size_t len;
    assert_int_equal(mpb__wrist_cache_read(hash, 3, &p, &len), MPB_OK);
    free(p);
    /* A reader with the wrong key length misses. */
    assert_int_equal(mpb__wrist_cache_read(hash, 4, &p, &len), MPB_ENOTFOUND);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "test $(ls -A '%s/wrist' | wc -l) -eq 1", dir);
    assert_int_equal(system(cmd), 0);
    print_message("%d whole reads during the writes\n", reads);
    remove_dir(dir);
}

/* Where the cache is, by the variables. */
static void the_directory(void **state)
{
    (void)state;
    char buf[256], *home = getenv("HOME") ? strdup(getenv("HOME")) : NULL;
    setenv("MPB_CACHE_DIR", "/c", 1);
    setenv("XDG_CACHE_HOME", "/x", 1);
    setenv("HOME", "/h", 1);
    assert_int_equal(mpb__wrist_cache_dir(buf, sizeof buf, 0), MPB_OK);
    assert_string_equal(buf, "/c/wrist");
    setenv("MPB_CACHE_DIR", "", 1);
    assert_int_equal(mpb__wrist_cache_dir(buf, sizeof buf, 0), MPB_OK);
    assert_string_equal(buf, "/x/mpbench/wrist");
    setenv("XDG_CACHE_HOME", "relative", 1);
    assert_int_equal(mpb__wrist_cache_dir(buf, sizeof buf, 0), MPB_OK);
    assert_string_equal(buf, "/h/.cache/mpbench/wrist");
    unsetenv("HOME");
    assert_int_equal(mpb__wrist_cache_dir(buf, sizeof buf, 0), MPB_ENOTFOUND);
    assert_int_equal(mpb__wrist_cache_dir(buf, 8, 0), MPB_ENOTFOUND);
    unsetenv("XDG_CACHE_HOME");
    if (home) {
        setenv("HOME", home, 1);
        free(home);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_directory),
        cmocka_unit_test(concurrent_writers_leave_one_whole_file),
        cmocka_unit_test_setup_teardown(a_second_process_reads_the_same_tables,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(a_corrupt_file_is_rebuilt, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(a_truncated_file_is_rebuilt, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(a_foreign_file_is_rebuilt, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(no_cache_builds_in_memory, setup,
                                        teardown),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
