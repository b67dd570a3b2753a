/*
 * lcm_filter_check.c - mpb-test-lcm-filter: what a socket filter from
 * mpb_lcm_create() lets through, over real UDP multicast (run it in a
 * private network namespace: tests/integration/test_lcm_filter.sh).
 *
 * Two listeners subscribe to every channel (".*"): one made by
 * mpb_lcm_create() to keep KEEP_1 and KEEP_TWO, one by
 * lcm_create() before it. A third instance publishes short messages
 * on kept channels, on channels that differ from them by a byte or by
 * length, and long (fragmented) ones. Prints, per listener, how many
 * messages arrived on each channel: "filtered KEEP_1 2".
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>

#include <lcm/lcm.h>

#include "mpbench/mpbench.h"

#define URL "udpm://239.255.76.67:7667?ttl=0"

static const char *const sent[] = {
    "KEEP_1", "KEEP_TWO", "DROP_ME", "KEEP_1X", "KEEP_", "KEEP_TWP", "K",
};
#define NSENT (int)(sizeof sent / sizeof sent[0])

typedef struct tally {
    const char *who;
    char channel[16][32];
    int count[16], n;
} tally;

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel,
                       void *user)
{
    tally *t = user;
    char key[32];
    snprintf(key, sizeof key, "%s%s", channel, rbuf->data_size > 10000 ? "+big" : "");
    for (int i = 0; i < t->n; i++)
        if (strcmp(t->channel[i], key) == 0) {
            t->count[i]++;
            return;
        }
    if (t->n < 16) {
        snprintf(t->channel[t->n], sizeof t->channel[t->n], "%s", key);
        t->count[t->n++] = 1;
    }
}

/* Handle what lcm has for up to ms milliseconds. */
static void drain(lcm_t *lcm, int ms)
{
    int fd = lcm_get_fileno(lcm);
    for (;;) {
        fd_set set;
        struct timeval tv = {0, ms * 1000};
        FD_ZERO(&set);
        FD_SET(fd, &set);
        if (select(fd + 1, &set, NULL, NULL, &tv) <= 0)
            return;
        lcm_handle(lcm);
    }
}

int main(void)
{
    static const char *const keep[] = {"KEEP_1", "KEEP_TWO"};
    static char big[100000];
    tally plain = {.who = "plain"}, filtered = {.who = "filtered"};

    int on = -1;
    lcm_t *a = lcm_create(URL);         /* unfiltered, made first */
    lcm_t *b = mpb_lcm_create(URL, keep, 2, &on);
    if (a == NULL || b == NULL) {
        fprintf(stderr, "mpb-test-lcm-filter: no LCM at %s\n", URL);
        return 1;
    }
    lcm_subscribe(a, ".*", on_message, &plain);
    lcm_subscribe(b, ".*", on_message, &filtered);
    printf("filtered %d\n", on);

    /* Refusals: an instance all the same, unfiltered. */
    const char *many[MPB_LCM_FILTER_CHANNELS + 1];
    char longname[MPB_LCM_FILTER_NAME_MAX + 2];
    for (int i = 0; i <= MPB_LCM_FILTER_CHANNELS; i++)
        many[i] = "X";
    memset(longname, 'x', sizeof longname - 1);
    longname[sizeof longname - 1] = '\0';
    const char *one_long[] = {longname};
    struct { const char *what, *url; const char *const *ch; int n; } refuse[] = {
        {"too_many", URL, many, MPB_LCM_FILTER_CHANNELS + 1},
        {"too_long", URL, one_long, 1},
        {"no_channels", URL, keep, 0},
        {"not_udpm", "memq://", keep, 2},
    };
    for (size_t i = 0; i < sizeof refuse / sizeof refuse[0]; i++) {
        int f = -1;
        lcm_t *x = mpb_lcm_create(refuse[i].url, refuse[i].ch, refuse[i].n, &f);
        printf("%s instance %d filtered %d\n", refuse[i].what, x != NULL, f);
        if (x)
            lcm_destroy(x);
    }

    lcm_t *pub = lcm_create(URL);
    for (int i = 0; i < NSENT; i++)
        lcm_publish(pub, sent[i], "hello", 5);
    memset(big, 'b', sizeof big);
    lcm_publish(pub, "KEEP_1", big, sizeof big);
    lcm_publish(pub, "DROP_BIG", big, sizeof big);
    lcm_publish(pub, "KEEP_1", "again", 5);

    drain(a, 300);
    drain(b, 300);
    tally *all[] = {&plain, &filtered};
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < all[k]->n; i++)
            printf("%s %s %d\n", all[k]->who, all[k]->channel[i], all[k]->count[i]);
    lcm_destroy(pub);
    lcm_destroy(b);
    lcm_destroy(a);
    return on == 1 ? 0 : 1;
}
