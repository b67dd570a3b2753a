/*
 * test_messages.c - a message is its .lcm file and one line: test_note_t
 * (tests/support/lcmtypes/test_note_t.lcm) and the line of
 * tests/support/test_note_messages.h, added to this program's own build of
 * the net layer (tests/CMakeLists.txt), get a receive-gate tag, a bounds
 * walk generated from the .lcm file, decoding and freeing, and a sealed
 * publish function, with nothing else written for them. Published over a
 * real LCM (its in-process memq provider), under a secret, it comes back
 * through the gate; cut short or with a count the bytes cannot hold, it
 * is refused before decoding.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <lcm/lcm.h>

#include "mpbench/mpbench.h"
#include "mpbench/link.h"
#include "mpb_test_note_t.h"
#include "test_tool.h"

static const double values[] = {1.5, -2.25, 3.0};
static char *tags[] = {"a", "bc"};

static mpb_test_note_t note(void)
{
    return (mpb_test_note_t){.utime = 7, .text = "hello", .num_values = 3,
                             .values = (double *)values, .num_tags = 2,
                             .tags = tags};
}

static void the_line_gives_a_tag_and_a_name(void **state)
{
    (void)state;
    assert_int_equal(MPB_WIRE_TEST_NOTE + 1, MPB_WIRE_COUNT);
    assert_string_equal(mpb_wire_type_name(MPB_WIRE_TEST_NOTE), "test_note_t");
    assert_string_equal(mpb_wire_type_name(MPB_WIRE_PLAN_REQUEST),
                        "plan_request_t");
    assert_string_equal(mpb_wire_channel(MPB_WIRE_TEST_NOTE), "MPB_TEST_NOTE");
    assert_null(mpb_wire_channel(MPB_WIRE_COUNT));
}

/* Its encoding passes the generated walk; every shorter or longer one,
 * and one whose count asks for more values than the bytes hold, fail. */
static void its_walk_is_generated_from_the_lcm_file(void **state)
{
    (void)state;
    mpb_test_note_t m = note();
    int n = mpb_test_note_t_encoded_size(&m);
    unsigned char *b = calloc((size_t)n + 1, 1);
    assert_int_equal(mpb_test_note_t_encode(b, 0, n, &m), n);
    char why[160];
    assert_true(mpb_wire_check(MPB_WIRE_TEST_NOTE, b, (size_t)n, why, sizeof why));
    for (int k = 0; k < n; k++)
        assert_false(mpb_wire_check(MPB_WIRE_TEST_NOTE, b, (size_t)k, NULL, 0));
    assert_false(mpb_wire_check(MPB_WIRE_TEST_NOTE, b, (size_t)n + 1, NULL, 0));
    /* another message's bytes are not a note */
    assert_false(mpb_wire_check(MPB_WIRE_RUN_ACK, b, (size_t)n, why, sizeof why));
    assert_non_null(strstr(why, "fingerprint"));
    /* num_values, after fingerprint 8, utime 8 and "hello" 4 + 6 */
    b[26] = 0x7f;
    b[27] = 0xff;
    assert_false(mpb_wire_check(MPB_WIRE_TEST_NOTE, b, (size_t)n, why, sizeof why));
    assert_non_null(strstr(why, "array longer than the message"));
    b[26] = 0xff;
    assert_false(mpb_wire_check(MPB_WIRE_TEST_NOTE, b, (size_t)n, why, sizeof why));
    assert_non_null(strstr(why, "negative array length"));
    free(b);
}

typedef struct got {
    mpb_auth *auth;
    int       count;
    mpb_test_note_t m;
} got;

static void on_note(const lcm_recv_buf_t *rbuf, const char *channel, void *ud)
{
    got *g = ud;
    mpb_received r;
    if (mpb_receive(g->auth, MPB_RECEIVE_FRESH | MPB_RECEIVE_UNPROVEN,
                    MPB_WIRE_TEST_NOTE, channel,
                    rbuf->data, rbuf->data_size, &g->m, &r) == MPB_OK)
        g->count++;
}

/* mpb_publish_note() seals it; the gate opens and decodes it, and
 * mpb_receive_done() frees it. */
static void it_is_published_and_received(void **state)
{
    (void)state;
    char dir[64], path[128], err[200];
    test_make_dir(dir, sizeof dir, "messages");
    snprintf(path, sizeof path, "%s/secret", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("a secret of thirty-two bytes or more\n", f);
    assert_int_equal(fclose(f), 0);
    mpb_auth *sender = NULL, *receiver = NULL;
    assert_int_equal(mpb_auth_open(path, &sender, err, sizeof err), MPB_OK);
    assert_int_equal(mpb_auth_open(path, &receiver, err, sizeof err), MPB_OK);
    lcm_t *lcm = lcm_create("memq://");
    assert_non_null(lcm);
    got g = {.auth = receiver};
    lcm_subscribe(lcm, "MPB_TEST_NOTE", on_note, &g);
    mpb_test_note_t m = note();
    assert_int_equal(mpb_publish_note(lcm, sender, 0, "MPB_TEST_NOTE", &m), MPB_OK);
    assert_int_equal(lcm_handle_timeout(lcm, 1000), 1);
    assert_int_equal(g.count, 1);
    assert_string_equal(g.m.text, "hello");
    assert_int_equal(g.m.num_values, 3);
    assert_true(g.m.values[1] == -2.25);
    assert_string_equal(g.m.tags[1], "bc");
    mpb_receive_done(MPB_WIRE_TEST_NOTE, &g.m);
    lcm_destroy(lcm);
    mpb_auth_close(sender);
    mpb_auth_close(receiver);
    test_remove_dir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_line_gives_a_tag_and_a_name),
        cmocka_unit_test(its_walk_is_generated_from_the_lcm_file),
        cmocka_unit_test(it_is_published_and_received),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
