/*
 * doomed.c - stopping when every run would fail alike: when the first
 * result of every planner configuration in this session is a failure
 * with the same world error (a mesh no planner finds, a format none
 * reads), the rest would fail so too, hundreds of runs each stored as
 * such. The loop then stops (main.c) with that error in one line; what
 * is stored stays, and the same command resumes once it is fixed.
 */
#include <stdlib.h>
#include <string.h>

#include "daemon.h"

/* The world's words in a stored message ("... world: mesh '...' not
 * found ..."), or NULL when the failure is not the world's. */
static const char *world_error(const char *status, const char *message)
{
    if (status == NULL || message == NULL ||
        strcmp(status, "invalid_request") != 0)
        return NULL;
    return strstr(message, "world: ");
}

void mpbd_doomed_result(mpbd *d, int config, const char *status,
                        const char *message)
{
    mpbd_doomed *m = &d->doomed;
    int n = d->exp->num_configs;
    if (m->stop || config < 0 || config >= n)
        return;
    if (m->seen == NULL) {
        if ((m->seen = calloc((size_t)n, 1)) == NULL)
            return;
        m->alike = 1;
    }
    if (m->seen[config])
        return;
    m->seen[config] = 1;
    m->num_seen++;
    const char *why = world_error(status, message);
    char esc[sizeof m->why];
    if (why == NULL)
        m->alike = 0;
    else if (m->num_seen == 1)
        mpb_escape(why, m->why, sizeof m->why);
    else if (strcmp(mpb_escape(why, esc, sizeof esc), m->why) != 0)
        m->alike = 0;
    m->stop = m->alike && m->num_seen == n;
}

void mpbd_doomed_free(mpbd *d)
{
    free(d->doomed.seen);
    d->doomed.seen = NULL;
}
