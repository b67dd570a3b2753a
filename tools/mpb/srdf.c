/*
 * srdf.c - `mpb srdf`: writes a robot's allowed-collision matrix (the
 * self-collision pairs mpbench skips) as an SRDF, for the user to review
 * and give back as the robot's `srdf:` in an experiment. Without an SRDF
 * the matrix is the one mpbench generates, as MoveIt's setup assistant
 * does (world.h); with --srdf it is what that SRDF gives (its pairs and
 * the adjacent links), the same way the daemon and the planners read it,
 * and before the pairs what mpbench makes of the SRDF's other elements
 * (srdf.h): its virtual joints, its groups with their joints and whether
 * mpbench can plan them, group states, end effectors, passive joints.
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpb.h"
#include "mpbench/robot.h"
#include "mpbench/srdf.h"

#define CMD "srdf"

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb srdf [-j JOINT,JOINT,... | -g GROUP] [-s SRDF] [-o OUT] "
        "ROBOT.urdf\n"
        "\n"
        "Write the robot's allowed-collision matrix, the pairs of links whose\n"
        "contact mpbench does not count as self-collision, as an SRDF\n"
        "(<disable_collisions link1= link2= reason=/>), to review and give\n"
        "back as the robot's 'srdf:' in an experiment. Without --srdf it is\n"
        "generated as MoveIt's setup assistant does: adjacent links\n"
        "(\"Adjacent\"), pairs in collision at the default state (every joint\n"
        "at 0, or the middle of its limits when 0 is outside; \"Default\"),\n"
        "pairs in collision in more than 95 %% of 200 random states\n"
        "(\"Always\") and pairs never in collision in %d random states of\n"
        "the group (\"Never\"); the states come from a fixed seed, so the same\n"
        "robot gives the same file. Every other pair is checked.\n"
        "\n"
        "Options:\n"
        "  -j, --joints LIST  the planning group, its joints base first,\n"
        "                     comma-separated (default: the robot's longest\n"
        "                     chain of revolute, continuous and prismatic\n"
        "                     joints); the others hold still\n"
        "  -g, --group NAME   the planning group as a group of the SRDF\n"
        "                     (needs --srdf)\n"
        "  -s, --srdf FILE    the matrix that SRDF gives instead: its pairs\n"
        "                     and the adjacent links; before them, for review,\n"
        "                     what mpbench makes of its virtual joints, groups\n"
        "                     (their joints, whether mpbench can plan them),\n"
        "                     group states, end effectors and passive joints;\n"
        "                     its pairs naming links the URDF lacks are left\n"
        "                     out with one warning, as MoveIt does\n"
        "  -o, --output OUT   write to OUT (default: standard output)\n"
        "  -h, --help         print this help\n"
        "\n"
        "Exit status: 0 when written, 1 on an error (a robot or SRDF that\n"
        "does not load: one line naming the file and place), 2 on a bad\n"
        "command line.\n", MPB_WORLD_ACM_SAMPLES);
}

/* Split a comma-separated list in place; the count, or -1 if too many. */
static int split_joints(char *list, char **names, int max)
{
    int n = 0;
    for (char *s = strtok(list, ","); s; s = strtok(NULL, ",")) {
        if (n == max)
            return -1;
        names[n++] = s;
    }
    return n;
}

/* XML attribute text: & < > " escaped. */
static void put_attr(FILE *f, const char *s)
{
    for (; *s; s++)
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
}

/* A number as short as it reads back exactly. */
static void put_number(FILE *f, double v)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%.15g", v);
    if (strtod(buf, NULL) != v)
        snprintf(buf, sizeof buf, "%.17g", v);
    fputs(buf, f);
}

/* One element with its attributes, name="value" pairs, NULL values left
 * out, closed with "/>" or ">" (open). */
static void put_element(FILE *f, const char *indent, const char *tag, int open,
                        const char *const *attrs)
{
    fprintf(f, "%s<%s", indent, tag);
    for (int i = 0; attrs[i]; i += 2) {
        if (!attrs[i + 1])
            continue;
        fprintf(f, " %s=\"", attrs[i]);
        put_attr(f, attrs[i + 1]);
        fputc('"', f);
    }
    fputs(open ? ">\n" : "/>\n", f);
}

/*
 * The SRDF's other elements as mpbench reads them: each group by its
 * joints (MoveIt's rules applied, subgroups included: the same joints as
 * the original's), with a comment saying what mpbench plans of it.
 */
static void write_semantics(FILE *f, const mpb_srdf *s)
{
    for (int i = 0; i < mpb_srdf_num_virtual_joints(s); i++) {
        const mpb_srdf_virtual_joint *v = mpb_srdf_get_virtual_joint(s, i);
        fprintf(f, "  <!-- held at the identity: the root link's frame is "
                   "the world's -->\n");
        put_element(f, "  ", "virtual_joint", 0, (const char *const[]){
            "name", v->name, "type", v->type, "parent_frame", v->parent_frame,
            "child_link", v->child_link, NULL});
    }
    for (int g = 0; g < mpb_srdf_num_groups(s); g++) {
        const mpb_srdf_group *G = mpb_srdf_get_group(s, g);
        char why[512];
        if (mpb_srdf_group_check(s, g, why, sizeof why) == MPB_OK) {
            fprintf(f, "  <!-- group '");
            put_attr(f, G->name);
            fprintf(f, "': mpbench plans %d joint%s, base first:", G->num_active,
                    G->num_active == 1 ? "" : "s");
            for (int j = 0; j < G->num_active; j++) {
                fputs(j ? ", " : " ", f);
                put_attr(f, G->active[j]);
            }
        } else {
            fprintf(f, "  <!-- not planned by mpbench: ");
            put_attr(f, why);
        }
        fprintf(f, " -->\n");
        put_element(f, "  ", "group", 1, (const char *const[]){
            "name", G->name, NULL});
        for (int j = 0; j < G->num_joints; j++)
            put_element(f, "    ", "joint", 0, (const char *const[]){
                "name", G->joints[j], NULL});
        fprintf(f, "  </group>\n");
    }
    for (int i = 0; i < mpb_srdf_num_states(s); i++) {
        const mpb_srdf_state *S = mpb_srdf_get_state(s, i);
        put_element(f, "  ", "group_state", 1, (const char *const[]){
            "name", S->name, "group", S->group, NULL});
        for (int j = 0; j < S->num_values; j++) {
            fprintf(f, "    <joint name=\"");
            put_attr(f, S->joints[j]);
            fprintf(f, "\" value=\"");
            put_number(f, S->values[j]);
            fprintf(f, "\"/>\n");
        }
        fprintf(f, "  </group_state>\n");
    }
    for (int i = 0; i < mpb_srdf_num_end_effectors(s); i++) {
        const mpb_srdf_end_effector *e = mpb_srdf_get_end_effector(s, i);
        put_element(f, "  ", "end_effector", 0, (const char *const[]){
            "name", e->name, "group", e->group, "parent_link", e->parent_link,
            "parent_group", e->parent_group, NULL});
    }
    for (int i = 0; i < mpb_srdf_num_passive_joints(s); i++)
        put_element(f, "  ", "passive_joint", 0, (const char *const[]){
            "name", mpb_srdf_passive_joint(s, i, NULL), NULL});
}

static int write_srdf(FILE *f, mpb_world *w, const char *robot_name,
                      const char *urdf_path, const char *srdf_path,
                      const mpb_srdf *sem)
{
    int n = mpb_world_num_allowed_pairs(w);
    fprintf(f, "<?xml version=\"1.0\"?>\n<!--\n  The allowed-collision matrix "
               "of ");
    put_attr(f, urdf_path);
    if (srdf_path) {
        fprintf(f, "\n  as ");
        put_attr(f, srdf_path);
        fprintf(f, " gives it (its pairs and the adjacent links),");
        if (sem && mpb_srdf_num_skipped_pairs(sem) > 0)
            fprintf(f, "\n  leaving out %d of its pairs that name links the "
                       "URDF lacks,", mpb_srdf_num_skipped_pairs(sem));
    } else {
        fprintf(f, ",\n  generated by mpb srdf as MoveIt's setup assistant "
                   "does (%d random\n  states),", MPB_WORLD_ACM_SAMPLES);
    }
    fprintf(f, " %d pairs. Every other pair of links is\n  checked for "
               "self-collision.\n-->\n<robot name=\"", n);
    put_attr(f, robot_name);
    fprintf(f, "\">\n");
    if (sem)
        write_semantics(f, sem);
    for (int i = 0; i < n; i++) {
        mpb_world_acm_pair p;
        if (mpb_world_allowed_pair(w, i, &p) != MPB_OK)
            return -1;
        fprintf(f, "  <disable_collisions link1=\"");
        put_attr(f, p.link1);
        fprintf(f, "\" link2=\"");
        put_attr(f, p.link2);
        fprintf(f, "\" reason=\"");
        put_attr(f, p.reason);
        fprintf(f, "\"/>\n");
    }
    fprintf(f, "</robot>\n");
    return 0;
}

int cmd_srdf(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"joints", required_argument, NULL, 'j'},
        {"group",  required_argument, NULL, 'g'},
        {"srdf",   required_argument, NULL, 's'},
        {"output", required_argument, NULL, 'o'},
        {"help",   no_argument,       NULL, 'h'},
        {NULL, 0, NULL, 0}
    };
    char *joint_list = NULL;
    const char *srdf_path = NULL, *out_path = NULL, *group = NULL;
    int opt;
    opterr = 0;
    optind = 1;
    while ((opt = getopt_long(argc, argv, ":j:g:s:o:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'j': joint_list = optarg; break;
        case 'g': group = optarg; break;
        case 's': srdf_path = optarg; break;
        case 'o': out_path = optarg; break;
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (optind >= argc) {
        fprintf(stderr, "mpb %s: expected the robot's URDF file (try 'mpb %s "
                "--help')\n", CMD, CMD);
        return MPB_EXIT_USAGE;
    }
    const char *urdf_path = argv[optind++];
    if (optind < argc)
        return tool_extra_argument(CMD, argv[optind]);
    if (group && (joint_list || !srdf_path)) {
        fprintf(stderr, "mpb %s: --group needs --srdf, and goes without "
                "--joints\n", CMD);
        return MPB_EXIT_USAGE;
    }

    enum { MAX_JOINTS = 256 };
    char *names[MAX_JOINTS];
    int num_joints = 0;
    if (joint_list) {
        num_joints = split_joints(joint_list, names, MAX_JOINTS);
        if (num_joints <= 0) {
            fprintf(stderr, "mpb %s: --joints needs 1 to %d joint names, "
                    "comma-separated\n", CMD, MAX_JOINTS);
            return MPB_EXIT_USAGE;
        }
    }

    int rc = MPB_EXIT_ERROR;
    size_t ulen, slen = 0;
    char *urdf = mpb_read_file(urdf_path, 0, &ulen);
    char *srdf = NULL, *text = NULL;
    char err[512];
    mpb_robot *robot = NULL;
    mpb_world *w = NULL;
    mpb_srdf *sem = NULL;
    FILE *f = NULL;
    if (urdf == NULL) {
        fprintf(stderr, "mpb %s: cannot read %s: %s\n", CMD, urdf_path,
                strerror(errno));
        goto done;
    }
    if (srdf_path && (srdf = mpb_read_file(srdf_path, 0, &slen)) == NULL) {
        fprintf(stderr, "mpb %s: cannot read %s: %s\n", CMD, srdf_path,
                strerror(errno));
        goto done;
    }
    /* The SRDF read against the URDF: its groups, and the group named. */
    if (srdf && mpb_srdf_open(urdf, srdf, &sem, err, sizeof err) != MPB_OK) {
        /* "srdf line 3: ..." is the SRDF file's line 3. */
        if (strncmp(err, "srdf ", 5) == 0)
            fprintf(stderr, "mpb %s: %s: %s\n", CMD, srdf_path, err + 5);
        else
            fprintf(stderr, "mpb %s: %s: %s\n", CMD, urdf_path, err);
        goto done;
    }
    /* Pairs naming links the URDF lacks: skipped, as MoveIt does. */
    if (sem && mpb_srdf_skipped_pairs(sem))
        fprintf(stderr, "mpb %s: warning: %s: %s\n", CMD, srdf_path,
                mpb_srdf_skipped_pairs(sem));
    if (group) {
        int g = mpb_srdf_group_index(sem, group);
        if (g < 0) {
            fprintf(stderr, "mpb %s: %s has no group '%s'\n", CMD, srdf_path,
                    group);
            goto done;
        }
        if (mpb_srdf_group_check(sem, g, err, sizeof err) != MPB_OK) {
            fprintf(stderr, "mpb %s: %s: %s\n", CMD, srdf_path, err);
            goto done;
        }
        const mpb_srdf_group *G = mpb_srdf_get_group(sem, g);
        for (int j = 0; j < G->num_active && j < MAX_JOINTS; j++)
            names[num_joints++] = (char *)G->active[j];
    }
    /* The robot alone first: its name, and the group when none is given. */
    if ((joint_list || group ? mpb_robot_open_urdf_joints(urdf,
                                                 (const char *const *)names,
                                                 num_joints, &robot, err, sizeof err)
                    : mpb_robot_open_urdf(urdf, NULL, NULL, &robot, err,
                                          sizeof err)) != MPB_OK) {
        fprintf(stderr, "mpb %s: %s: %s\n", CMD, urdf_path, err);
        goto done;
    }
    if (!joint_list && !group) {
        num_joints = mpb_robot_num_joints(robot);
        for (int j = 0; j < num_joints && j < MAX_JOINTS; j++)
            names[j] = (char *)mpb_robot_get_joint(robot, j)->name;
    }
    /* The SRDF goes on the line after the URDF (world.h). */
    text = malloc(ulen + slen + 2);
    if (text == NULL) {
        fprintf(stderr, "mpb %s: out of memory\n", CMD);
        goto done;
    }
    snprintf(text, ulen + slen + 2, "%s%s%s", urdf,
             srdf && ulen > 0 && urdf[ulen - 1] != '\n' ? "\n" : "",
             srdf ? srdf : "");
    /* The URDF's folder: where its meshes are looked for last. */
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", urdf_path);
    char *slash = strrchr(dir, '/');
    if (slash)
        slash[1] = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    if (mpb_world_open_group_in("urdf", text, dir, "moveit-scene",
                                "(no scene)\n.\n", (const char *const *)names,
                                num_joints, &w, err, sizeof err) != MPB_OK) {
        /* "srdf line 3: ..." is the SRDF file's line 3. */
        if (srdf && strncmp(err, "srdf ", 5) == 0)
            fprintf(stderr, "mpb %s: %s: %s\n", CMD, srdf_path, err + 5);
        else
            fprintf(stderr, "mpb %s: %s: %s\n", CMD, urdf_path, err);
        goto done;
    }
    f = out_path ? fopen(out_path, "w") : stdout;
    if (f == NULL) {
        fprintf(stderr, "mpb %s: cannot write %s: %s\n", CMD, out_path,
                strerror(errno));
        goto done;
    }
    if (write_srdf(f, w, mpb_robot_name(robot), urdf_path, srdf_path, sem) != 0 ||
        fflush(f) != 0 || ferror(f)) {
        fprintf(stderr, "mpb %s: cannot write %s: %s\n", CMD,
                out_path ? out_path : "standard output", strerror(errno));
        goto done;
    }
    rc = MPB_EXIT_OK;
done:
    if (f && f != stdout && fclose(f) != 0 && rc == MPB_EXIT_OK) {
        fprintf(stderr, "mpb %s: cannot write %s: %s\n", CMD, out_path,
                strerror(errno));
        rc = MPB_EXIT_ERROR;
    }
    mpb_world_close(w);
    mpb_srdf_close(sem);
    mpb_robot_close(robot);
    free(text);
    free(srdf);
    free(urdf);
    return rc;
}
