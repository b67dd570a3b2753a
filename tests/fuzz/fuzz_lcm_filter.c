/*
 * fuzz_lcm_filter.c - libFuzzer target: the socket filter of lcm_filter.h.
 * The input is one UDP datagram's payload. It goes through the classic BPF
 * programs mpb_lcm_filter_program() makes (one keeping every channel, one
 * keeping the daemon's four), run by a small interpreter below, and through
 * mpb_lcm_datagram_is_valid(); they must agree. Every datagram they pass
 * must then be safe for a model of liblcm's receive code (1.3.1's and the
 * PyPI binding's 1.5.x lcm_udpm.c): no read past the datagram, no size
 * that wraps, no copy outside the message's buffer.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"

#define UDP_HEADER 8

/* ---- a classic BPF interpreter, for the instructions the filter uses ---- */

static uint32_t load(const uint8_t *pkt, size_t len, uint32_t k, int size, int *out)
{
    if ((uint64_t)k + (uint64_t)size > len) {
        *out = 1;       /* past the end: the kernel ends the program, 0 */
        return 0;
    }
    uint32_t v = 0;
    for (int i = 0; i < size; i++)
        v = v << 8 | pkt[k + (uint32_t)i];
    return v;
}

/* What the program returns for the packet (UDP header and payload). */
static uint32_t run(const struct sock_filter *op, int n, const uint8_t *pkt,
                    size_t len)
{
    uint32_t a = 0, x = 0, mem[BPF_MEMWORDS] = {0};
    int out = 0;
    for (int pc = 0; pc < n; pc++) {
        const struct sock_filter *f = &op[pc];
        uint32_t k = f->k;
        switch (f->code) {
        case BPF_LD | BPF_W | BPF_LEN: a = (uint32_t)len; break;
        case BPF_LD | BPF_W | BPF_ABS: a = load(pkt, len, k, 4, &out); break;
        case BPF_LD | BPF_H | BPF_ABS: a = load(pkt, len, k, 2, &out); break;
        case BPF_LD | BPF_B | BPF_ABS: a = load(pkt, len, k, 1, &out); break;
        case BPF_LD | BPF_MEM:
            if (k >= BPF_MEMWORDS) abort();
            a = mem[k];
            break;
        case BPF_LDX | BPF_W | BPF_IMM: x = k; break;
        case BPF_LDX | BPF_W | BPF_MEM:
            if (k >= BPF_MEMWORDS) abort();
            x = mem[k];
            break;
        case BPF_ST:
            if (k >= BPF_MEMWORDS) abort();
            mem[k] = a;
            break;
        case BPF_MISC | BPF_TAX: x = a; break;
        case BPF_MISC | BPF_TXA: a = x; break;
        case BPF_ALU | BPF_ADD | BPF_X: a += x; break;
        case BPF_ALU | BPF_SUB | BPF_K: a -= k; break;
        case BPF_ALU | BPF_SUB | BPF_X: a -= x; break;
        case BPF_ALU | BPF_MUL | BPF_K: a *= k; break;
        case BPF_JMP | BPF_JA: pc += (int)k; break;
        case BPF_JMP | BPF_JEQ | BPF_K: pc += a == k ? f->jt : f->jf; break;
        case BPF_JMP | BPF_JEQ | BPF_X: pc += a == x ? f->jt : f->jf; break;
        case BPF_JMP | BPF_JGE | BPF_K: pc += a >= k ? f->jt : f->jf; break;
        case BPF_JMP | BPF_JGE | BPF_X: pc += a >= x ? f->jt : f->jf; break;
        case BPF_JMP | BPF_JGT | BPF_K: pc += a > k ? f->jt : f->jf; break;
        case BPF_JMP | BPF_JGT | BPF_X: pc += a > x ? f->jt : f->jf; break;
        case BPF_RET | BPF_K: return k;
        default: abort();       /* an instruction this interpreter lacks */
        }
        if (out)
            return 0;
    }
    abort();                    /* ran off the end: the kernel refuses that */
}

/* ---- a model of liblcm's receive code, for a datagram it is given ---- */

static uint32_t be(const uint8_t *b, int n)
{
    uint32_t v = 0;
    for (int i = 0; i < n; i++)
        v = v << 8 | b[i];
    return v;
}

/* strlen() as LCM calls it, but never past the datagram: a name that runs
 * off the end is a read past it, and fails the test. */
static uint32_t lcm_strlen(const uint8_t *b, size_t len, size_t at)
{
    for (size_t i = at; i < len; i++)
        if (b[i] == 0)
            return (uint32_t)(i - at);
    abort();
}

/* One fragment copied as LCM does: frag_size bytes from data_start to
 * offset in a buffer of msg_size, after its own 32-bit bounds check. */
static void lcm_copy(uint32_t offset, uint32_t frag_size, uint32_t msg_size,
                     size_t data_start, size_t len)
{
    int lcm_drops = offset + frag_size > msg_size;          /* 32 bits */
    if ((uint64_t)offset + frag_size > msg_size && !lcm_drops)
        abort();                /* the wrap of issue 28 */
    if (!lcm_drops && data_start + frag_size > len)
        abort();                /* a copy from past the datagram */
}

static void lcm_receive(const uint8_t *b, size_t len)
{
    if (len < 8)
        abort();                /* LCM drops it itself; the filter must too */
    uint32_t magic = be(b, 4);
    if (magic == 0x4c433032u) {
        uint32_t channel = lcm_strlen(b, len, 8);
        if (channel > 63)
            abort();
        int data_size = (int)len - (int)(8 + channel + 1);  /* LCM's int */
        if (data_size < 0)
            abort();
        return;
    }
    if (magic != 0x4c433033u || len < 20)
        abort();
    uint32_t msg_size = be(b + 8, 4), offset = be(b + 12, 4);
    uint32_t number = be(b + 16, 2), count = be(b + 18, 2);
    if (msg_size > (uint32_t)LCM_MAX_MESSAGE_SIZE || msg_size > MPB_LCM_MESSAGE_MAX ||
        number >= count)
        abort();
    uint32_t frag_size = (uint32_t)len - 20;
    if (number == 0) {
        uint32_t channel = lcm_strlen(b, len, 20);
        if (channel > 63 || channel + 1 > frag_size)
            abort();
        /* 1.3.1 with a buffer already open for this sender takes the
         * channel as payload; otherwise, and 1.5.x always, it skips it. */
        lcm_copy(offset, frag_size, msg_size, 20, len);
        lcm_copy(offset, frag_size - channel - 1, msg_size, 20 + channel + 1, len);
    } else {
        lcm_copy(offset, frag_size, msg_size, 20, len);
    }
}

/* ---- the target ---- */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static struct sock_filter all[MPB_LCM_FILTER_PROGRAM_MAX];
    static struct sock_filter some[MPB_LCM_FILTER_PROGRAM_MAX];
    static const char *const kept[] = {MPB_CHANNEL_ANNOUNCE, MPB_CHANNEL_RESULT,
                                       MPB_CHANNEL_ACK, MPB_CHANNEL_STATUS};
    static int n_all, n_some;
    static uint8_t pkt[UDP_HEADER + 65536];
    if (n_all == 0) {
        n_all = mpb_lcm_filter_program(NULL, 0, all, MPB_LCM_FILTER_PROGRAM_MAX);
        n_some = mpb_lcm_filter_program(kept, 4, some, MPB_LCM_FILTER_PROGRAM_MAX);
        if (n_all < 1 || n_some < 1)
            abort();
    }
    if (size > sizeof pkt - UDP_HEADER)
        return 0;
    memset(pkt, 0, UDP_HEADER);
    memcpy(pkt + UDP_HEADER, data, size);

    int valid = mpb_lcm_datagram_is_valid(data, size);
    int pass_all = run(all, n_all, pkt, UDP_HEADER + size) != 0;
    int pass_some = run(some, n_some, pkt, UDP_HEADER + size) != 0;
    if (valid != pass_all)
        abort();                /* the program and its specification differ */
    if (pass_some && !valid)
        abort();
    if (valid) {
        lcm_receive(data, size);
        /* A short message passes the channel filter if and only if its
         * channel is kept; a fragment passes it whatever it carries. */
        int keep = 1;
        if (be(data, 4) == 0x4c433032u) {
            keep = 0;
            for (int i = 0; i < 4; i++)
                keep |= strcmp((const char *)data + 8, kept[i]) == 0;
        }
        if (pass_some != keep)
            abort();
    }
    return 0;
}
