/* log.c - the daemon's console log: one short line per event worth seeing. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "daemon.h"

void mpbd_log(const char *fmt, ...)
{
    char stamp[16];
    time_t t = time(NULL);
    struct tm tm;
    va_list ap;

    localtime_r(&t, &tm);
    strftime(stamp, sizeof stamp, "%H:%M:%S", &tm);
    fprintf(stderr, "%s mpbenchd: ", stamp);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

void mpbd_db_error(mpbd *d)
{
    const char *msg = mpb_store_errmsg(d->store);
    if (strcmp(msg, d->db_error) == 0)
        return;
    snprintf(d->db_error, sizeof d->db_error, "%s", msg);
    mpbd_log("database %s: %s", d->db_path, msg);
}
