/*
 * mesh_assimp.cpp - triangle meshes: allocation and checks, URI resolution
 * against a search path, and loading through assimp. The C++ stays inside;
 * every extern "C" function catches every exception.
 */
#include "mpbench/mpbench.h"
#include "mpbench/mesh.h"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/version.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <sys/stat.h>

#include "core/cxx_guard.h"
#include "core/errbuf.h"
#include "geometry/mesh_cache.h"
#include "geometry/mesh.h"

namespace {

bool is_file(const std::string &path)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string join(const char *dir, const std::string &rel)
{
    std::string s(dir);
    while (s.size() > 1 && s.back() == '/')
        s.pop_back();
    if (!s.empty() && s.back() != '/')
        s += '/';
    return s + rel;
}

/* The last component of a directory path, trailing slashes ignored. */
std::string basename_of(const char *dir)
{
    std::string s(dir);
    while (s.size() > 1 && s.back() == '/')
        s.pop_back();
    size_t slash = s.rfind('/');
    return slash == std::string::npos ? s : s.substr(slash + 1);
}

/* Length of a URI scheme followed by "://", or 0 if there is none. */
size_t scheme_len(const char *uri)
{
    size_t i = 0;
    if (!((uri[0] >= 'a' && uri[0] <= 'z') || (uri[0] >= 'A' && uri[0] <= 'Z')))
        return 0;
    while (uri[i] && (isalnum((unsigned char)uri[i]) || uri[i] == '+' ||
                      uri[i] == '-' || uri[i] == '.'))
        i++;
    return strncmp(uri + i, "://", 3) == 0 ? i : 0;
}

int resolve(const char *uri, const char *const *dirs, int num_dirs,
            std::string &out, char *err, size_t errlen)
{
    if (!uri || !*uri) {
        mpb__set_err(err, errlen, "mesh: empty URI");
        return MPB_EINVAL;
    }
    if (num_dirs < 0 || (num_dirs > 0 && !dirs)) {
        mpb__set_err(err, errlen, "mesh '%s': bad search path", uri);
        return MPB_EINVAL;
    }
    size_t sl = scheme_len(uri);
    if (sl == 7 && strncmp(uri, "package", 7) == 0) {
        const char *pkg = uri + 10;
        const char *slash = strchr(pkg, '/');
        if (!slash || slash == pkg || !slash[1]) {
            mpb__set_err(err, errlen, "mesh '%s': expected package://<package>/<path>", uri);
            return MPB_EINVAL;
        }
        std::string name(pkg, (size_t)(slash - pkg)), rel(slash + 1);
        for (int i = 0; i < num_dirs; i++) {
            if (!dirs[i] || !*dirs[i])
                continue;
            std::string p = join(dirs[i], name + "/" + rel);
            if (is_file(p)) {
                out = p;
                return MPB_OK;
            }
            if (basename_of(dirs[i]) == name) {
                p = join(dirs[i], rel);
                if (is_file(p)) {
                    out = p;
                    return MPB_OK;
                }
            }
        }
        mpb__set_err(err, errlen, "mesh '%s': not found (package '%s' looked for in "
                     "%d search director%s)", uri, name.c_str(), num_dirs,
                     num_dirs == 1 ? "y" : "ies");
        return MPB_ENOTFOUND;
    }
    if (sl == 4 && strncmp(uri, "file", 4) == 0) {
        const char *p = uri + 7;
        if (*p != '/') {
            mpb__set_err(err, errlen, "mesh '%s': expected file:///<absolute path>", uri);
            return MPB_EINVAL;
        }
        if (!is_file(p)) {
            mpb__set_err(err, errlen, "mesh '%s': no such file", uri);
            return MPB_ENOTFOUND;
        }
        out = p;
        return MPB_OK;
    }
    if (sl > 0) {
        mpb__set_err(err, errlen, "mesh '%s': URI scheme not supported (use "
                     "package://, file:// or a path)", uri);
        return MPB_EUNSUPPORTED;
    }
    if (uri[0] == '/') {
        if (!is_file(uri)) {
            mpb__set_err(err, errlen, "mesh '%s': no such file", uri);
            return MPB_ENOTFOUND;
        }
        out = uri;
        return MPB_OK;
    }
    for (int i = 0; i < num_dirs; i++) {
        if (!dirs[i] || !*dirs[i])
            continue;
        std::string p = join(dirs[i], uri);
        if (is_file(p)) {
            out = p;
            return MPB_OK;
        }
    }
    mpb__set_err(err, errlen, "mesh '%s': not found (relative path looked for in "
                 "%d search director%s)", uri, num_dirs, num_dirs == 1 ? "y" : "ies");
    return MPB_ENOTFOUND;
}

struct Collected {
    std::vector<double>  v;
    std::vector<int32_t> t;
};

/* Append the triangles of node and its children, transformed by tf. */
bool collect(const aiScene *scene, const aiNode *node, const aiMatrix4x4 &tf,
             Collected &c)
{
    for (unsigned k = 0; k < node->mNumMeshes; k++) {
        const aiMesh *m = scene->mMeshes[node->mMeshes[k]];
        if (!m || !m->mVertices)
            continue;
        size_t base = c.v.size() / 3;
        if (base + m->mNumVertices > (size_t)INT32_MAX / 3)
            return false;
        for (unsigned i = 0; i < m->mNumVertices; i++) {
            aiVector3D p = tf * m->mVertices[i];
            c.v.push_back(p.x);
            c.v.push_back(p.y);
            c.v.push_back(p.z);
        }
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            const aiFace &face = m->mFaces[f];
            if (face.mNumIndices != 3)
                continue;       /* points and lines */
            if (c.t.size() / 3 + 1 > (size_t)INT32_MAX / 3)
                return false;
            for (int j = 0; j < 3; j++)
                c.t.push_back((int32_t)(base + face.mIndices[j]));
        }
    }
    for (unsigned k = 0; k < node->mNumChildren; k++) {
        const aiNode *child = node->mChildren[k];
        if (!collect(scene, child, tf * child->mTransformation, c))
            return false;
    }
    return true;
}

/* The scale factors of scale (NULL: 1 1 1) into s; MPB_EINVAL if one is
 * not finite or is zero. */
int check_scale(const char *uri, const double scale[3], double s[3],
                char *err, size_t errlen)
{
    for (int i = 0; i < 3; i++)
        s[i] = 1.0;
    if (scale)
        for (int i = 0; i < 3; i++) {
            if (!std::isfinite(scale[i]) || scale[i] == 0.0) {
                mpb__set_err(err, errlen, "mesh '%s': scale must be finite and "
                             "nonzero", uri ? uri : "");
                return MPB_EINVAL;
            }
            s[i] = scale[i];
        }
    return MPB_OK;
}

/* What read_mesh() is, for the disk cache's key: a newer assimp, or
 * other steps, may read a file into another mesh. A change to what
 * read_mesh() makes of a file must change this text, or the cache hands
 * out meshes made the old way. */
const std::string &reader_id()
{
    static const std::string id = [] {
        char buf[160];
        std::snprintf(buf, sizeof buf, "assimp %u.%u.%u; remove components, "
                      "triangulate, join identical vertices, sort by type; "
                      "points and lines dropped; root scale kept",
                      aiGetVersionMajor(), aiGetVersionMinor(),
                      aiGetVersionRevision());
        return std::string(buf);
    }();
    return id;
}

/* The mesh file at path (resolved), scaled by s, into *out. */
int read_mesh(const std::string &path, const double s[3], mpb_mesh **out,
              char *err, size_t errlen)
{
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
        aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
        aiComponent_COLORS | aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS |
        aiComponent_ANIMATIONS | aiComponent_TEXTURES | aiComponent_LIGHTS |
        aiComponent_CAMERAS | aiComponent_MATERIALS);
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene *scene = importer.ReadFile(path,
        aiProcess_RemoveComponent | aiProcess_Triangulate |
        aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
    if (!scene || !scene->mRootNode) {
        mpb__set_err(err, errlen, "mesh '%s': assimp: %s", path.c_str(),
                     importer.GetErrorString());
        return MPB_EPARSE;
    }
    /*
     * The root's transform is assimp's COLLADA unit scale times its Y-up
     * rotation: keep the scale (RViz applies <unit meter>), drop the rest.
     */
    const aiMatrix4x4 &r = scene->mRootNode->mTransformation;
    double det = (double)r.a1 * (r.b2 * r.c3 - r.b3 * r.c2)
               - (double)r.a2 * (r.b1 * r.c3 - r.b3 * r.c1)
               + (double)r.a3 * (r.b1 * r.c2 - r.b2 * r.c1);
    double unit = std::cbrt(std::fabs(det));
    if (!std::isfinite(unit) || unit <= 0.0)
        unit = 1.0;
    aiMatrix4x4 root;
    root.a1 = root.b2 = root.c3 = (ai_real)unit;
    Collected c;
    if (!collect(scene, scene->mRootNode, root, c)) {
        mpb__set_err(err, errlen, "mesh '%s': too many vertices or triangles",
                     path.c_str());
        return MPB_EPARSE;
    }
    if (c.t.empty()) {
        mpb__set_err(err, errlen, "mesh '%s': no triangles", path.c_str());
        return MPB_EPARSE;
    }
    mpb_mesh *m = mpb__mesh_create((int)(c.v.size() / 3), (int)(c.t.size() / 3));
    if (!m)
        return MPB_ENOMEM;
    for (size_t i = 0; i < c.v.size(); i++)
        m->vertices[i] = c.v[i] * s[i % 3];
    memcpy(m->triangles, c.t.data(), c.t.size() * sizeof(int32_t));
    char why[160];
    if (mpb__mesh_check(m, why, sizeof why) != MPB_OK) {
        mpb__set_err(err, errlen, "mesh '%s': %s", path.c_str(), why);
        mpb__mesh_destroy(m);
        return MPB_EPARSE;
    }
    *out = m;
    return MPB_OK;
}

int load(const char *uri, const char *const *dirs, int num_dirs,
         const double scale[3], mpb_mesh **out, char *err, size_t errlen)
{
    double s[3];
    int rc = check_scale(uri, scale, s, err, errlen);
    if (rc != MPB_OK)
        return rc;
    std::string path;
    if ((rc = resolve(uri, dirs, num_dirs, path, err, errlen)) != MPB_OK)
        return rc;
    return read_mesh(path, s, out, err, errlen);
}

/*
 * The process-wide mesh cache of mesh_cache.h. A file is the same file
 * while its path, device, inode, size and times are; the scale is part of
 * the key as its bits. Entries are counted references, freed with the last
 * release; one whose file changed while assimp read it is handed out but
 * never found by a later load.
 */
struct CacheKey {
    std::string path;
    unsigned long long dev, ino;
    long long size, mtime_s, mtime_ns, ctime_s, ctime_ns;
    unsigned long long scale[3];

    bool operator<(const CacheKey &o) const
    {
        return std::tie(path, dev, ino, size, mtime_s, mtime_ns, ctime_s, ctime_ns,
                        scale[0], scale[1], scale[2]) <
               std::tie(o.path, o.dev, o.ino, o.size, o.mtime_s, o.mtime_ns, o.ctime_s,
                        o.ctime_ns, o.scale[0], o.scale[1], o.scale[2]);
    }
    bool same_file(const CacheKey &o) const
    {
        return dev == o.dev && ino == o.ino && size == o.size &&
               mtime_s == o.mtime_s && mtime_ns == o.mtime_ns &&
               ctime_s == o.ctime_s && ctime_ns == o.ctime_ns;
    }
};

struct CacheEntry {
    mpb_mesh *mesh = nullptr; /* owned */
    long      refs = 0;
    bool      keyed = false;  /* in Cache::by_key under key */
    CacheKey  key;

    CacheEntry() = default;
    CacheEntry(const CacheEntry &) = delete;
    CacheEntry &operator=(const CacheEntry &) = delete;
    ~CacheEntry() { mpb__mesh_destroy(mesh); }
};

struct Cache {
    std::mutex mu;
    std::map<CacheKey, CacheEntry *> by_key;
    std::unordered_map<const mpb_mesh *, CacheEntry *> by_mesh;
    long reads = 0;
};

Cache &cache()
{
    static Cache *c = new Cache();   /* never destroyed: worlds closed at
                                        exit may still release into it */
    return *c;
}

/* The identity of the file at path into k; false if it cannot be read. */
bool file_key(const std::string &path, const double s[3], CacheKey &k)
{
    struct stat st;
    if (stat(path.c_str(), &st) != 0)
        return false;
    k.path = path;
    k.dev = (unsigned long long)st.st_dev;
    k.ino = (unsigned long long)st.st_ino;
    k.size = (long long)st.st_size;
    k.mtime_s = (long long)st.st_mtim.tv_sec;
    k.mtime_ns = (long long)st.st_mtim.tv_nsec;
    k.ctime_s = (long long)st.st_ctim.tv_sec;
    k.ctime_ns = (long long)st.st_ctim.tv_nsec;
    for (int i = 0; i < 3; i++)
        memcpy(&k.scale[i], &s[i], sizeof k.scale[i]);
    return true;
}

int load_shared(const char *uri, const char *const *dirs, int num_dirs,
                const double scale[3], const mpb_mesh **out, char *err,
                size_t errlen)
{
    double s[3];
    int rc = check_scale(uri, scale, s, err, errlen);
    if (rc != MPB_OK)
        return rc;
    std::string path;
    if ((rc = resolve(uri, dirs, num_dirs, path, err, errlen)) != MPB_OK)
        return rc;
    CacheKey key;
    if (!file_key(path, s, key)) {
        mpb__set_err(err, errlen, "mesh '%s': no such file", path.c_str());
        return MPB_ENOTFOUND;
    }
    Cache &c = cache();
    {
        std::lock_guard<std::mutex> lock(c.mu);
        auto it = c.by_key.find(key);
        if (it != c.by_key.end()) {
            it->second->refs++;
            *out = it->second->mesh;
            return MPB_OK;
        }
    }
    /* Read outside the lock: other threads' meshes need not wait. From
     * the disk cache when it has these bytes, else by assimp. */
    std::unique_ptr<CacheEntry> e(new CacheEntry());
    e->key = key;
    e->refs = 1;
    mpb__mesh_disk_id id;
    bool have_id = mpb__mesh_disk_key(path.c_str(), s, reader_id().c_str(),
                                      &id) == MPB_OK;
    bool from_disk = have_id && (e->mesh = mpb__mesh_disk_get(&id)) != nullptr;
    if (!from_disk && (rc = read_mesh(path, s, &e->mesh, err, errlen)) != MPB_OK)
        return rc;
    CacheKey after;
    bool unchanged = file_key(path, s, after) && after.same_file(key);
    /* Stored only when the file stayed the same from its key to here. */
    if (unchanged && have_id && !from_disk)
        mpb__mesh_disk_put(&id, e->mesh);
    std::lock_guard<std::mutex> lock(c.mu);
    c.reads++;
    if (unchanged) {
        auto it = c.by_key.find(key);
        if (it != c.by_key.end()) {
            /* Another thread read it meanwhile: take its copy. */
            it->second->refs++;
            *out = it->second->mesh;
            return MPB_OK;
        }
        e->keyed = true;
    }
    auto at = c.by_mesh.emplace(e->mesh, e.get()).first;
    if (e->keyed) {
        try {
            c.by_key.emplace(key, e.get());
        } catch (...) {
            c.by_mesh.erase(at);
            throw;
        }
    }
    *out = e->mesh;
    (void)e.release();          /* the cache's now */
    return MPB_OK;
}

/* The C boundary of both loaders: no exception crosses it, and every
 * failure leaves one line naming the mesh. */
template <typename Out, typename Load>
int load_at_boundary(const char *uri, Out **out, char *err, size_t errlen,
                     Load load_it)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!out) {
        mpb__set_err(err, errlen, "mesh: no place for the result");
        return MPB_EINVAL;
    }
    *out = NULL;
    char prefix[1024];
    std::snprintf(prefix, sizeof prefix, "mesh '%s': ", uri ? uri : "");
    const mpb__cxx_guard says = {prefix, "", MPB_EPARSE, "unexpected error",
                                 MPB_EERROR};
    int rc = mpb__cxx_guarded(err, errlen, says, load_it);
    if (rc == MPB_ENOMEM)
        mpb__set_err(err, errlen, "%sout of memory", prefix);
    return rc;
}

} // namespace

extern "C" {

mpb_mesh *mpb__mesh_create(int num_vertices, int num_triangles)
{
    if (num_vertices < 0 || num_triangles < 0 ||
        num_vertices > INT32_MAX / 3 || num_triangles > INT32_MAX / 3)
        return NULL;
    mpb_mesh *m = (mpb_mesh *)calloc(1, sizeof *m);
    if (!m)
        return NULL;
    m->vertices = (double *)calloc((size_t)num_vertices * 3 + 1, sizeof(double));
    m->triangles = (int32_t *)calloc((size_t)num_triangles * 3 + 1, sizeof(int32_t));
    if (!m->vertices || !m->triangles) {
        mpb__mesh_destroy(m);
        return NULL;
    }
    m->num_vertices = num_vertices;
    m->num_triangles = num_triangles;
    return m;
}

void mpb__mesh_destroy(mpb_mesh *m)
{
    if (!m)
        return;
    free(m->vertices);
    free(m->triangles);
    free(m);
}

mpb_mesh *mpb__mesh_copy(const mpb_mesh *m)
{
    if (!m)
        return NULL;
    mpb_mesh *c = mpb__mesh_create(m->num_vertices, m->num_triangles);
    if (!c)
        return NULL;
    if (m->num_vertices)
        memcpy(c->vertices, m->vertices, (size_t)m->num_vertices * 3 * sizeof(double));
    if (m->num_triangles)
        memcpy(c->triangles, m->triangles, (size_t)m->num_triangles * 3 * sizeof(int32_t));
    return c;
}

int mpb__mesh_check(const mpb_mesh *m, char *err, size_t errlen)
{
    if (!m) {
        mpb__set_err(err, errlen, "no mesh");
        return MPB_EINVAL;
    }
    if (m->num_triangles < 1 || m->num_vertices < 3 || !m->vertices || !m->triangles) {
        mpb__set_err(err, errlen, "a mesh needs at least 3 vertices and 1 triangle "
                     "(has %d and %d)", m->num_vertices, m->num_triangles);
        return MPB_EINVAL;
    }
    for (long i = 0; i < 3L * m->num_vertices; i++)
        if (!std::isfinite(m->vertices[i])) {
            mpb__set_err(err, errlen, "vertex %ld is not finite", i / 3);
            return MPB_EINVAL;
        }
    for (long i = 0; i < 3L * m->num_triangles; i++)
        if (m->triangles[i] < 0 || m->triangles[i] >= m->num_vertices) {
            mpb__set_err(err, errlen, "triangle %ld uses vertex %ld, out of range "
                         "0..%d", i / 3, (long)m->triangles[i], m->num_vertices - 1);
            return MPB_EINVAL;
        }
    return MPB_OK;
}

int mpb__mesh_bounds(const mpb_mesh *m, double lo[3], double hi[3])
{
    if (!m || !lo || !hi || m->num_vertices < 1 || !m->vertices)
        return MPB_EINVAL;
    for (int k = 0; k < 3; k++)
        lo[k] = hi[k] = m->vertices[k];
    for (int i = 1; i < m->num_vertices; i++)
        for (int k = 0; k < 3; k++) {
            double x = m->vertices[3 * i + k];
            if (x < lo[k])
                lo[k] = x;
            if (x > hi[k])
                hi[k] = x;
        }
    return MPB_OK;
}

int mpb_mesh_resolve(const char *uri, const char *const *dirs, int num_dirs,
                     char *path, size_t pathlen, char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!path || pathlen == 0) {
        mpb__set_err(err, errlen, "mesh: no room for the path");
        return MPB_EINVAL;
    }
    path[0] = '\0';
    static const mpb__cxx_guard says = {"mesh: ", "", MPB_EERROR,
                                        "unexpected error", MPB_EERROR};
    return mpb__cxx_guarded(err, errlen, says, [&]() -> int {
        std::string p;
        int rc = resolve(uri, dirs, num_dirs, p, err, errlen);
        if (rc != MPB_OK)
            return rc;
        if (p.size() + 1 > pathlen) {
            mpb__set_err(err, errlen, "mesh '%s': resolved path longer than %zu bytes",
                         uri, pathlen - 1);
            return MPB_EINVAL;
        }
        memcpy(path, p.c_str(), p.size() + 1);
        return MPB_OK;
    });
}

int mpb__mesh_create_from_uri(const char *uri, const char *const *dirs, int num_dirs,
                             const double scale[3], mpb_mesh **out,
                             char *err, size_t errlen)
{
    return load_at_boundary(uri, out, err, errlen, [&] {
        return load(uri, dirs, num_dirs, scale, out, err, errlen);
    });
}

int mpb__mesh_load_shared(const char *uri, const char *const *dirs,
                          int num_dirs, const double scale[3],
                          const mpb_mesh **out, char *err, size_t errlen)
{
    return load_at_boundary(uri, out, err, errlen, [&] {
        return load_shared(uri, dirs, num_dirs, scale, out, err, errlen);
    });
}

void mpb__mesh_release(const mpb_mesh *m)
{
    if (!m)
        return;
    CacheEntry *dead = nullptr;
    {
        Cache &c = cache();
        std::lock_guard<std::mutex> lock(c.mu);
        auto it = c.by_mesh.find(m);
        if (it == c.by_mesh.end())
            return;             /* not ours: a caller's bug, no crash */
        CacheEntry *e = it->second;
        if (--e->refs > 0)
            return;
        c.by_mesh.erase(it);
        if (e->keyed)
            c.by_key.erase(e->key);
        dead = e;
    }
    delete dead;
}

long mpb__mesh_cache_reads(void)
{
    Cache &c = cache();
    std::lock_guard<std::mutex> lock(c.mu);
    return c.reads;
}

long mpb__mesh_cache_live(void)
{
    Cache &c = cache();
    std::lock_guard<std::mutex> lock(c.mu);
    return (long)c.by_mesh.size();
}

} // extern "C"
