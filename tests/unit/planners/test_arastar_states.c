/*
 * test_arastar_states.c - the ARA* planner's state table: one id per
 * lattice point, found again, and a hard bound on the number of states.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "state_table.h"

static void test_one_id_per_point(void **state)
{
    (void)state;
    ara_state_table t;
    assert_int_equal(ara_states_init(&t, 3, 100000), 0);
    int added, n = 0;
    /* A 21^3 cube of points around the origin, negative values included. */
    for (int x = -10; x <= 10; x++)
        for (int y = -10; y <= 10; y++)
            for (int z = -10; z <= 10; z++) {
                int16_t c[3] = {(int16_t)x, (int16_t)y, (int16_t)z};
                int id = ara_states_get(&t, c, &added);
                assert_int_equal(id, n++);
                assert_int_equal(added, 1);
                assert_true(isinf(t.states[id].g));
                assert_int_equal(t.states[id].parent, -1);
            }
    for (int x = -10; x <= 10; x++) {
        int16_t c[3] = {(int16_t)x, 3, -7};
        int id = ara_states_get(&t, c, &added);
        assert_int_equal(added, 0);
        assert_int_equal(ara_states_find(&t, c), id);
        const int16_t *back = ara_states_coords(&t, id);
        assert_int_equal(back[0], x);
        assert_int_equal(back[1], 3);
        assert_int_equal(back[2], -7);
    }
    int16_t outside[3] = {11, 0, 0};
    assert_int_equal(ara_states_find(&t, outside), -1);
    assert_int_equal(t.size, 21 * 21 * 21);
    ara_states_free(&t);
}

static void test_bounded(void **state)
{
    (void)state;
    ara_state_table t;
    assert_int_equal(ara_states_init(&t, 2, 5000), 0);
    int added;
    for (int i = 0; i < 5000; i++) {
        int16_t c[2] = {(int16_t)i, (int16_t)-i};
        assert_int_equal(ara_states_get(&t, c, &added), i);
    }
    int16_t more[2] = {-1, 1};
    assert_int_equal(ara_states_get(&t, more, &added), -1);   /* full */
    int16_t old[2] = {17, -17};
    assert_int_equal(ara_states_get(&t, old, &added), 17);    /* still found */
    assert_int_equal(added, 0);
    ara_states_free(&t);
    assert_int_equal(ara_states_init(&t, 0, 10), -1);
    ara_states_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_id_per_point),
        cmocka_unit_test(test_bounded),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
