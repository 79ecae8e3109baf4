/* scene: the .scene parser (the format: scenes/README.md) and the scene
 * model's small queries. */
#include "scene.h"

#include <assert.h>
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "utf8.h"

#define SCENE_MAX_TOKENS 48
#define SCENE_MAX_TOKEN 256
#define SCENE_MAX_COORD 1e15
#define SCENE_MAX_POWER 1e35
#define SCENE_MAX_ITEMS 100000
#define SCENE_MAX_FILE (64u << 20)
/* Shortest radius, edge and scene size: below it squared lengths underflow
 * (a rect of edges 1e-160 would get an infinite 1/|edge|^2). */
#define SCENE_MIN_LENGTH 1e-50
/* A spawned ray's offset from the surface, relative to the sum of the
 * magnitudes of the coordinates involved (ray origin, hit point, shape):
 * 2^-46, i.e. 64 ulps of a double, over ten times the rounding error of a
 * hit point (a few ulps of the largest of them). */
#define SCENE_EPS_REL 0x1p-46

typedef struct {
    size_t start, len; /* byte offsets into the text */
    int col;           /* 1-based column */
} token;

typedef struct {
    const char *name;
    const char *text;
    char *err;
    size_t errlen;
    int line;
    token tok[SCENE_MAX_TOKENS];
    int ntok;
    scene *sc;
    int camera_line, light_line;
    size_t cap_materials, cap_shapes, cap_shape_lines;
    int *name_index;    /* hash table of material indices (-1: empty), name_cap slots */
    size_t name_cap;    /* 0 or a power of two */
} parser;

static pm_status perr(parser *p, int col, const char *fmt, ...)
{
    int n = snprintf(p->err, p->errlen, "%s:%d:%d: ", p->name, p->line, col);
    if (n >= 0 && (size_t)n < p->errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(p->err + n, p->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return PM_ERR_INPUT;
}

static int tok_is(const parser *p, int i, const char *word)
{
    size_t n = strlen(word);
    return p->tok[i].len == n && memcmp(p->text + p->tok[i].start, word, n) == 0;
}

/* Copies token i as a C string for messages (cut at 40 bytes). */
static const char *tok_str(const parser *p, int i, char *buf, size_t cap)
{
    size_t n = p->tok[i].len < cap - 1 ? p->tok[i].len : cap - 1;
    if (n > 40)
        n = 40;
    memcpy(buf, p->text + p->tok[i].start, n);
    buf[n] = '\0';
    return buf;
}


/* Splits one line (without its '\n') into tokens, validating every byte. */
static pm_status tokenize(parser *p, size_t start, size_t end)
{
    const unsigned char *t = (const unsigned char *)p->text;
    p->ntok = 0;
    size_t i = start;
    while (i < end) {
        unsigned c = t[i];
        int col = (int)(i - start) + 1;
        if (c == '#') { /* comment: any valid UTF-8, no control bytes */
            for (size_t j = i + 1; j < end;) {
                unsigned d = t[j];
                if ((d < 0x20 && d != '\t' && d != '\r') || d == 0x7f)
                    return perr(p, (int)(j - start) + 1, "control byte 0x%02x in comment", d);
                size_t l = utf8_sequence_len(t + j, end - j);
                if (l == 0)
                    return perr(p, (int)(j - start) + 1, "invalid UTF-8 byte 0x%02x in comment", d);
                j += l;
            }
            break;
        }
        if (c == ' ' || c == '\t' || c == '\r') {
            i++;
            continue;
        }
        if (c < 0x20 || c >= 0x7f) {
            if (c >= 0x80)
                return perr(p, col, "non-ASCII byte 0x%02x outside a comment", c);
            return perr(p, col, "control byte 0x%02x (binary data?)", c);
        }
        size_t s = i;
        while (i < end && t[i] > 0x20 && t[i] < 0x7f && t[i] != '#')
            i++;
        if (i - s > SCENE_MAX_TOKEN)
            return perr(p, col, "token longer than %d bytes", SCENE_MAX_TOKEN);
        if (p->ntok == SCENE_MAX_TOKENS)
            return perr(p, col, "too many fields on one line (at most %d)", SCENE_MAX_TOKENS);
        p->tok[p->ntok].start = s;
        p->tok[p->ntok].len = i - s;
        p->tok[p->ntok].col = col;
        p->ntok++;
    }
    return PM_OK;
}

/* Parses token i as a finite number in [lo, hi]. */
static pm_status parse_number(parser *p, int i, double lo, double hi, double *out)
{
    char buf[SCENE_MAX_TOKEN + 1];
    const token *tk = &p->tok[i];
    memcpy(buf, p->text + tk->start, tk->len);
    buf[tk->len] = '\0';
    char c0 = buf[0];
    /* decimal only, as scenes/README.md says: strtod also takes hex floats
     * ("0x10", "0x1p-1074"; tests/hostile.test.sh) */
    int looks_numeric = ((c0 >= '0' && c0 <= '9') || c0 == '-' || c0 == '+' || c0 == '.') && !strpbrk(buf, "xX");
    char *end = NULL;
    errno = 0;
    double v = looks_numeric ? strtod(buf, &end) : 0.0;
    if (!looks_numeric || end == buf || *end != '\0')
        return perr(p, tk->col, "expected a number, got '%s'", tok_str(p, i, buf, sizeof buf));
    if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1.0))
        return perr(p, tk->col, "number '%s' is not finite", buf);
    if (v < lo || v > hi)
        return perr(p, tk->col, "%s is out of range [%g, %g]", buf, lo, hi);
    *out = v;
    return PM_OK;
}

typedef enum { F_NUM, F_VEC, F_NAME } field_kind;

/* One field of a statement: its key, kind and range (numbers). */
typedef struct {
    const char *key;
    field_kind kind;
    double lo, hi;
} field_spec;

/* What parse_fields found for one field. */
typedef struct {
    int col;  /* column of the first value; 0 while not seen */
    vec3 v;   /* F_VEC; F_NUM in v.x */
    int name; /* F_NAME: token index */
} field_val;

#define COORD(key) {key, F_VEC, -SCENE_MAX_COORD, SCENE_MAX_COORD}
static const field_spec camera_fields[] = {COORD("position"), COORD("look_at"), COORD("up"),
                                           {"fov", F_NUM, 0.01, 179.0}};
static const field_spec light_fields[] = {COORD("position"), {"power", F_VEC, 0.0, SCENE_MAX_POWER}};
static const field_spec sphere_fields[] = {COORD("center"), {"radius", F_NUM, 0.0, SCENE_MAX_COORD},
                                           {"material", F_NAME, 0, 0}};
static const field_spec rect_fields[] = {COORD("corner"), COORD("edge1"), COORD("edge2"), {"material", F_NAME, 0, 0}};
#undef COORD
enum { CAM_POSITION, CAM_LOOK_AT, CAM_UP, CAM_FOV };
enum { LIGHT_POSITION, LIGHT_POWER };
enum { SPHERE_CENTER, SPHERE_RADIUS, SPHERE_MATERIAL };
enum { RECT_CORNER, RECT_EDGE1, RECT_EDGE2, RECT_MATERIAL };
#define NFIELDS(a) ((int)(sizeof a / sizeof a[0]))

/* The material kinds: each has one field. */
typedef struct {
    const char *name;
    material_kind kind;
    field_spec field;
} material_spec;
static const material_spec material_specs[] = {
    {"lambert", MATERIAL_LAMBERT, {"rho", F_VEC, 0.0, 1.0}},
    {"mirror", MATERIAL_MIRROR, {"reflectance", F_VEC, 0.0, 1.0}},
    {"glass", MATERIAL_GLASS, {"ior", F_NUM, 1.0, 10.0}},
};

/* Parses "key value..." pairs from token `first` on into val[] (nf fields
 * of spec[]): every field exactly once. */
static pm_status parse_fields(parser *p, int first, const field_spec *spec, field_val *val, int nf, const char *stmt)
{
    char buf[64];
    for (int k = 0; k < nf; k++)
        val[k].col = 0;
    for (int i = first; i < p->ntok;) {
        int k;
        for (k = 0; k < nf; k++)
            if (tok_is(p, i, spec[k].key))
                break;
        if (k == nf) {
            char msg[256] = "";
            for (int j = 0; j < nf; j++) {
                strncat(msg, j ? ", " : "", sizeof msg - strlen(msg) - 1);
                strncat(msg, spec[j].key, sizeof msg - strlen(msg) - 1);
            }
            return perr(p, p->tok[i].col, "unknown %s field '%s' (expected %s)", stmt,
                        tok_str(p, i, buf, sizeof buf), msg);
        }
        if (val[k].col)
            return perr(p, p->tok[i].col, "%s field '%s' given twice", stmt, spec[k].key);
        int arity = spec[k].kind == F_VEC ? 3 : 1;
        if (i + arity >= p->ntok) {
            int col = (int)(p->tok[p->ntok - 1].col + p->tok[p->ntok - 1].len);
            return perr(p, col, "%s field '%s' needs %d value%s", stmt, spec[k].key, arity, arity > 1 ? "s" : "");
        }
        val[k].col = p->tok[i + 1].col;
        if (spec[k].kind == F_NAME) {
            val[k].name = i + 1;
        } else {
            double c[3] = {0, 0, 0};
            for (int j = 0; j < arity; j++) {
                pm_status rc = parse_number(p, i + 1 + j, spec[k].lo, spec[k].hi, &c[j]);
                if (rc != PM_OK)
                    return rc;
            }
            val[k].v = vec_make(c[0], c[1], c[2]);
        }
        i += 1 + arity;
    }
    for (int k = 0; k < nf; k++)
        if (!val[k].col)
            return perr(p, p->tok[0].col, "%s is missing field '%s'", stmt, spec[k].key);
    return PM_OK;
}

static int is_name(const parser *p, int i)
{
    const char *s = p->text + p->tok[i].start;
    size_t n = p->tok[i].len;
    if (n == 0 || n >= MATERIAL_NAME_MAX)
        return 0;
    if (!((s[0] >= 'a' && s[0] <= 'z') || (s[0] >= 'A' && s[0] <= 'Z') || s[0] == '_'))
        return 0;
    for (size_t j = 1; j < n; j++) {
        char c = s[j];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
              c == '-'))
            return 0;
    }
    return 1;
}

/* ---- material names: an open-addressing hash table of material indices,
 * so that defining and using N materials costs O(N), not O(N^2) ---- */

static uint64_t name_hash(const char *s, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull; /* FNV-1a */
    for (size_t i = 0; i < n; i++) {
        h ^= (unsigned char)s[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

/* The slot of token i's name: its material's slot, or the empty slot where it
 * would go. The table is never full (load <= 1/2). */
static size_t name_slot(const parser *p, int i)
{
    const char *s = p->text + p->tok[i].start;
    size_t n = p->tok[i].len, mask = p->name_cap - 1;
    assert(p->name_cap > 0 && (p->name_cap & mask) == 0);
    for (size_t j = (size_t)name_hash(s, n) & mask;; j = (j + 1) & mask) {
        int m = p->name_index[j];
        if (m < 0 || tok_is(p, i, p->sc->materials[m].name))
            return j;
    }
}

static int find_material(const parser *p, int i)
{
    return p->name_cap ? p->name_index[name_slot(p, i)] : -1;
}

/* Makes room for one more name (rehashing into a table twice the size when
 * half full). Returns PM_OK, or PM_ERR_NOMEM. */
static pm_status names_reserve(parser *p)
{
    if (2 * (p->sc->nmaterials + 1) <= p->name_cap)
        return PM_OK;
    size_t cap = p->name_cap ? 2 * p->name_cap : 64;
    int *idx = malloc(cap * sizeof(int));
    if (!idx)
        return PM_ERR_NOMEM;
    for (size_t j = 0; j < cap; j++)
        idx[j] = -1;
    for (size_t m = 0; m < p->sc->nmaterials; m++) {
        const char *name = p->sc->materials[m].name;
        size_t j = (size_t)name_hash(name, strlen(name)) & (cap - 1);
        while (idx[j] >= 0)
            j = (j + 1) & (cap - 1);
        idx[j] = (int)m;
    }
    free(p->name_index);
    p->name_index = idx;
    p->name_cap = cap;
    return PM_OK;
}

static pm_status parse_camera(parser *p)
{
    field_val f[NFIELDS(camera_fields)];
    if (p->camera_line)
        return perr(p, p->tok[0].col, "second camera (the first is on line %d)", p->camera_line);
    pm_status rc = parse_fields(p, 1, camera_fields, f, NFIELDS(camera_fields), "camera");
    if (rc != PM_OK)
        return rc;
    vec3 dir = vec_sub(f[CAM_LOOK_AT].v, f[CAM_POSITION].v);
    /* only an exact tie: a relative test refused a room at x = 1e15 - 3 whose
     * camera looked 2.4 units ahead (whether such a scene can be rendered is
     * decided from the photon map, render.c check_precision) */
    if (dir.x == 0.0 && dir.y == 0.0 && dir.z == 0.0)
        return perr(p, f[CAM_LOOK_AT].col, "camera look_at equals its position (after rounding to double precision)");
    /* so short that its squared length underflows: no direction to normalize
     * (position z 2.41e-300, look_at z 0) */
    if (!(vec_len(dir) > 0.0))
        return perr(p, f[CAM_LOOK_AT].col, "camera look_at is too close to its position (%g apart)",
                    vec_maxc(vec_make(fabs(dir.x), fabs(dir.y), fabs(dir.z))));
    if (vec_len(f[CAM_UP].v) == 0.0)
        return perr(p, f[CAM_UP].col, "camera up vector is zero (or too short to normalize)");
    vec3 side = vec_cross(vec_norm(dir), vec_norm(f[CAM_UP].v));
    if (!(vec_len(side) >= 1e-6))
        return perr(p, f[CAM_UP].col, "camera up vector is parallel to the view direction");
    p->sc->camera.position = f[CAM_POSITION].v;
    p->sc->camera.look_at = f[CAM_LOOK_AT].v;
    p->sc->camera.up = f[CAM_UP].v;
    p->sc->camera.hfov_deg = f[CAM_FOV].v.x;
    p->camera_line = p->line;
    return PM_OK;
}

static pm_status parse_light(parser *p)
{
    field_val f[NFIELDS(light_fields)];
    if (p->light_line)
        return perr(p, p->tok[0].col, "second light (one point light is supported; the first is on line %d)",
                    p->light_line);
    if (p->ntok < 2 || !tok_is(p, 1, "point"))
        return perr(p, p->ntok < 2 ? (int)(p->tok[0].col + p->tok[0].len) : p->tok[1].col,
                    "expected 'light point ...' (the only light type)");
    pm_status rc = parse_fields(p, 2, light_fields, f, NFIELDS(light_fields), "light");
    if (rc != PM_OK)
        return rc;
    p->sc->light.position = f[LIGHT_POSITION].v;
    p->sc->light.power = f[LIGHT_POWER].v;
    p->light_line = p->line;
    return PM_OK;
}

/* Makes room for element n of the array *arr of *cap elements of elem
 * bytes (doubling it). Returns PM_OK, or PM_ERR_NOMEM (*arr unchanged). */
static pm_status grow(void **arr, size_t *cap, size_t n, size_t elem)
{
    if (n < *cap)
        return PM_OK;
    size_t nc = *cap ? *cap * 2 : 8;
    void *q = realloc(*arr, nc * elem);
    if (!q)
        return PM_ERR_NOMEM;
    *arr = q;
    *cap = nc;
    return PM_OK;
}

static pm_status parse_material(parser *p)
{
    char buf[64];
    scene *sc = p->sc;
    if (p->ntok < 3)
        return perr(p, (int)(p->tok[p->ntok - 1].col + p->tok[p->ntok - 1].len),
                    "expected 'material NAME lambert|mirror|glass ...'");
    if (!is_name(p, 1))
        return perr(p, p->tok[1].col, "bad material name '%s' (letters, digits, _ and -, at most %d)",
                    tok_str(p, 1, buf, sizeof buf), MATERIAL_NAME_MAX - 1);
    int prev = find_material(p, 1);
    if (prev >= 0)
        return perr(p, p->tok[1].col, "material '%s' already defined on line %d", tok_str(p, 1, buf, sizeof buf),
                    p->sc->material_lines[prev]);
    if (sc->nmaterials >= SCENE_MAX_ITEMS)
        return perr(p, p->tok[0].col, "too many materials (at most %d)", SCENE_MAX_ITEMS);
    const material_spec *ms = NULL;
    for (size_t k = 0; k < sizeof material_specs / sizeof material_specs[0]; k++)
        if (tok_is(p, 2, material_specs[k].name))
            ms = &material_specs[k];
    if (!ms)
        return perr(p, p->tok[2].col, "unknown material kind '%s' (expected lambert, mirror or glass)",
                    tok_str(p, 2, buf, sizeof buf));
    char stmt[32];
    snprintf(stmt, sizeof stmt, "%s material", ms->name);
    field_val f;
    pm_status rc = parse_fields(p, 3, &ms->field, &f, 1, stmt);
    if (rc != PM_OK)
        return rc;
    material m;
    memset(&m, 0, sizeof m);
    m.kind = ms->kind;
    m.color = ms->field.kind == F_VEC ? f.v : vec_make(1, 1, 1);
    m.ior = ms->field.kind == F_NUM ? f.v.x : 1.0;
    memcpy(m.name, p->text + p->tok[1].start, p->tok[1].len);
    m.name[p->tok[1].len] = '\0';
    size_t cap = p->cap_materials;
    if ((rc = grow((void **)&sc->materials, &p->cap_materials, sc->nmaterials, sizeof(material))) != PM_OK ||
        (rc = names_reserve(p)) != PM_OK)
        return rc;
    if (p->cap_materials != cap) {
        int *q = realloc(p->sc->material_lines, p->cap_materials * sizeof(int));
        if (!q)
            return PM_ERR_NOMEM;
        p->sc->material_lines = q;
    }
    p->sc->material_lines[sc->nmaterials] = p->line;
    size_t slot = name_slot(p, 1); /* the empty slot for this name */
    sc->materials[sc->nmaterials] = m;
    p->name_index[slot] = (int)sc->nmaterials++;
    return PM_OK;
}

static pm_status resolve_material(parser *p, const field_val *f, int *out)
{
    char buf[64];
    int m = find_material(p, f->name);
    if (m < 0)
        return perr(p, f->col, "unknown material '%s'%s", tok_str(p, f->name, buf, sizeof buf),
                    p->sc->nmaterials ? "" : " (no material is defined above this line)");
    *out = m;
    return PM_OK;
}

static pm_status add_shape(parser *p, shape s)
{
    if (p->sc->nshapes >= SCENE_MAX_ITEMS)
        return perr(p, p->tok[0].col, "too many shapes (at most %d)", SCENE_MAX_ITEMS);
    pm_status rc;
    if ((rc = grow((void **)&p->sc->shapes, &p->cap_shapes, p->sc->nshapes, sizeof(shape))) != PM_OK)
        return rc;
    if ((rc = grow((void **)&p->sc->shape_lines, &p->cap_shape_lines, p->sc->nshapes, sizeof(int))) != PM_OK)
        return rc;
    p->sc->shape_lines[p->sc->nshapes] = p->line;
    p->sc->shapes[p->sc->nshapes++] = s;
    return PM_OK;
}

static pm_status parse_sphere(parser *p)
{
    field_val f[NFIELDS(sphere_fields)];
    pm_status rc = parse_fields(p, 1, sphere_fields, f, NFIELDS(sphere_fields), "sphere");
    if (rc != PM_OK)
        return rc;
    if (!(f[SPHERE_RADIUS].v.x >= SCENE_MIN_LENGTH))
        return perr(p, f[SPHERE_RADIUS].col, "sphere radius must be positive and at least %g", SCENE_MIN_LENGTH);
    int m;
    if ((rc = resolve_material(p, &f[SPHERE_MATERIAL], &m)))
        return rc;
    return add_shape(p, shape_sphere(f[SPHERE_CENTER].v, f[SPHERE_RADIUS].v.x, m));
}

static pm_status parse_rect(parser *p)
{
    field_val f[NFIELDS(rect_fields)];
    pm_status rc = parse_fields(p, 1, rect_fields, f, NFIELDS(rect_fields), "rect");
    if (rc != PM_OK)
        return rc;
    vec3 e1 = f[RECT_EDGE1].v, e2 = f[RECT_EDGE2].v;
    double l1 = vec_len(e1), l2 = vec_len(e2);
    if (!(l1 >= SCENE_MIN_LENGTH))
        return perr(p, f[RECT_EDGE1].col, "rect edge1 is zero or shorter than %g", SCENE_MIN_LENGTH);
    if (!(l2 >= SCENE_MIN_LENGTH))
        return perr(p, f[RECT_EDGE2].col, "rect edge2 is zero or shorter than %g", SCENE_MIN_LENGTH);
    if (fabs(vec_dot(e1, e2)) > 1e-9 * l1 * l2)
        return perr(p, f[RECT_EDGE2].col, "rect edges are not perpendicular");
    int m;
    if ((rc = resolve_material(p, &f[RECT_MATERIAL], &m)))
        return rc;
    return add_shape(p, shape_rect(f[RECT_CORNER].v, e1, e2, m));
}

static pm_status parse_line(parser *p)
{
    char buf[64];
    if (p->ntok == 0)
        return PM_OK;
    if (tok_is(p, 0, "camera"))
        return parse_camera(p);
    if (tok_is(p, 0, "light"))
        return parse_light(p);
    if (tok_is(p, 0, "material"))
        return parse_material(p);
    if (tok_is(p, 0, "sphere"))
        return parse_sphere(p);
    if (tok_is(p, 0, "rect"))
        return parse_rect(p);
    return perr(p, p->tok[0].col, "unknown keyword '%s' (expected camera, light, material, sphere or rect)",
                tok_str(p, 0, buf, sizeof buf));
}

static void compute_bounds(scene *sc)
{
    vec3 lo = sc->light.position, hi = lo;
    for (size_t i = 0; i < sc->nshapes; i++) {
        vec3 a, b;
        shape_bounds(&sc->shapes[i], &a, &b);
        lo = vec_make(fmin(lo.x, a.x), fmin(lo.y, a.y), fmin(lo.z, a.z));
        hi = vec_make(fmax(hi.x, b.x), fmax(hi.y, b.y), fmax(hi.z, b.z));
    }
    sc->bounds_lo = lo;
    sc->bounds_hi = hi;
    sc->scale = vec_len(vec_sub(hi, lo));
}

pm_status scene_parse_buffer(const char *name, const char *text, size_t len, scene **out, char *err, size_t errlen)
{
    assert(name && out && err && errlen > 0);
    *out = NULL;
    err[0] = '\0';
    parser p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.text = text;
    p.err = err;
    p.errlen = errlen;
    p.sc = calloc(1, sizeof(scene));
    if (!p.sc) {
        snprintf(err, errlen, "%s: out of memory", name);
        return PM_ERR_NOMEM;
    }
    pm_status rc = PM_OK;
    size_t pos = 0;
    p.line = 0;
    while (pos < len && rc == PM_OK) {
        const char *nl = memchr(text + pos, '\n', len - pos);
        size_t end = nl ? (size_t)(nl - text) : len;
        p.line++;
        rc = tokenize(&p, pos, end);
        if (rc == PM_OK)
            rc = parse_line(&p);
        pos = end + 1;
    }
    if (rc == PM_OK) {
        if (p.line == 0)
            p.line = 1;
        if (!p.camera_line)
            rc = perr(&p, 1, "%s: no camera", p.line == 1 && len == 0 ? "empty scene" : "end of scene");
        else if (!p.light_line)
            rc = perr(&p, 1, "end of scene: no light");
        else if (p.sc->nshapes == 0)
            rc = perr(&p, 1, "end of scene: no shapes");
    }
    if (rc == PM_ERR_NOMEM)
        snprintf(err, errlen, "%s: out of memory while parsing", name);
    free(p.name_index);
    if (rc != PM_OK) {
        scene_free(p.sc);
        return rc;
    }
    compute_bounds(p.sc);
    /* everything within rounding of one point: epsilons and radii would be 0
     * (a light and a 1e-320 sphere at x = 1) */
    if (!(p.sc->scale >= SCENE_MIN_LENGTH)) {
        perr(&p, 1, "end of scene: the scene has no extent (bounding-box diagonal %g, at least %g needed)",
             p.sc->scale, SCENE_MIN_LENGTH);
        scene_free(p.sc);
        return PM_ERR_INPUT;
    }
    *out = p.sc;
    return PM_OK;
}

pm_status scene_load(const char *path, scene **out, char *err, size_t errlen)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return PM_ERR_IO;
    }
    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap);
    pm_status rc = PM_OK;
    while (buf) {
        if (len == cap) {
            if (cap >= SCENE_MAX_FILE) {
                snprintf(err, errlen, "%s:1:1: file larger than %u MiB; not a scene", path, SCENE_MAX_FILE >> 20);
                rc = PM_ERR_INPUT;
                break;
            }
            char *q = realloc(buf, cap * 2);
            if (!q) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = q;
            cap *= 2;
        }
        size_t n = fread(buf + len, 1, cap - len, f);
        len += n;
        if (n == 0) {
            if (ferror(f)) {
                snprintf(err, errlen, "%s: read error: %s", path, strerror(errno));
                rc = PM_ERR_IO;
            }
            break;
        }
    }
    fclose(f);
    if (!buf) {
        snprintf(err, errlen, "%s: out of memory reading the file", path);
        return PM_ERR_NOMEM;
    }
    if (rc == PM_OK)
        rc = scene_parse_buffer(path, buf, len, out, err, errlen);
    free(buf);
    return rc;
}

int scene_sphere_between(const scene *s, vec3 a, vec3 b)
{
    for (size_t i = 0; i < s->nshapes; i++) {
        const shape *sh = &s->shapes[i];
        if (sh->kind != SHAPE_SPHERE || s->materials[sh->material].kind == MATERIAL_GLASS)
            continue;
        double r2 = sh->radius * sh->radius;
        int in_a = vec_len2(vec_sub(a, sh->center)) < r2, in_b = vec_len2(vec_sub(b, sh->center)) < r2;
        if (in_a != in_b)
            return (int)i;
    }
    return SCENE_NO_SHAPE;
}

void scene_free(scene *s)
{
    if (!s)
        return;
    bvh_free(s->accel);
    free(s->materials);
    free(s->shapes);
    free(s->material_lines);
    free(s->shape_lines);
    free(s);
}

pm_status scene_set_accel(scene *s, scene_accel mode)
{
    assert(s && s->nshapes > 0);
    assert(mode == SCENE_ACCEL_AUTO || mode == SCENE_ACCEL_BVH || mode == SCENE_ACCEL_LINEAR);
    int want = mode == SCENE_ACCEL_BVH || (mode == SCENE_ACCEL_AUTO && s->nshapes >= SCENE_BVH_MIN_SHAPES);
    if (!want) {
        bvh_free(s->accel);
        s->accel = NULL;
        return PM_OK;
    }
    if (s->accel) /* the shapes never change after parsing */
        return PM_OK;
    /* every ray starts at the camera, the light or a point on a shape */
    double reach = vec_max2(vec_max_abs(s->camera.position), vec_max2(vec_max_abs(s->bounds_lo), vec_max_abs(s->bounds_hi)));
    s->accel = bvh_build(s->shapes, s->nshapes, reach);
    return s->accel ? PM_OK : PM_ERR_NOMEM;
}

int scene_intersect_counted(const scene *s, const shape_ray *r, double tmax, scene_hit *h, uint64_t *tests)
{
    int best = -1;
    if (s->accel) {
        best = bvh_intersect_counted(s->accel, s->shapes, r, tmax, &tmax, tests);
    } else {
        *tests += s->nshapes;
        double tt;
        shape_ray_axes ra = shape_ray_axes_of(r);
        for (size_t i = 0; i < s->nshapes; i++) {
            if (shape_intersect_axes(&s->shapes[i], r, &ra, 0.0, tmax, &tt)) {
                tmax = tt;
                best = (int)i;
            }
        }
    }
    if (best < 0)
        return 0;
    const shape *sh = &s->shapes[best];
    h->shape = best;
    h->t = tmax;
    h->p = shape_hit_point(sh, r, tmax);
    vec3 ng = shape_normal(sh, h->p);
    h->front = vec_dot(ng, r->dir) < 0.0;
    h->n = h->front ? ng : vec_neg(ng);
    /* The hit point's rounding error is a few ulps of the largest coordinate
     * that went into it (the ray's origin, the point, the shape); a spawned
     * ray starts SCENE_EPS_REL of that away from the surface, far beyond the
     * error and far below any feature, wherever the scene sits and whatever
     * its scale (pbrt's error-bounded offsets, with a fixed generous bound). */
    h->eps = SCENE_EPS_REL * (vec_max_abs(r->origin) + vec_max_abs(h->p) + sh->magnitude);
    return 1;
}

int scene_occluded_counted(const scene *s, const shape_ray *r, double tmax, uint64_t *tests)
{
    if (s->accel)
        return bvh_occluded_counted(s->accel, s->shapes, r, tmax, tests);
    double t;
    shape_ray_axes ra = shape_ray_axes_of(r);
    for (size_t i = 0; i < s->nshapes; i++)
        if (shape_intersect_axes(&s->shapes[i], r, &ra, 0.0, tmax, &t)) {
            *tests += i + 1;
            return 1;
        }
    *tests += s->nshapes;
    return 0;
}

int scene_intersect(const scene *s, const shape_ray *r, double tmax, scene_hit *h)
{
    uint64_t tests = 0;
    return scene_intersect_counted(s, r, tmax, h, &tests);
}

int scene_occluded(const scene *s, const shape_ray *r, double tmax)
{
    uint64_t tests = 0;
    return scene_occluded_counted(s, r, tmax, &tests);
}
