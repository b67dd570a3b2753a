/*
 * test_arastar_heap.c - the ARA* planner's OPEN list: items leave in
 * (f, h, id) order, a changed key moves its item, nothing is lost.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "heap.h"

static void test_pops_in_key_order(void **state)
{
    (void)state;
    ara_heap hp;
    ara_heap_init(&hp);
    uint32_t x = 12345;
    for (int id = 0; id < 5000; id++) {
        x = x * 1103515245u + 12345u;            /* keys with many ties */
        assert_int_equal(ara_heap_push(&hp, id, (double)(x >> 24) / 7,
                                       (double)((x >> 8) & 3)), 0);
    }
    assert_int_equal(hp.size, 5000);
    ara_heap_item prev = ara_heap_pop(&hp);
    int popped = 1;
    while (hp.size > 0) {
        ara_heap_item it = ara_heap_pop(&hp);
        assert_true(prev.f < it.f || (prev.f == it.f && (prev.h < it.h ||
                    (prev.h == it.h && prev.id < it.id))));
        assert_false(ara_heap_contains(&hp, it.id));
        prev = it;
        popped++;
    }
    assert_int_equal(popped, 5000);
    assert_null(ara_heap_top(&hp));
    ara_heap_free(&hp);
}

static void test_ties_and_decrease_key(void **state)
{
    (void)state;
    ara_heap hp;
    ara_heap_init(&hp);
    ara_heap_push(&hp, 7, 10.0, 2.0);
    ara_heap_push(&hp, 3, 10.0, 2.0);
    ara_heap_push(&hp, 9, 10.0, 1.0);
    ara_heap_push(&hp, 1, 20.0, 0.0);
    /* Equal f: the smaller h first, then the smaller id. */
    assert_int_equal(ara_heap_top(&hp)->id, 9);
    /* A better key for 1 moves it to the front, without a second copy. */
    ara_heap_push(&hp, 1, 5.0, 0.0);
    assert_int_equal(hp.size, 4);
    assert_int_equal(ara_heap_pop(&hp).id, 1);
    /* A worse key moves an item back. */
    ara_heap_push(&hp, 9, 30.0, 1.0);
    assert_int_equal(ara_heap_pop(&hp).id, 3);
    assert_int_equal(ara_heap_pop(&hp).id, 7);
    ara_heap_item last = ara_heap_pop(&hp);
    assert_int_equal(last.id, 9);
    assert_true(last.f == 30.0);
    ara_heap_free(&hp);
}

static void test_clear_keeps_working(void **state)
{
    (void)state;
    ara_heap hp;
    ara_heap_init(&hp);
    for (int id = 0; id < 100; id++)
        ara_heap_push(&hp, id, 100.0 - id, 0.0);
    ara_heap_clear(&hp);
    assert_int_equal(hp.size, 0);
    for (int id = 0; id < 100; id++)
        assert_false(ara_heap_contains(&hp, id));
    ara_heap_push(&hp, 42, 1.0, 0.0);
    assert_true(ara_heap_contains(&hp, 42));
    assert_int_equal(ara_heap_pop(&hp).id, 42);
    assert_int_equal(ara_heap_push(&hp, -1, 0.0, 0.0), -1);
    ara_heap_free(&hp);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pops_in_key_order),
        cmocka_unit_test(test_ties_and_decrease_key),
        cmocka_unit_test(test_clear_keeps_working),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
