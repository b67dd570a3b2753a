/* proto.c - attempt ids, content hashes, channel names and clocks of the
 * protocol. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <sodium.h>

#include "mpbench/mpbench.h"
#include "mpb_daemon_status_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_stage_t.h"

static const char hexdigits[] = "0123456789abcdef";

static void to_hex(const unsigned char *in, size_t n, char *out)
{
    for (size_t i = 0; i < n; i++) {
        out[2 * i] = hexdigits[in[i] >> 4];
        out[2 * i + 1] = hexdigits[in[i] & 15];
    }
    out[2 * n] = '\0';
}

int mpb_attempt_id_new(char out[MPB_ATTEMPT_ID_SIZE])
{
    unsigned char raw[16];
    /* sodium_init() is idempotent and thread-safe; it opens the kernel's
     * random source once. */
    if (sodium_init() < 0)
        return MPB_EIO;
    randombytes_buf(raw, sizeof raw);
    to_hex(raw, sizeof raw, out);
    return MPB_OK;
}

int mpb_attempt_id_is_valid(const char *s)
{
    if (s == NULL)
        return 0;
    for (int i = 0; i < MPB_ATTEMPT_ID_SIZE - 1; i++)
        if (!((s[i] >= '0' && s[i] <= '9') || (s[i] >= 'a' && s[i] <= 'f')))
            return 0;
    return s[MPB_ATTEMPT_ID_SIZE - 1] == '\0';
}

void mpb_hash_hex(const void *data, size_t len, char out[MPB_HASH_SIZE])
{
    unsigned char raw[16];
    crypto_generichash(raw, sizeof raw, data, len, NULL, 0);
    to_hex(raw, sizeof raw, out);
}

int mpb_planner_id_is_valid(const char *id)
{
    size_t n = 0;
    if (id == NULL)
        return 0;
    for (; id[n] != '\0'; n++) {
        char c = id[n];
        if (n >= MPB_PLANNER_ID_MAX)
            return 0;
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
              (c >= '0' && c <= '9') || strchr("_.:@-", c) != NULL))
            return 0;
    }
    return n > 0;
}

static int name_char_ok(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
           (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-';
}

int mpb_planner_id_make(const char *name, const char *host, long pid,
                        char *out, size_t outlen)
{
    char h[MPB_PLANNER_ID_MAX + 1], pidtext[24];
    size_t nlen = name != NULL ? strlen(name) : 0;
    if (outlen > 0)
        out[0] = '\0';
    if (nlen == 0 || nlen > 32 || outlen < MPB_PLANNER_ID_MAX + 1)
        return MPB_EINVAL;
    for (size_t i = 0; i < nlen; i++)
        if (!name_char_ok(name[i]))
            return MPB_EINVAL;
    if (host == NULL || host[0] == '\0')
        host = "localhost";
    snprintf(pidtext, sizeof pidtext, "%ld", pid);
    /* name '@' host ':' pid; the name and pid leave room for 10 or more. */
    size_t room = MPB_PLANNER_ID_MAX - nlen - 2 - strlen(pidtext);
    size_t hlen = strlen(host), keep = hlen <= room ? hlen : room - 9;
    for (size_t i = 0; i < keep; i++)
        h[i] = name_char_ok(host[i]) ? host[i] : '-';
    h[keep] = '\0';
    if (keep < hlen) {
        char hash[MPB_HASH_SIZE];
        mpb_hash_hex(host, hlen, hash);
        snprintf(h + keep, sizeof h - keep, "-%.8s", hash);
    }
    snprintf(out, outlen, "%s@%s:%s", name, h, pidtext);
    return MPB_OK;
}

/* The bytes of the character at u (one for a byte that starts no valid
 * UTF-8: no overlong form, no surrogate, nothing past U+10FFFF), and
 * whether it may be shown as it is. */
static int escape_next(const unsigned char *u, int *shown)
{
    int len = u[0] < 0x80 ? 1 : u[0] >= 0xc2 && u[0] <= 0xdf ? 2
              : u[0] >= 0xe0 && u[0] <= 0xef ? 3
              : u[0] >= 0xf0 && u[0] <= 0xf4 ? 4 : 0;
    unsigned c = len == 1 ? u[0] : u[0] & (0x7fu >> len);
    for (int i = 1; i < len; i++) {
        if ((u[i] & 0xc0) != 0x80) {
            len = 0;
            break;
        }
        c = c << 6 | (u[i] & 0x3fu);
    }
    if ((len == 3 && (c < 0x800 || (c >= 0xd800 && c <= 0xdfff))) ||
        (len == 4 && (c < 0x10000 || c > 0x10ffff)))
        len = 0;
    *shown = len > 0 && c >= 0x20 && c != 0x7f && c != '\\' &&
             !(c >= 0x80 && c <= 0x9f);
    return len > 0 ? len : 1;
}

char *mpb_escape(const char *s, char *out, size_t outlen)
{
    const unsigned char *u = (const unsigned char *)s;
    size_t o = 0, whole = 0;
    int shown;
    if (outlen == 0)
        return out;
    for (const unsigned char *p = u; *p != '\0';) {
        int len = escape_next(p, &shown);
        whole += shown ? (size_t)len : 4 * (size_t)len;
        p += len;
    }
    /* Cut short: room for "..." after the last character that fits. */
    size_t room = whole < outlen ? outlen - 1 : outlen > 4 ? outlen - 4 : 0;
    while (*u != '\0') {
        int len = escape_next(u, &shown);
        size_t n = shown ? (size_t)len : 4 * (size_t)len;
        if (o + n > room)
            break;
        for (int i = 0; i < len; i++, u++) {
            if (shown)
                out[o++] = (char)*u;
            else {
                snprintf(out + o, 5, "\\x%02x", *u);
                o += 4;
            }
        }
    }
    if (*u != '\0' && o + 3 < outlen) {
        memcpy(out + o, "...", 3);
        o += 3;
    }
    out[o] = '\0';
    return out;
}

/* A planner's own channel: prefix + id, for a valid id that fits. */
static int planner_channel(const char *prefix, const char *planner_id,
                           char *out, size_t outlen)
{
    if (!mpb_planner_id_is_valid(planner_id))
        return MPB_EINVAL;
    int n = snprintf(out, outlen, "%s%s", prefix, planner_id);
    return (n < 0 || (size_t)n >= outlen) ? MPB_EINVAL : MPB_OK;
}

int mpb_request_channel(const char *planner_id, char *out, size_t outlen)
{
    return planner_channel(MPB_CHANNEL_REQUEST_PREFIX, planner_id, out, outlen);
}

int mpb_ack_channel(const char *planner_id, char *out, size_t outlen)
{
    return planner_channel(MPB_CHANNEL_ACK_PREFIX, planner_id, out, outlen);
}

int64_t mpb_utime_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

double mpb_monotonic_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

int mpb_approach_index(const char *approach)
{
    static const char *const words[MPB_NUM_APPROACHES] = {MPB_APPROACHES};
    for (int i = 0; approach != NULL && i < MPB_NUM_APPROACHES; i++)
        if (strcmp(approach, words[i]) == 0)
            return i;
    return -1;
}

const char *mpb_status_name(int status)
{
    switch (status) {
    case MPB_PLAN_RESULT_T_SOLVED:          return "solved";
    case MPB_PLAN_RESULT_T_APPROXIMATE:     return "approximate";
    case MPB_PLAN_RESULT_T_TIMEOUT:         return "timeout";
    case MPB_PLAN_RESULT_T_FAILED:          return "failed";
    case MPB_PLAN_RESULT_T_INVALID_REQUEST: return "invalid_request";
    case MPB_PLAN_RESULT_T_CRASH:           return "crash";
    case MPB_PLAN_RESULT_T_MEMORY:          return "memory";
    }
    return "unknown";
}

int mpb_status_is_planners(int status)
{
    return status >= MPB_PLAN_RESULT_T_SOLVED &&
           status <= MPB_PLAN_RESULT_T_MEMORY &&
           status != MPB_PLAN_RESULT_T_CRASH;
}

int mpb_stage_sizes_ok(const mpb_stage_t *st, int num_joints, char *why,
                       size_t whylen)
{
    if (st->num_joints == num_joints && st->num_waypoints >= 0 &&
        st->num_values >= 0 &&
        (int64_t)st->num_waypoints * st->num_joints == st->num_values)
        return 1;
    if (why != NULL)
        snprintf(why, whylen, "stage '%.40s' has %d waypoints of %d joints in "
                 "%d values; the robot has %d joints", st->name ? st->name : "",
                 st->num_waypoints, st->num_joints, st->num_values, num_joints);
    return 0;
}

int64_t mpb_daemon_started_utime(const mpb_daemon_status_t *st)
{
    return st->utime - (int64_t)llround(st->elapsed_s * 1e6);
}

int mpb_daemon_started_before(int64_t a_utime, const char *a_id,
                              int64_t b_utime, const char *b_id)
{
    return a_utime != b_utime ? a_utime < b_utime : strcmp(a_id, b_id) < 0;
}
