/*
 * sense.c - `mpb sense SCENE -o SENSED`: what depth cameras would see of a
 * scene (mpbench/sense.h: rays per pixel against the scene's objects,
 * Gaussian noise along each, the hits fused into an occupancy octree),
 * written as a scene of one octree object. This file reads the options;
 * each is checked by mpb_sense_options_check() as it is read, so the
 * ranges are the library's and a bad one is named as the user wrote it.
 */
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/octree.h"
#include "mpbench/scene.h"
#include "mpbench/sense.h"

#include "mpb.h"

#define CMD "sense"

static int parse_numbers(const char *s, double *v, int n)
{
    char *e;
    for (int i = 0; i < n; i++) {
        v[i] = strtod(s, &e);
        if (e == s || !isfinite(v[i]))
            return -1;
        s = e;
        while (*s == ' ' || *s == ',')
            s++;
    }
    return *s ? -1 : 0;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: mpb sense SCENE -o SENSED [options]\n"
            "  --camera 'EX EY EZ AX AY AZ'  a camera at E looking at A (repeat; default:\n"
            "                                two, 1.5 m back and 1 m up, either side)\n"
            "  --width N --height N    pixels (default 160 x 120)\n"
            "  --fov DEG               horizontal field of view (default 60)\n"
            "  --range NEAR FAR        m (default 0.3 4)\n"
            "  --noise SIGMA           m along each ray, Gaussian (default 0.002)\n"
            "  --resolution R          the octree's cells, m (default 0.01)\n"
            "  --seed N                the noise's seed (default 1)\n");
}

/* Whether o is good after one option was set (the others were). */
static int good(const mpb_sense_options *o)
{
    return mpb_sense_options_check(o, NULL, 0) == MPB_OK;
}

/* The number in arg into *field, one of o's; whether both are good. */
static int set_number(mpb_sense_options *o, double *field, const char *arg)
{
    double v;
    if (parse_numbers(arg, &v, 1) != 0)
        return 0;
    *field = v;
    return good(o);
}

int cmd_sense(int argc, char **argv)
{
    mpb_sense_options so;
    mpb_sense_options_init(&so);
    const char *outpath = NULL;
    static const struct option opts[] = {
        {"output", required_argument, NULL, 'o'}, {"camera", required_argument, NULL, 'c'},
        {"width", required_argument, NULL, 'W'},  {"height", required_argument, NULL, 'H'},
        {"fov", required_argument, NULL, 'f'},    {"range", required_argument, NULL, 'r'},
        {"noise", required_argument, NULL, 'n'},  {"resolution", required_argument, NULL, 'R'},
        {"seed", required_argument, NULL, 's'},   {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    opterr = 0;
    optind = 1;
    int opt;
    char why[300];
    while ((opt = getopt_long(argc, argv, ":o:h", opts, NULL)) != -1) {
        double v[6];
        switch (opt) {
        case 'o':
            outpath = optarg;
            break;
        case 'c': {
            if (so.num_cameras == MPB_SENSE_MAX_CAMERAS || parse_numbers(optarg, v, 6) != 0) {
                fprintf(stderr, "mpb sense: --camera needs 'EX EY EZ AX AY AZ' (at most "
                        "%d cameras), not '%s'\n", MPB_SENSE_MAX_CAMERAS, optarg);
                return MPB_EXIT_USAGE;
            }
            mpb_camera *c = &so.cameras[so.num_cameras++];
            memcpy(c->eye, v, 3 * sizeof *v);
            memcpy(c->at, v + 3, 3 * sizeof *v);
            if (mpb_sense_options_check(&so, why, sizeof why) != MPB_OK) {
                fprintf(stderr, "mpb sense: --camera '%s': %s\n", optarg, why);
                return MPB_EXIT_USAGE;
            }
            break;
        }
        case 'W':
        case 'H': {
            int ok = parse_numbers(optarg, v, 1) == 0 && v[0] == floor(v[0]) &&
                     fabs(v[0]) <= INT_MAX;
            if (ok) {
                *(opt == 'W' ? &so.width : &so.height) = (int)v[0];
                ok = good(&so);
            }
            if (!ok) {
                fprintf(stderr, "mpb sense: --%s needs a whole number of pixels from 1 "
                        "to %d, not '%s'\n", opt == 'W' ? "width" : "height",
                        MPB_SENSE_MAX_SIDE, optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        }
        case 'f':
            if (!set_number(&so, &so.fov, optarg)) {
                fprintf(stderr, "mpb sense: --fov needs degrees in (0, %g), not '%s'\n",
                        MPB_SENSE_MAX_FOV, optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        case 'r': {
            int ok = optind < argc && parse_numbers(optarg, v, 1) == 0 &&
                     parse_numbers(argv[optind], v + 1, 1) == 0;
            if (ok) {
                optind++;
                so.near = v[0];
                so.far = v[1];
                ok = good(&so);
            }
            if (!ok) {
                fprintf(stderr, "mpb sense: --range needs NEAR FAR, 0 <= NEAR < FAR\n");
                return MPB_EXIT_USAGE;
            }
            break;
        }
        case 'n':
            if (!set_number(&so, &so.noise, optarg)) {
                fprintf(stderr, "mpb sense: --noise needs a standard deviation >= 0 m, "
                        "not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        case 'R':
            if (!set_number(&so, &so.resolution, optarg)) {
                fprintf(stderr, "mpb sense: --resolution needs %g .. %g m, not '%s'\n",
                        MPB_OCTREE_MIN_RESOLUTION, MPB_OCTREE_MAX_RESOLUTION, optarg);
                return MPB_EXIT_USAGE;
            }
            break;
        case 's': {
            char *e;
            unsigned long long x = strtoull(optarg, &e, 10);
            if (e == optarg || *e || optarg[0] == '-') {
                fprintf(stderr, "mpb sense: --seed needs a whole number >= 0, not '%s'\n",
                        optarg);
                return MPB_EXIT_USAGE;
            }
            so.seed = x;
            break;
        }
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (optind >= argc || !outpath) {
        usage(stderr);
        return MPB_EXIT_USAGE;
    }
    if (optind + 1 < argc)
        return tool_extra_argument(CMD, argv[optind + 1]);
    const char *inpath = argv[optind];
    char err[600];
    mpb_scene *s = NULL;
    if (mpb_scene_open(inpath, &s, err, sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb sense: %s\n", err);
        return MPB_EXIT_ERROR;
    }
    char *text = NULL;
    long hits = 0;
    int cells = 0;
    int rc = mpb_scene_sense_text(s, &so, &text, &hits, &cells, err, sizeof err);
    mpb_scene_close(s);
    if (rc != MPB_OK) {
        fprintf(stderr, "mpb sense: %s: %s\n", inpath, err);
        return MPB_EXIT_ERROR;
    }
    FILE *f = fopen(outpath, "w");
    if (!f) {
        fprintf(stderr, "mpb sense: cannot write %s\n", outpath);
        free(text);
        return MPB_EXIT_ERROR;
    }
    fputs(text, f);
    int bad = ferror(f) | (fclose(f) != 0);
    free(text);
    if (bad) {
        fprintf(stderr, "mpb sense: write error on %s\n", outpath);
        return MPB_EXIT_ERROR;
    }
    printf("%s: %ld hits, %d cells at %g m\n", outpath, hits, cells, so.resolution);
    return MPB_EXIT_OK;
}
