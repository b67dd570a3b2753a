/*
 * experiment_seen.c - a scene entry's `seen:`: what its planners are
 * given instead of the scene, as a robot plans on what its sensors give
 * it. Either a scene of its own (`format:` and `file:` or `text:`, as a
 * scene), or `sense:`, what depth cameras would see of this scene
 * (sense.h, as `mpb sense` makes it), made here at loading, the same
 * bytes for the same settings. The daemon judges every path on the scene
 * (the truth) and also on what was seen (measure.c), and the store keeps
 * both (mpb_seen_scene).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "experiment_load.h"
#include "mpbench/scene.h"
#include "mpbench/sense.h"

/* A list of exactly n numbers at node n, into v. */
static int numbers(mpbd_loader *L, yaml_node_t *n, const char *what, int len,
                   double *v)
{
    if (n == NULL || n->type != YAML_SEQUENCE_NODE || count_items(n) != len)
        return fail_at(L, n, "%s must be a list of %d numbers", what, len);
    for (int i = 0; i < len; i++)
        if (parse_double(L, node(L, n->data.sequence.items.start[i]), what,
                         &v[i]) != 0)
            return -1;
    return 0;
}

/* `sense: {cameras, width, height, fov, range, noise, resolution, seed}`,
 * every key optional (mpb_sense_options_init()'s defaults). */
static int read_sense(mpbd_loader *L, yaml_node_t *m, mpb_sense_options *o)
{
    static const char *const keys[] = {"cameras", "width", "height", "fov",
                                       "range", "noise", "resolution",
                                       "seed", NULL};
    yaml_node_t *n;
    mpb_sense_options_init(o);
    if (m == NULL || (m->type != YAML_MAPPING_NODE &&
                      !(m->type == YAML_SCALAR_NODE && scalar(m)[0] == '\0')))
        return fail_at(L, m, "sense must be a mapping of camera settings "
                       "(each optional: cameras, width, height, fov, range, "
                       "noise, resolution, seed)");
    if (m->type != YAML_MAPPING_NODE)
        return 0;
    if (only_keys(L, m, keys) != 0)
        return -1;
    if ((n = get(L, m, "cameras")) != NULL) {
        if (n->type != YAML_SEQUENCE_NODE || count_items(n) == 0 ||
            count_items(n) > MPB_SENSE_MAX_CAMERAS)
            return fail_at(L, n, "cameras must be a list of 1 to %d cameras, "
                           "each [EX, EY, EZ, AX, AY, AZ]: at E, looking at A",
                           MPB_SENSE_MAX_CAMERAS);
        for (yaml_node_item_t *it = n->data.sequence.items.start;
             it < n->data.sequence.items.top; it++) {
            double v[6];
            if (numbers(L, node(L, *it), "a camera", 6, v) != 0)
                return -1;
            mpb_camera *c = &o->cameras[o->num_cameras++];
            memcpy(c->eye, v, sizeof c->eye);
            memcpy(c->at, v + 3, sizeof c->at);
        }
    }
    double range[2];
    if (((n = get(L, m, "width")) &&
         parse_int_in(L, n, "width", 1, 4096, &o->width) != 0) ||
        ((n = get(L, m, "height")) &&
         parse_int_in(L, n, "height", 1, 4096, &o->height) != 0) ||
        ((n = get(L, m, "fov")) && parse_double(L, n, "fov", &o->fov) != 0) ||
        ((n = get(L, m, "noise")) &&
         parse_double(L, n, "noise", &o->noise) != 0) ||
        ((n = get(L, m, "resolution")) &&
         parse_double(L, n, "resolution", &o->resolution) != 0))
        return -1;
    if ((n = get(L, m, "range")) != NULL) {
        if (numbers(L, n, "range", 2, range) != 0)
            return -1;
        o->near = range[0];
        o->far = range[1];
    }
    if ((n = get(L, m, "seed")) != NULL) {
        const char *s = scalar(n);
        char *end;
        unsigned long long seed = s ? strtoull(s, &end, 10) : 0;
        if (s == NULL || s[0] == '\0' || s[0] == '-' || *end != '\0')
            return fail_at(L, n, "seed must be a whole number >= 0");
        o->seed = (uint64_t)seed;
    }
    char why[256];
    if (mpb_sense_options_check(o, why, sizeof why) != MPB_OK)
        return fail_at(L, m, "sense: %s", why);
    return 0;
}

/* What the cameras of `sense:` (node m) see of scene sc, as its seen
 * scene. */
static int sense_scene(mpbd_loader *L, mpbd_scene *sc, yaml_node_t *m)
{
    mpb_sense_options o;
    char why[512];
    if (read_sense(L, m, &o) != 0)
        return -1;
    if (strcmp(sc->scene_format, "moveit-scene") != 0)
        return fail_at(L, m, "sense: scene '%s' is a '%s' scene; cameras see "
                       "moveit-scene ones only", sc->name, sc->scene_format);
    mpb_scene *truth = NULL;
    if (mpb_scene_open_text(sc->scene, &truth, why, sizeof why) != MPB_OK)
        return fail_at(L, m, "sense: scene '%s': %s", sc->name, why);
    long hits = 0;
    int cells = 0;
    int rc = mpb_scene_sense_text(truth, &o, &sc->seen, &hits, &cells, why,
                                  sizeof why);
    if (rc == MPB_OK && o.num_cameras == 0)
        mpb_sense_default_cameras(truth, &o);
    mpb_scene_close(truth);
    if (rc != MPB_OK)
        return fail_at(L, m, "sense: scene '%s': %s", sc->name, why);
    char how[256];
    snprintf(how, sizeof how, "sensed: %d camera%s %dx%d, fov %g, range "
             "%g..%g m, noise %g m, seed %llu, %g m cells: %d occupied",
             o.num_cameras, o.num_cameras == 1 ? "" : "s", o.width, o.height,
             o.fov, o.near, o.far, o.noise, (unsigned long long)o.seed,
             o.resolution, cells);
    if ((sc->seen_how = strdup(how)) == NULL ||
        (sc->seen_format = strdup(sc->scene_format)) == NULL)
        return fail_at(L, m, "out of memory");
    return 0;
}

int mpbd_load_seen(mpbd_loader *L, mpbd_experiment *e, mpbd_scene *sc,
                   yaml_node_t *entry, int one_scene)
{
    yaml_node_t *m = get(L, entry, "seen");
    char *file = NULL, why[512];
    if (m == NULL)
        return 0;
    if (m->type != YAML_MAPPING_NODE)
        return fail_at(L, m, "seen must be a mapping: a scene (format and "
                       "file or text) or sense: {camera settings}");
    if (get(L, m, "sense") != NULL) {
        static const char *const keys[] = {"sense", NULL};
        if (only_keys(L, m, keys) != 0 ||
            sense_scene(L, sc, get(L, m, "sense")) != 0)
            return -1;
    } else {
        if (!one_scene)
            return fail_at(L, m, "seen: a problem set's scenes each need "
                           "their own; give sense: {camera settings} here");
        if (mpbd_load_model(L, m, "seen", &sc->seen_format, &sc->seen,
                            &file) != 0)
            return free(file), -1;
        char how[4200];
        snprintf(how, sizeof how, "given: %s", file ? file : "inline text");
        free(file);
        if ((sc->seen_how = strdup(how)) == NULL)
            return fail_at(L, m, "out of memory");
    }
    mpb_hash_hex(sc->seen, strlen(sc->seen), sc->seen_hash);
    if (mpbd_scene_world_copy(e, (int)(sc - e->scenes), 1, &sc->seen_world,
                              why, sizeof why) != MPB_OK)
        return fail_at(L, m, "seen: scene '%s': %s", sc->name, why);
    return 0;
}

int mpbd_experiment_seen_note(const mpbd_experiment *e, char *buf, size_t len)
{
    int n = 0, first = -1;
    for (int i = 0; i < e->num_scenes; i++)
        if (e->scenes[i].seen != NULL) {
            n++;
            if (first < 0)
                first = i;
        }
    if (n == 0)
        return 0;
    snprintf(buf, len, "%d of %d scene%s planned on what was seen and judged "
             "on the truth too (the first, '%s': %s)", n, e->num_scenes,
             e->num_scenes == 1 ? "" : "s", e->scenes[first].name,
             e->scenes[first].seen_how);
    return 1;
}
