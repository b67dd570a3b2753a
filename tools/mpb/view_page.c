/*
 * view_page.c - the page `mpb view` writes: the template (view_page.html,
 * with its script view_page.js, both built into mpb), the run's data as
 * JSON with the numbers in base64 (Float32Array / Uint32Array, little-
 * endian, each mesh once), and three.js inlined, so that it opens offline.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "view.h"

/* Built from view_page.html and view_page.js (tools/CMakeLists.txt). */
extern const char mpb_view_page_html[];
extern const char mpb_view_page_js[];

/* ---- JSON ---------------------------------------------------------------- */

/* A JSON string that is also safe inside a <script> element: '<', '>' and
 * '&' as \u escapes, so no "</script>" can end it early. */
static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
        if (*p == '"' || *p == '\\')
            fprintf(f, "\\%c", *p);
        else if (*p < 0x20 || *p == '<' || *p == '>' || *p == '&')
            fprintf(f, "\\u%04x", *p);
        else
            fputc(*p, f);
    }
    fputc('"', f);
}

static void json_num(FILE *f, double v)
{
    if (v != v || v > 1e300 || v < -1e300)
        fputs("null", f);
    else
        fprintf(f, "%.9g", v);
}

static void json_nums(FILE *f, const double *v, int n)
{
    fputc('[', f);
    for (int i = 0; i < n; i++) {
        if (i)
            fputc(',', f);
        json_num(f, v[i]);
    }
    fputc(']', f);
}

static void json_floats(FILE *f, const float *v, int n)
{
    fputc('[', f);
    for (int i = 0; i < n; i++) {
        if (i)
            fputc(',', f);
        json_num(f, v[i]);
    }
    fputc(']', f);
}

/* ---- base64 of 32-bit numbers, little-endian ------------------------------ */

typedef struct b64 {
    FILE         *f;
    unsigned char in[3];
    int           n;
} b64;

static const char B64[] =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static void b64_byte(b64 *b, unsigned char c)
{
    b->in[b->n++] = c;
    if (b->n < 3)
        return;
    fputc(B64[b->in[0] >> 2], b->f);
    fputc(B64[((b->in[0] & 3) << 4) | (b->in[1] >> 4)], b->f);
    fputc(B64[((b->in[1] & 15) << 2) | (b->in[2] >> 6)], b->f);
    fputc(B64[b->in[2] & 63], b->f);
    b->n = 0;
}

static void b64_u32(b64 *b, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        b64_byte(b, (unsigned char)(v >> (8 * i)));
}

static void b64_end(b64 *b)
{
    if (b->n == 0)
        return;
    unsigned char c0 = b->in[0], c1 = b->n > 1 ? b->in[1] : 0;
    fputc(B64[c0 >> 2], b->f);
    fputc(B64[((c0 & 3) << 4) | (c1 >> 4)], b->f);
    fputc(b->n > 1 ? B64[(c1 & 15) << 2] : '=', b->f);
    fputc('=', b->f);
    b->n = 0;
}

static void json_b64_floats(FILE *f, const float *v, size_t n)
{
    b64 b = {f, {0}, 0};
    fputc('"', f);
    for (size_t i = 0; i < n; i++) {
        uint32_t u;
        memcpy(&u, &v[i], sizeof u);
        b64_u32(&b, u);
    }
    b64_end(&b);
    fputc('"', f);
}

/* ---- the run as JSON ----------------------------------------------------- */

static void json_pose(FILE *f, const mpb_pose *p)
{
    double q[4];
    mpb_pose_get_quat(p, q);
    double v[7] = {p->t[0], p->t[1], p->t[2], q[0], q[1], q[2], q[3]};
    json_nums(f, v, 7);
}

/* Every distinct mesh, once; shapes refer to them by index. */
typedef struct mesh_list {
    const mpb_mesh **m;
    int              n, cap;
} mesh_list;

static int mesh_index(mesh_list *l, const mpb_mesh *m)
{
    for (int i = 0; i < l->n; i++)
        if (l->m[i] == m)
            return i;
    if (mpb__grow((void **)&l->m, &l->cap, l->n + 1, sizeof *l->m) != MPB_OK)
        return -1;
    l->m[l->n] = m;
    return l->n++;
}

static void json_meshes(FILE *f, const mesh_list *l)
{
    fputs("[", f);
    for (int i = 0; i < l->n; i++) {
        const mpb_mesh *m = l->m[i];
        b64 b = {f, {0}, 0};
        fputs(i ? ",{\"v\":\"" : "{\"v\":\"", f);
        for (int k = 0; k < 3 * m->num_vertices; k++) {
            float x = (float)m->vertices[k];
            uint32_t u;
            memcpy(&u, &x, sizeof u);
            b64_u32(&b, u);
        }
        b64_end(&b);
        fputs("\",\"i\":\"", f);
        for (int k = 0; k < 3 * m->num_triangles; k++)
            b64_u32(&b, (uint32_t)m->triangles[k]);
        b64_end(&b);
        fputs("\"}", f);
    }
    fputs("]", f);
}

/* The bodies of b, each at its pose in poses (7 floats a body); with
 * obstacles_only, the scene's alone (what was seen: the robot is the
 * truth's). */
static int json_bodies(FILE *f, const mpb_bodies *bodies, const float *poses,
                       int obstacles_only, mesh_list *meshes)
{
    int nb = mpb_bodies_count(bodies), written = 0;
    fputs("[", f);
    for (int i = 0; i < nb; i++) {
        const mpb_body *b = mpb_bodies_get(bodies, i);
        if (obstacles_only && b->robot)
            continue;
        fputs(written++ ? ",\n{\"name\":" : "\n{\"name\":", f);
        json_str(f, b->name);
        fprintf(f, ",\"robot\":%d,\"moves\":%d,\"pose\":", b->robot, b->moves);
        json_floats(f, poses + 7 * i, 7);
        fputs(",\"shapes\":[", f);
        for (int k = 0; k < b->num_shapes; k++) {
            const mpb_body_shape *s = &b->shapes[k];
            fputs(k ? ",{\"type\":" : "{\"type\":", f);
            json_str(f, mpb_shape_type_name(s->geometry.type));
            fputs(",\"dims\":", f);
            json_nums(f, s->geometry.dims, 4);
            if (s->geometry.type == MPB_SHAPE_MESH) {
                int m = mesh_index(meshes, s->geometry.mesh);
                if (m < 0)
                    return -1;
                fprintf(f, ",\"mesh\":%d", m);
            }
            fputs(",\"offset\":", f);
            json_pose(f, &s->offset);
            if (s->color[3] > 0) {
                fputs(",\"color\":", f);
                json_floats(f, s->color, 4);
            }
            fputs("}", f);
        }
        fputs("]}", f);
    }
    fputs("]", f);
    return 0;
}

static void json_stage(FILE *f, const view_run *v, const view_stage *s)
{
    fputs("{\"name\":", f);
    json_str(f, s->name);
    fprintf(f, ",\"valid\":%d,\"verdict\":", s->valid);
    json_str(f, s->verdict);
    fputs(",\"detail\":", f);
    json_str(f, s->detail);
    fprintf(f, ",\"segment\":%d,\"waypoints\":%d,\"frames\":%d,"
            "\"fail_frame\":%d,\"frame_at\":", s->segment, s->num_waypoints,
            s->num_frames, s->fail_frame);
    json_b64_floats(f, s->frame_at, (size_t)s->num_frames);
    fputs(",\"poses\":", f);
    json_b64_floats(f, s->poses, (size_t)s->num_frames * v->num_moving * 7);
    if (s->has_collision) {
        /* s exactly: the certified check names it with 17 digits. */
        fprintf(f, ",\"collision\":{\"s\":%.17g,\"certified\":%d,"
                "\"q\":", s->collision_s, s->collision_certified);
        json_nums(f, s->collision_q, v->num_joints);
        fprintf(f, ",\"bodies\":[%d,%d],\"poses\":", s->contact[0],
                s->contact[1]);
        json_b64_floats(f, s->collision_poses, (size_t)v->num_moving * 7);
        fputs("}", f);
    }
    fputs("}", f);
}

static int json_run(FILE *f, const view_run *v)
{
    mesh_list meshes = {0};
    const mpb_run_detail *r = &v->run;
    fputs("{\"run\":{\"id\":", f);
    fprintf(f, "%lld,\"experiment\":", (long long)r->run_id);
    json_str(f, v->experiment);
    fprintf(f, ",\"experiment_id\":%lld,\"planner\":",
            (long long)r->experiment_id);
    json_str(f, r->planner_config);
    fputs(",\"planner_id\":", f);
    json_str(f, r->planner_id);
    fputs(",\"scene\":", f);
    json_str(f, v->scene);
    fputs(",\"query\":", f);
    json_str(f, v->query);
    char place[512];
    fputs(",\"place\":", f);
    json_str(f, view_place(v->scene, v->query, place, sizeof place));
    fprintf(f, ",\"repetition\":%d,\"status\":", r->repetition);
    json_str(f, *r->status ? r->status : r->state);
    fprintf(f, ",\"success\":%d,\"verdict\":", r->success);
    json_str(f, r->verdict);
    fputs(",\"message\":", f);
    json_str(f, r->message);
    fputs(",\"time_total\":", f);
    json_num(f, r->time_total);
    fputs("},\n\"format\":", f);
    json_str(f, v->robot_format);
    fputs(",\"resolution\":", f);
    json_num(f, v->resolution);
    fprintf(f, ",\"resolution_known\":%d,\"joints\":[", v->resolution_known);
    for (int j = 0; j < v->num_joints; j++) {
        if (j)
            fputc(',', f);
        json_str(f, v->joint_names[j]);
    }
    fputs("],\"start\":", f);
    json_nums(f, v->start, v->num_joints);
    fputs(",\"held\":{", f);
    for (int j = 0; j < v->num_held; j++) {
        if (j)
            fputc(',', f);
        json_str(f, v->held_names[j]);
        fputc(':', f);
        json_num(f, v->held_values[j]);
    }
    fputc('}', f);
    fputs(",\"moving\":[", f);
    for (int m = 0; m < v->num_moving; m++)
        fprintf(f, m ? ",%d" : "%d", v->moving[m]);
    fputs("],\"start_poses\":", f);
    json_b64_floats(f, v->start_poses, (size_t)v->num_moving * 7);
    fputs(",\n\"goal\":", f);
    if (v->goal_kind == MPB_GOAL_JOINTS && v->goal_poses) {
        fputs("{\"kind\":\"joints\",\"joints\":", f);
        json_nums(f, v->goal_joints, v->num_joints);
        fputs(",\"poses\":", f);
        json_b64_floats(f, v->goal_poses, (size_t)v->num_moving * 7);
        fputs("}", f);
    } else if (v->goal_kind == MPB_GOAL_POSE_REGION) {
        fputs("{\"kind\":\"region\",\"link\":", f);
        json_str(f, v->goal_link);
        fputs(",\"center\":", f);
        json_nums(f, v->goal_region, 3);
        fputs(",\"half\":", f);
        json_nums(f, v->goal_region + 3, 3);
        fputs(",\"rpy\":", f);
        json_nums(f, v->goal_region + 6, 3);
        fputs(",\"tolerance\":", f);
        json_nums(f, v->goal_region + 9, 3);
        fputs("}", f);
    } else {
        fputs("null", f);
    }
    fputs(",\n\"bodies\":", f);
    if (json_bodies(f, v->bodies, v->static_poses, 0, &meshes) != 0) {
        free(meshes.m);
        return -1;
    }
    /* What its planner was given instead of the scene, and the run as
     * judged there. */
    fputs(",\n\"seen\":", f);
    if (v->seen_bodies != NULL) {
        fputs("{\"how\":", f);
        json_str(f, v->seen_how ? v->seen_how : "");
        fprintf(f, ",\"success\":%d,\"verdict\":", v->seen_success);
        json_str(f, v->seen_verdict ? v->seen_verdict : "");
        fputs(",\"detail\":", f);
        json_str(f, v->seen_detail ? v->seen_detail : "");
        fputs(",\"bodies\":", f);
        if (json_bodies(f, v->seen_bodies, v->seen_poses, 1, &meshes) != 0) {
            free(meshes.m);
            return -1;
        }
        fputs("}", f);
    } else {
        fputs("null", f);
    }
    fputs(",\n\"meshes\":", f);
    json_meshes(f, &meshes);
    free(meshes.m);
    fputs(",\n\"stages\":[", f);
    for (int i = 0; i < v->num_stages; i++) {
        if (i)
            fputs(",\n", f);
        json_stage(f, v, &v->stages[i]);
    }
    fputs("]}", f);
    return 0;
}

/* ---- the page ------------------------------------------------------------ */

/* Write the template from *at up to the marker (or its end); *at then
 * points past the marker. */
static void template_to(FILE *f, const char **at, const char *marker)
{
    const char *m = strstr(*at, marker);
    size_t n = m ? (size_t)(m - *at) : strlen(*at);
    fwrite(*at, 1, n, f);
    *at += n + (m ? strlen(marker) : 0);
}

void view_html_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '<')
            fputs("&lt;", f);
        else if (*s == '>')
            fputs("&gt;", f);
        else if (*s == '&')
            fputs("&amp;", f);
        else if (*s == '"')
            fputs("&quot;", f);
        else
            fputc(*s, f);
    }
}

const char *view_place(const char *scene, const char *query, char *buf,
                       size_t n)
{
    scene = scene ? scene : "";
    query = query ? query : "";
    size_t k = strlen(scene);
    if (*scene == '\0' || strcmp(scene, query) == 0 ||
        (strncmp(query, scene, k) == 0 && query[k] == '/'))
        snprintf(buf, n, "%s", query);
    else if (*query == '\0')
        snprintf(buf, n, "%s", scene);
    else
        snprintf(buf, n, "%s / %s", scene, query);
    return buf;
}

int view_write_page(const view_run *v, const char *three_js, FILE *f)
{
    const char *at = mpb_view_page_html;
    char title[1024], place[512];
    snprintf(title, sizeof title, "mpb view: run %lld, %s, %s",
             (long long)v->run.run_id, v->run.planner_config,
             view_place(v->scene, v->query, place, sizeof place));
    template_to(f, &at, "@TITLE@");
    view_html_text(f, title);
    template_to(f, &at, "@DATA@");
    if (json_run(f, v) != 0)
        return -1;
    template_to(f, &at, "@THREE@");
    fputs(three_js, f);
    template_to(f, &at, "@SCRIPT@");
    fputs(mpb_view_page_js, f);
    template_to(f, &at, "@END@");
    return ferror(f) ? -1 : 0;
}
