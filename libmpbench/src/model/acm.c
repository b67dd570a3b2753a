/*
 * acm.c - the allowed-collision matrix of a "urdf" world: the SRDF's
 * <disable_collisions> pairs plus the adjacent links when the robot text
 * carries an SRDF, else generated as MoveIt's setup assistant does
 * (acm_generate()); then the collision world told to skip those pairs.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/world.h"
#include "core/errbuf.h"
#include "model/srdf_xml.h"
#include "model/world_urdf.h"
#include "geometry/collision_internal.h"

/* The reasons a pair is allowed, as MoveIt's setup assistant writes them. */
static const char REASON_ADJACENT[] = "Adjacent";
static const char REASON_DEFAULT[] = "Default";
static const char REASON_ALWAYS[] = "Always";
static const char REASON_NEVER[] = "Never";

/* The setup assistant's batch for "Always" pairs (its SMALL_TRIAL_COUNT). */
#define ACM_BATCH 200

/* Allow the pair (a, b) for `reason`, unless it is allowed already. */
static void acm_allow(urdf_world *u, int a, int b, const char *reason)
{
    if (a == b || *acm_at(u, a, b))
        return;
    *acm_at(u, a, b) = *acm_at(u, b, a) = reason;
}

/*
 * Adjacent links, as MoveIt's setup assistant finds them: parent and child
 * are connected, whatever the joint (fixed ones too); then, again and
 * again until nothing changes, every two links connected to a link without
 * shapes are connected to each other. Adjacent are the connected pairs of
 * links that both have shapes.
 */
static int acm_adjacent(urdf_world *u)
{
    int n = u->num_links;
    unsigned char *g = calloc((size_t)n * (size_t)n + 1, 1);
    if (!g)
        return MPB_ENOMEM;
    for (int l = 0; l < n; l++) {
        int p = mpb_robot_get_link(u->robot, l)->parent;
        if (p >= 0)
            g[(size_t)l * n + p] = g[(size_t)p * n + l] = 1;
    }
    for (int changed = 1; changed;) {
        changed = 0;
        for (int l = 0; l < n; l++) {
            if (has_body(u, l))
                continue;
            for (int i = 0; i < n; i++)
                for (int j = i + 1; g[(size_t)l * n + i] && j < n; j++)
                    if (g[(size_t)l * n + j] && i != j && !g[(size_t)i * n + j]) {
                        g[(size_t)i * n + j] = g[(size_t)j * n + i] = 1;
                        changed = 1;
                    }
        }
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            if (g[(size_t)i * n + j] && has_body(u, i) && has_body(u, j))
                acm_allow(u, i, j, REASON_ADJACENT);
    free(g);
    return MPB_OK;
}

/*
 * The rest of MoveIt's setup assistant's matrix, after the adjacent pairs:
 * the pairs in collision at the default state ("Default"), the pairs in
 * collision nearly always ("Always"), then the pairs never in collision in
 * MPB_WORLD_ACM_SAMPLES random states ("Never"), all drawn from a fixed
 * seed. Pairs of fixed links are decided by the default state alone: they
 * never move.
 */
static int acm_generate(urdf_world *u, const double *q0)
{
    const mpb_robot *r = u->robot;
    int n = u->num_links, nj = mpb_robot_num_joints(r), rc = MPB_OK;
    int *cand = malloc(((size_t)n * (size_t)n + 1) * 2 * sizeof *cand);
    int *count = NULL;
    unsigned char *seen = NULL;
    double *q = malloc(((size_t)nj + 1) * sizeof *q);
    if (!cand || !q) {
        free(cand);
        free(q);
        return MPB_ENOMEM;
    }
    if (mpb__urdf_place(u, q0) != MPB_OK) {
        rc = MPB_EINVAL;
        goto done;
    }
    int nc = 0;
    for (int a = 0; a < n; a++)
        for (int b = a + 1; has_body(u, a) && b < n; b++) {
            if (!has_body(u, b) || *acm_at(u, a, b))
                continue;
            int hit = mpb__collision_check_pair(u->coll, a, b);
            if (hit < 0) {
                rc = hit;
                goto done;
            }
            const mpb_robot_link *la = mpb_robot_get_link(r, a);
            const mpb_robot_link *lb = mpb_robot_get_link(r, b);
            if (hit)
                acm_allow(u, a, b, REASON_DEFAULT);
            else if (!la->moves && !lb->moves)
                acm_allow(u, a, b, REASON_NEVER);
            else {
                cand[2 * nc] = a;
                cand[2 * nc + 1] = b;
                nc++;
            }
        }
    uint64_t rng = MPB_WORLD_ACM_SEED;
    /* "Always": batches of ACM_BATCH random states; a pair in collision in
     * more than 95 % of a batch is allowed, until a batch allows none.
     * A pair seen in collision here is no "Never" pair. */
    count = calloc((size_t)nc + 1, sizeof *count);
    seen = calloc((size_t)nc + 1, 1);
    if (!count || !seen) {
        rc = MPB_ENOMEM;
        goto done;
    }
    for (int found = 1; found && nc > 0;) {
        memset(count, 0, (size_t)nc * sizeof *count);
        for (int s = 0; s < ACM_BATCH; s++) {
            mpb_robot_random_config(r, &rng, q);
            if (mpb__urdf_place(u, q) != MPB_OK) {
                rc = MPB_EINVAL;
                goto done;
            }
            for (int i = 0; i < nc; i++) {
                int hit = mpb__collision_check_pair(u->coll, cand[2 * i],
                                                   cand[2 * i + 1]);
                if (hit < 0) {
                    rc = hit;
                    goto done;
                }
                count[i] += hit;
                seen[i] |= (unsigned char)hit;
            }
        }
        found = 0;
        for (int i = 0; i < nc;) {
            if (count[i] * 100 <= ACM_BATCH * 95) {
                i++;
                continue;
            }
            acm_allow(u, cand[2 * i], cand[2 * i + 1], REASON_ALWAYS);
            found = 1;
            nc--;
            cand[2 * i] = cand[2 * nc];
            cand[2 * i + 1] = cand[2 * nc + 1];
            count[i] = count[nc];
            seen[i] = seen[nc];
        }
    }
    for (int i = 0; i < nc;) {
        if (!seen[i]) {
            i++;
            continue;
        }
        nc--;
        cand[2 * i] = cand[2 * nc];
        cand[2 * i + 1] = cand[2 * nc + 1];
        seen[i] = seen[nc];
    }
    /* "Never": each pair seen in collision leaves the candidates. */
    for (int s = 0; s < MPB_WORLD_ACM_SAMPLES && nc > 0; s++) {
        mpb_robot_random_config(r, &rng, q);
        if (mpb__urdf_place(u, q) != MPB_OK) {
            rc = MPB_EINVAL;
            goto done;
        }
        for (int i = 0; i < nc;) {
            int hit = mpb__collision_check_pair(u->coll, cand[2 * i], cand[2 * i + 1]);
            if (hit < 0) {
                rc = hit;
                goto done;
            }
            if (hit) {
                nc--;
                cand[2 * i] = cand[2 * nc];
                cand[2 * i + 1] = cand[2 * nc + 1];
            } else {
                i++;
            }
        }
    }
    for (int i = 0; i < nc; i++)
        acm_allow(u, cand[2 * i], cand[2 * i + 1], REASON_NEVER);
done:
    free(cand);
    free(count);
    free(seen);
    free(q);
    return rc;
}

/* The SRDF's pairs; those naming a link the robot lacks are skipped, as
 * MoveIt does (mpb_srdf_skipped_pairs() says which, for a warning). */
static void acm_from_srdf(urdf_world *u)
{
    const mpb__srdf *raw = mpb__srdf_raw(u->srdf);
    for (int i = 0; i < raw->num_pairs; i++) {
        const mpb__srdf_pair *p = &raw->pairs[i];
        int a = mpb_robot_link_index(u->robot, p->link1);
        int b = mpb_robot_link_index(u->robot, p->link2);
        if (a >= 0 && b >= 0)
            acm_allow(u, a, b, p->reason);
    }
}

int mpb__urdf_build_acm(urdf_world *u, const double *q0, char *err,
                        size_t errlen)
{
    int n = u->num_links, rc;
    u->allowed = calloc((size_t)n * (size_t)n + 1, sizeof *u->allowed);
    if (!u->allowed)
        return MPB_ENOMEM;
    if (u->from_srdf)
        acm_from_srdf(u);
    if ((rc = acm_adjacent(u)) != MPB_OK)
        return rc;
    if (!u->from_srdf && (rc = acm_generate(u, q0)) != MPB_OK) {
        mpb__set_err(err, errlen, "robot: self-collision matrix: %s",
                     mpb_collision_errmsg(u->coll));
        return rc;
    }
    u->pairs = malloc(((size_t)n * (size_t)n + 1) * sizeof *u->pairs);
    if (!u->pairs)
        return MPB_ENOMEM;
    u->acm_in_coll = 1;
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            int fixed = !mpb_robot_get_link(u->robot, a)->moves &&
                        !mpb_robot_get_link(u->robot, b)->moves;
            if (*acm_at(u, a, b)) {
                u->pairs[2 * u->num_pairs] = a;
                u->pairs[2 * u->num_pairs + 1] = b;
                u->num_pairs++;
            }
            if ((*acm_at(u, a, b) || fixed) && has_body(u, a) &&
                has_body(u, b) &&
                (rc = mpb__collision_allow_pair(u->coll, a, b)) != MPB_OK)
                return rc;
        }
    if ((rc = mpb__urdf_find_wrists(u)) != MPB_OK)
        mpb__set_err(err, errlen, "robot: wrist tables: %s",
                     rc == MPB_ENOMEM ? "out of memory" : "FCL failed");
    return rc;
}
