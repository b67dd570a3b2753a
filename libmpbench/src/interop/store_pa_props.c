/*
 * store_pa_props.c - an mpbench experiment as the run properties of OMPL's
 * formats (store_pa.h): their names and types (time, solved, status, the
 * first and final stage's path metrics as "solution ..." and "simplified
 * solution ...", the stages between as "<stage> solution ...", the
 * planner's own numbers), as the database writer and the log writer
 * declare them. The walk that fills them is store_pa_walk.c; what every
 * writer says of an experiment, store_pa_exp.c.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "interop/store_pa.h"

/* ---- the run properties ---------------------------------------------------- */

/* The header gives the sizes of these two: a definition of another
 * length does not compile. */
const char *const mpb__pa_status_enum[] = {
    "Unknown status", "Invalid start", "Invalid goal",
    "Unrecognized goal type", "Timeout", "Approximate solution",
    "Exact solution", "Crash", "Abort", "Infeasible", "Invalid request",
    "Out of memory",
};

const char *const mpb__pa_exp_params[][2] = {
    {"query", "VARCHAR(512)"},
    {"mpbench experiment", "INTEGER"},
};

/* Names a run property must not take: the runs table's own columns and
 * what Planner Arena joins onto each run. */
static const char *const reserved[] = {
    "id", "experimentid", "plannerid", "planner", "experiment", "version",
    "query", "mpbench experiment",
};

void mpb__pa_props_free(prop_list *l)
{
    for (int i = 0; i < l->n; i++) {
        free(l->v[i].name);
        free(l->v[i].stage);
        free(l->v[i].source);
    }
    free(l->v);
    *l = (prop_list){0};
}

/*
 * A property name from free text, prefix then text: letters and digits
 * kept, anything else (spaces, '_', punctuation) a single space between
 * words; "value" if nothing is left, "v " before a leading digit. Such a
 * name is a valid SQL column once its spaces are '_', as OMPL's script
 * makes them. Caller frees.
 */
static char *prop_name(const char *prefix, const char *text)
{
    size_t lp = strlen(prefix), lt = strlen(text);
    char *in = malloc(lp + lt + 1), *out = malloc(lp + lt + 8), *o = out;
    if (in == NULL || out == NULL) {
        free(in);
        free(out);
        return NULL;
    }
    memcpy(in, prefix, lp);
    memcpy(in + lp, text, lt + 1);
    int space = 0;
    for (const char *p = in; *p; p++) {
        char ch = *p;
        int word = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                   (ch >= '0' && ch <= '9');
        if (!word) {
            space = 1;
            continue;
        }
        if (o == out && ch >= '0' && ch <= '9') {
            *o++ = 'v';
            *o++ = ' ';
        } else if (space && o > out) {
            *o++ = ' ';
        }
        *o++ = ch;
        space = 0;
    }
    *o = '\0';
    if (o == out)
        strcpy(out, "value");
    free(in);
    return out;
}

int mpb__pa_same_column(const char *a, const char *b)
{
    for (;; a++, b++) {
        char x = *a == '_' ? ' ' : *a, y = *b == '_' ? ' ' : *b;
        if (x >= 'A' && x <= 'Z')
            x = (char)(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z')
            y = (char)(y - 'A' + 'a');
        if (x != y)
            return 0;
        if (x == '\0')
            return 1;
    }
}

static int name_taken(const prop_list *l, const char *name)
{
    for (size_t i = 0; i < sizeof reserved / sizeof reserved[0]; i++)
        if (mpb__pa_same_column(reserved[i], name))
            return 1;
    for (int i = 0; i < l->n; i++)
        if (mpb__pa_same_column(l->v[i].name, name))
            return 1;
    return 0;
}

/*
 * Add a property; name is taken over (freed on failure). A name already
 * taken gets fallback_prefix ("planner ", "progress "), then " 2", " 3" ...
 */
static int prop_add(prop_list *l, char *name, const char *type, prop_kind kind,
                    stage_role role, const char *stage, const char *source,
                    const char *fallback_prefix)
{
    if (name == NULL)
        return MPB_ENOMEM;
    if (name_taken(l, name) && fallback_prefix != NULL) {
        char *alt = prop_name(fallback_prefix, name);
        free(name);
        if ((name = alt) == NULL)
            return MPB_ENOMEM;
    }
    for (int k = 2; name_taken(l, name); k++) {
        size_t n = strlen(name) + 16;
        char *alt = malloc(n);
        if (alt == NULL) {
            free(name);
            return MPB_ENOMEM;
        }
        snprintf(alt, n, "%s %d", name, k);
        if (!name_taken(l, alt)) {
            free(name);
            name = alt;
            break;
        }
        free(alt);
    }
    if (mpb__grow((void **)&l->v, &l->cap, l->n + 1, sizeof *l->v)) {
        free(name);
        return MPB_ENOMEM;
    }
    prop *p = &l->v[l->n];
    *p = (prop){.name = name, .type = type, .kind = kind, .role = role};
    l->n++;
    if ((stage && (p->stage = strdup(stage)) == NULL) ||
        (source && (p->source = strdup(source)) == NULL))
        return MPB_ENOMEM;
    return MPB_OK;
}

/* ---- what an experiment holds ---------------------------------------------- */

void mpb__pa_names_free(name_list *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->v[i]);
    free(l->v);
    *l = (name_list){0};
}

static int add_name(void *ud, const char *name)
{
    name_list *out = ud;
    if (mpb__grow((void **)&out->v, &out->cap, out->n + 1, sizeof *out->v) ||
        (out->v[out->n] = strdup(name)) == NULL)
        return MPB_ENOMEM;
    out->n++;
    return MPB_OK;
}

/* The names the experiment's finished runs give (store_export.h). */
static int read_names(mpb_store *s, mpb__run_names which,
                      int64_t experiment_id, name_list *out)
{
    int rc = mpb__store_each_run_name(s, experiment_id, which, add_name, out);
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "out of memory");
    return rc;
}

/* The metrics of a stage, in the order the properties list them: those
 * the metric list ranks (path length, smoothness, clearance, ...) first,
 * then any other alphabetically. */
static int metric_rank(const char *name)
{
    const mpb_metric_info *mi = mpb_metric_info_of(mpb_metric_find(name));
    return mi != NULL && mi->rank > 0 ? mi->rank : MPB_NUM_METRICS + 1;
}

static int cmp_metric(const void *a, const void *b)
{
    const char *x = *(const char *const *)a, *y = *(const char *const *)b;
    int rx = metric_rank(x), ry = metric_rank(y);
    return rx != ry ? rx - ry : strcmp(x, y);
}

/* The property word of a stage metric: "length" for path_length, ...;
 * NULL for those the stage's time and segments say. */
static const char *metric_word(const char *metric)
{
    const mpb_metric_info *mi = mpb_metric_info_of(mpb_metric_find(metric));
    return mi != NULL ? mi->word : metric;
}

/* The properties of one stage role: "<prefix>solution time", ... */
static int add_stage_props(prop_list *l, const char *prefix, stage_role role,
                           const char *stage, const name_list *metrics)
{
    char buf[256];
    int rc;
    snprintf(buf, sizeof buf, "%ssolution time", prefix);
    if ((rc = prop_add(l, prop_name("", buf), "REAL", K_STAGE_TIME, role,
                       stage, NULL, "stage ")))
        return rc;
    for (int i = 0; i < metrics->n; i++) {
        const char *m = metrics->v[i], *word = metric_word(m);
        if (word == NULL)
            continue;   /* the stage's time and segments say it */
        snprintf(buf, sizeof buf, "%ssolution %s", prefix, word);
        if ((rc = prop_add(l, prop_name("", buf), "REAL", K_STAGE_METRIC,
                           role, stage, m, "stage ")))
            return rc;
    }
    snprintf(buf, sizeof buf, "%ssolution segments", prefix);
    if ((rc = prop_add(l, prop_name("", buf), "INTEGER", K_STAGE_SEGMENTS,
                       role, stage, NULL, "stage ")))
        return rc;
    snprintf(buf, sizeof buf, "%scorrect solution", prefix);
    return prop_add(l, prop_name("", buf), "BOOLEAN", K_STAGE_VALID, role,
                    stage, NULL, "stage ");
}

/* One of the four property types of OMPL's logs (static text), REAL for
 * any other. */
static const char *log_type(const char *type)
{
    static const char *const known[] = {"INTEGER", "BOOLEAN", "ENUM"};
    for (int i = 0; type && i < 3; i++)
        if (strcmp(type, known[i]) == 0)
            return known[i];
    return "REAL";
}

/* A property an imported log declares (log_properties). */
typedef struct declared {
    char *name;
    const char *type;   /* log_type()'s */
} declared;

typedef struct declared_list {
    declared *v;
    int       n, cap;
} declared_list;

static void declared_free(declared_list *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->v[i].name);
    free(l->v);
    *l = (declared_list){0};
}

/* The run (progress 0) or progress (1) properties the imported logs of an
 * experiment declare, each name once (its first planner's type), in their
 * planners' and the logs' order; none for a database made before they
 * were kept. */
static int note_declared(void *ud, const char *name, const char *type)
{
    declared_list *out = ud;
    for (int i = 0; i < out->n; i++)
        if (strcmp(out->v[i].name, name) == 0)
            return MPB_OK;
    if (mpb__grow((void **)&out->v, &out->cap, out->n + 1, sizeof *out->v) ||
        (out->v[out->n].name = strdup(name)) == NULL)
        return MPB_ENOMEM;
    out->v[out->n++].type = log_type(type);
    return MPB_OK;
}

static int read_declared(mpb_store *s, int64_t experiment_id, int progress,
                         declared_list *out)
{
    return mpb__store_each_log_property(s, experiment_id, progress,
                                        note_declared, out);
}

/*
 * What the declared properties d add to l: the type of each planner value
 * a log declared (its K_VALUE property of that source), and a property of
 * its own for each that is not a column of l yet (no run measured it):
 * NULL in every run, as in OMPL's script's database.
 */
static int add_declared(prop_list *l, const declared_list *d,
                        const char *fallback_prefix)
{
    int rc = MPB_OK;
    for (int i = 0; i < d->n && rc == MPB_OK; i++) {
        char *name = prop_name("", d->v[i].name);
        if (name == NULL)
            return MPB_ENOMEM;
        int present = 0;
        for (int k = 0; k < l->n; k++) {
            prop *p = &l->v[k];
            if (p->kind == K_VALUE && p->source &&
                strcmp(p->source, d->v[i].name) == 0) {
                p->type = d->v[i].type;
                present = 1;
            } else if (mpb__pa_same_column(p->name, name)) {
                present = 1;
            }
        }
        if (present)
            free(name);
        else
            rc = prop_add(l, name, d->v[i].type, K_VALUE, ROLE_FIRST, NULL,
                          d->v[i].name, fallback_prefix);
    }
    return rc;
}

/*
 * An imported log's runs: the properties that mpbench works out from what
 * it keeps (the claim, the status, whether approximate, whether a stage
 * is valid) give back the log's own cell instead, NULL where the run has
 * none (its planner's block does not declare the property, or the run
 * left it empty), if the log declares it (mpb import keeps such cells as
 * planner values); and the simplified stage's properties are NULL for a
 * run without one, not the first stage's.
 */
static int log_cells(prop_list *l, const declared_list *d)
{
    static const struct { prop_kind kind; stage_role role; const char *name; }
        own[] = {
        {K_CLAIMED, ROLE_FIRST, "solved"},
        {K_STATUS, ROLE_FIRST, "status"},
        {K_APPROX, ROLE_FIRST, "approximate solution"},
        {K_STAGE_VALID, ROLE_FIRST, "correct solution"},
        {K_STAGE_VALID, ROLE_FINAL, "simplified correct solution"},
    };
    for (int k = 0; k < l->n; k++) {
        prop *p = &l->v[k];
        for (size_t i = 0; i < sizeof own / sizeof own[0]; i++) {
            int said = 0;
            for (int j = 0; j < d->n && !said; j++)
                said = strcmp(d->v[j].name, own[i].name) == 0;
            if (!said || p->kind != own[i].kind || p->role != own[i].role)
                continue;
            free(p->source);
            if ((p->source = strdup(own[i].name)) == NULL)
                return MPB_ENOMEM;
            p->kind = K_VALUE;
            p->role = ROLE_FIRST;
            break;
        }
        if (p->role == ROLE_FINAL)
            p->role = ROLE_SIMPLIFIED;
    }
    return MPB_OK;
}

int mpb__pa_experiment_props(mpb_store *s, int64_t experiment_id,
                             prop_list *props, prop_list *progress)
{
    static const struct { const char *name, *type; prop_kind kind; } fixed[] = {
        {"time", "REAL", K_TIME},
        {"time raw", "REAL", K_TIME_RAW},
        {"time other", "REAL", K_TIME_OTHER},
        {"wall time", "REAL", K_WALL},
        {"verify time", "REAL", K_VERIFY},
        /* OMPL's Benchmark's name, which Planner Arena plots. */
        {"memory", "REAL", K_MEMORY},
        {"solved", "BOOLEAN", K_SOLVED},
        {"claimed success", "BOOLEAN", K_CLAIMED},
        {"approximate solution", "BOOLEAN", K_APPROX},
        {"status", "ENUM", K_STATUS},
    };
    name_list metrics = {0}, mids = {0}, values = {0}, samples = {0};
    declared_list run_decl = {0}, progress_decl = {0};
    int rc;

    if ((rc = read_names(s, MPB__NAMES_METRICS, experiment_id, &metrics)) ||
        (rc = read_names(s, MPB__NAMES_MID_STAGES, experiment_id, &mids)) ||
        (rc = read_names(s, MPB__NAMES_VALUES, experiment_id, &values)) ||
        (rc = read_names(s, MPB__NAMES_PROGRESS, experiment_id, &samples)) ||
        (rc = read_declared(s, experiment_id, 0, &run_decl)) ||
        (rc = read_declared(s, experiment_id, 1, &progress_decl)))
        goto done;
    if (metrics.n > 1) /* qsort with NULL is undefined, even for 0 */
        qsort(metrics.v, (size_t)metrics.n, sizeof *metrics.v, cmp_metric);

    /* An imported log's runs give back the log's own properties: its
     * "time" (tau_r: tau_t has the simplification too), its "solved" (the
     * claim) and its "simplification time" (the final stage's). */
    int imported = 0;
    if ((rc = mpb__store_experiment_imported(s, experiment_id, &imported)))
        goto done;
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++) {
        prop_kind kind = fixed[i].kind;
        if (imported && kind == K_TIME)
            kind = K_TIME_RAW;
        else if (imported && kind == K_SOLVED)
            kind = K_CLAIMED;
        if ((rc = prop_add(props, prop_name("", fixed[i].name), fixed[i].type,
                           kind, ROLE_FIRST, NULL, NULL, NULL)))
            goto done;
    }
    if (imported && (rc = prop_add(props, prop_name("", "simplification time"),
                                   "REAL", K_STAGE_TIME, ROLE_FINAL, NULL,
                                   NULL, NULL)))
        goto done;
    if ((rc = add_stage_props(props, "", ROLE_FIRST, NULL, &metrics)))
        goto done;
    for (int i = 0; i < mids.n; i++) {
        char *prefix = prop_name("", mids.v[i]);
        if (prefix == NULL) {
            rc = MPB_ENOMEM;
            goto done;
        }
        char buf[160];
        snprintf(buf, sizeof buf, "%.150s ", prefix);
        free(prefix);
        if ((rc = add_stage_props(props, buf, ROLE_MID, mids.v[i], &metrics)))
            goto done;
    }
    if ((rc = add_stage_props(props, "simplified ", ROLE_FINAL, NULL,
                              &metrics)))
        goto done;
    if (imported && (rc = log_cells(props, &run_decl)))
        goto done;
    for (int i = 0; i < values.n; i++) {
        int taken = 0;  /* read by a property above (log_cells()) */
        for (int k = 0; k < props->n && !taken; k++)
            taken = props->v[k].kind == K_VALUE &&
                    strcmp(props->v[k].source, values.v[i]) == 0;
        if (!taken && (rc = prop_add(props, prop_name("", values.v[i]), "REAL",
                                     K_VALUE, ROLE_FIRST, NULL, values.v[i],
                                     "planner ")))
            goto done;
    }
    if ((rc = add_declared(props, &run_decl, "planner ")))
        goto done;
    /* Progress: "time" is the x-axis column of the table itself. */
    prop_list taken = {0};
    if ((rc = prop_add(&taken, prop_name("", "time"), "REAL", K_TIME,
                       ROLE_FIRST, NULL, NULL, NULL)) == MPB_OK) {
        *progress = taken;
        for (int i = 0; i < samples.n && rc == MPB_OK; i++)
            rc = prop_add(progress, prop_name("", samples.v[i]), "REAL",
                          K_VALUE, ROLE_FIRST, NULL, samples.v[i],
                          "progress ");
        if (rc == MPB_OK)
            rc = add_declared(progress, &progress_decl, "progress ");
    } else {
        mpb__pa_props_free(&taken);
    }
done:
    if (rc == MPB_ENOMEM)
        mpb__store_fail(s, rc, "out of memory");
    mpb__pa_names_free(&metrics);
    mpb__pa_names_free(&mids);
    mpb__pa_names_free(&values);
    mpb__pa_names_free(&samples);
    declared_free(&run_decl);
    declared_free(&progress_decl);
    return rc;
}
