/* pairs.c - configurations compared problem by problem: per-problem
 * medians, ratios, signed-rank tests and Holm's adjustment (pairs.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/stats.h"
#include "pairs.h"

int pairs_init(pairs_data *d, int nc, int nq, double limit)
{
    *d = (pairs_data){.limit = limit, .nc = nc, .nq = nq};
    d->cells = calloc((size_t)(nc > 0 ? nc : 1) * (size_t)(nq > 0 ? nq : 1),
                      sizeof *d->cells);
    d->query_set = calloc((size_t)(nq > 0 ? nq : 1), sizeof *d->query_set);
    return d->cells && d->query_set ? MPB_OK : MPB_ENOMEM;
}

static int grow(double **v, int *cap, int n)
{
    if (n < *cap)
        return 0;
    int c = *cap ? 2 * *cap : 4;
    double *nv = realloc(*v, (size_t)c * sizeof *nv);
    if (nv == NULL)
        return -1;
    *v = nv;
    *cap = c;
    return 0;
}

int pairs_add(pairs_data *d, int config, int query, int success,
              double time, double length)
{
    pairs_cell *x = &d->cells[(size_t)config * (size_t)d->nq + (size_t)query];
    if (grow(&x->times, &x->cap_t, x->runs) != 0)
        return MPB_ENOMEM;
    x->times[x->runs++] = success && isfinite(time) ? time : d->limit;
    if (success) {
        if (grow(&x->lengths, &x->cap_l, x->successes) != 0)
            return MPB_ENOMEM;
        x->lengths[x->successes++] = length;
    }
    return MPB_OK;
}

void pairs_free(pairs_data *d)
{
    if (d->cells != NULL)
        for (size_t i = 0; i < (size_t)d->nc * (size_t)d->nq; i++) {
            free(d->cells[i].times);
            free(d->cells[i].lengths);
        }
    free(d->cells);
    free(d->query_set);
    *d = (pairs_data){0};
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of v's finite values; v is left holding them, sorted. */
static double median_of(double *v, int n)
{
    int m = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i]))
            v[m++] = v[i];
    if (m == 0)
        return NAN;
    qsort(v, (size_t)m, sizeof *v, by_value);
    return mpb_quantile(v, m, 0.5);
}

/* ratio of x[i] / y[i] over n problems: median, interval, signed-rank p of
 * the log ratios. x and y are overwritten. */
static int ratio_of(double *x, double *y, int n, pairs_ratio *r)
{
    *r = (pairs_ratio){.n = n, .median = NAN, .lo = NAN, .hi = NAN, .p = NAN,
                       .p_holm = NAN};
    if (n == 0)
        return MPB_OK;
    for (int i = 0; i < n; i++) {
        double a = fmax(x[i], 1e-9), b = fmax(y[i], 1e-9);
        x[i] = a / b;
        y[i] = log(x[i]);   /* of the ratio: equal ratios tie exactly */
    }
    int rc = mpb_signed_rank_test(y, n, NULL, &r->p);
    if (rc != MPB_OK)
        return rc;
    r->p_holm = r->p;
    qsort(x, (size_t)n, sizeof *x, by_value);
    r->median = mpb_quantile(x, n, 0.5);
    return mpb_median_interval(x, n, &r->lo, &r->hi, NULL);
}

int pairs_compare(pairs_data *d, int a, int b, int set, pairs_pair *out)
{
    *out = (pairs_pair){.a = a, .b = b};
    size_t nq = (size_t)d->nq;
    double *ta = malloc((nq + 1) * sizeof *ta), *tb = malloc((nq + 1) * sizeof *tb);
    double *la = malloc((nq + 1) * sizeof *la), *lb = malloc((nq + 1) * sizeof *lb);
    int rc = MPB_ENOMEM, nt = 0, nl = 0;
    if (!ta || !tb || !la || !lb)
        goto done;
    for (int q = 0; q < d->nq; q++) {
        if (set >= 0 && d->query_set[q] != set)
            continue;
        pairs_cell *x = &d->cells[(size_t)a * nq + (size_t)q];
        pairs_cell *y = &d->cells[(size_t)b * nq + (size_t)q];
        if (x->runs == 0 || y->runs == 0)
            continue;
        out->problems++;
        int sa = 2 * x->successes > x->runs, sb = 2 * y->successes > y->runs;
        out->both += sa && sb;
        out->only_a += sa && !sb;
        out->only_b += !sa && sb;
        out->neither += !sa && !sb;
        if (sa || sb) {
            ta[nt] = median_of(x->times, x->runs);
            tb[nt++] = median_of(y->times, y->runs);
        }
        if (sa && sb) {
            la[nl] = median_of(x->lengths, x->successes);
            lb[nl] = median_of(y->lengths, y->successes);
            if (isfinite(la[nl]) && isfinite(lb[nl]))
                nl++;
        }
    }
    if ((rc = ratio_of(ta, tb, nt, &out->time)) == MPB_OK)
        rc = ratio_of(la, lb, nl, &out->length);
done:
    free(ta);
    free(tb);
    free(la);
    free(lb);
    return rc;
}

int pairs_holm(pairs_pair *pairs, int n)
{
    if (n <= 0)
        return MPB_OK;
    double *p = calloc((size_t)n, sizeof *p);
    if (p == NULL)
        return MPB_ENOMEM;
    int rc;
    for (int k = 0; k < n; k++)
        p[k] = isnan(pairs[k].time.p) ? 1.0 : pairs[k].time.p;
    if ((rc = mpb_holm(p, n, p)) != MPB_OK)
        goto done;
    for (int k = 0; k < n; k++)
        pairs[k].time.p_holm = p[k];
    for (int k = 0; k < n; k++)
        p[k] = isnan(pairs[k].length.p) ? 1.0 : pairs[k].length.p;
    if ((rc = mpb_holm(p, n, p)) != MPB_OK)
        goto done;
    for (int k = 0; k < n; k++)
        pairs[k].length.p_holm = p[k];
done:
    free(p);
    return rc;
}

int pairs_index(int n, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a;
    return lo * n - lo * (lo + 1) / 2 + (hi - lo - 1);
}

int pairs_all(pairs_data *d, int set, pairs_pair **out)
{
    int n = d->nc * (d->nc - 1) / 2, k = 0, rc;
    *out = NULL;
    if (n <= 0)
        return MPB_OK;
    pairs_pair *pairs = calloc((size_t)n, sizeof *pairs);
    if (pairs == NULL)
        return MPB_ENOMEM;
    for (int a = 0; a < d->nc; a++)
        for (int b = a + 1; b < d->nc; b++, k++)
            if ((rc = pairs_compare(d, a, b, set, &pairs[k])) != MPB_OK)
                goto fail;
    if ((rc = pairs_holm(pairs, n)) != MPB_OK)
        goto fail;
    *out = pairs;
    return MPB_OK;
fail:
    free(pairs);
    return rc;
}

int pairs_verdict(const pairs_ratio *r)
{
    if (r->n == 0 || !(r->p_holm < PAIRS_ALPHA) || r->median == 1 ||
        isnan(r->median))
        return 0;
    return r->median < 1 ? -1 : 1;
}
