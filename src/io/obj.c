/* obj.c - the Wavefront OBJ reader (see include/envtex/io/obj.h). */
#include "envtex/io/obj.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/io/fileio.h"

typedef struct reader {
    obj_mesh *m;
    const char *name;
    error *err;
    int line;
    long max;
    long cap_v, cap_vt, cap_vn, cap_tris;
    budget *mem;
} reader;

static int fail(reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(reader *r, const char *fmt, ...)
{
    char msg[ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return error_set(r->err, r->name, r->line, "%s", msg);
}

/* Room for one more element in *arr (count n, capacity *cap): the limit is checked first. */
static int grow(reader *r, void **arr, long n, long *cap, size_t size, const char *what)
{
    if (n >= r->max) return fail(r, "more than %ld %s", r->max, what);
    if (n < *cap) return 0;
    long c = *cap > 0 ? *cap : 64;
    while (c <= n) c *= 2;                           /* n < max <= OBJ_MAX_ELEMS: no overflow */
    double more = (double)(c - *cap) * (double)size; /* what the array grows by */
    if (budget_charge(r->mem, more, r->name, r->line, r->err, "room for %ld more %s x %zu bytes",
                      c - *cap, what, size))
        return -1;
    void *q = realloc(*arr, (size_t)c * size);
    if (!q) {
        budget_release(r->mem, more);
        return fail(r, "out of memory for %ld %s", n + 1, what);
    }
    r->m->bytes += more;
    *arr = q;
    *cap = c;
    return 0;
}

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/* Next white-space separated token of *s (NUL-terminated in place), or NULL at the end. */
static char *next_token(char **s)
{
    char *p = *s;
    while (is_space(*p)) p++;
    if (*p == '\0' || *p == '#') return NULL; /* a '#' token ends the line */
    char *start = p;
    while (*p && !is_space(*p)) p++;
    if (*p) *p++ = '\0';
    *s = p;
    return start;
}

static int parse_num(reader *r, const char *kw, const char *tok, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(tok, &end);
    if (end == tok || *end != '\0') return fail(r, "expected a number for '%s', got '%s'", kw, tok);
    if (!isfinite(v)) return fail(r, "expected a finite number for '%s', got '%s'", kw, tok);
    *out = v;
    return 0;
}

/* `count` numbers (at least `need`, the rest default to 0); extra tokens beyond `allow` error. */
static int parse_nums(reader *r, const char *kw, char **s, int need, int allow, double *v)
{
    int n = 0;
    char *tok;
    while ((tok = next_token(s)) != NULL) {
        if (n >= allow)
            return fail(r, "'%s' takes at most %d numbers, got more ('%s')", kw, allow, tok);
        double x = 0;
        if (parse_num(r, kw, tok, &x)) return -1;
        if (n < 3) v[n] = x;
        n++;
    }
    if (n < need) return fail(r, "'%s' takes %d numbers, got %d", kw, need, n);
    for (int k = n; k < 3; k++) v[k] = 0;
    return 0;
}

/* One index of a face corner: 1-based, or negative relative to `count` records so far. */
static int parse_index(reader *r, const char *text, size_t len, long count, const char *what,
                       long *out)
{
    char buf[32];
    if (len == 0 || len >= sizeof buf)
        return fail(r, "bad index '%.*s' in 'f'", (int)(len < 20 ? len : 20), text);
    memcpy(buf, text, len);
    buf[len] = '\0';
    char *end;
    errno = 0;
    long i = strtol(buf, &end, 10);
    if (*end != '\0' || errno) return fail(r, "bad index '%s' in 'f'", buf);
    long k = i > 0 ? i - 1 : i < 0 ? count + i : -1; /* -1 is the latest: count - 1 */
    if (i == 0 || k < 0 || k >= count)
        return fail(r, "index %s of 'f' is out of range: %ld %s so far", buf, count, what);
    *out = k;
    return 0;
}

/* A corner "v", "v/vt", "v//vn" or "v/vt/vn". */
static int parse_corner(reader *r, const char *tok, long *v, long *vt, long *vn)
{
    const char *a = strchr(tok, '/');
    const char *b = a ? strchr(a + 1, '/') : NULL;
    if (b && strchr(b + 1, '/')) return fail(r, "bad corner '%s' in 'f'", tok);
    size_t lv = a ? (size_t)(a - tok) : strlen(tok);
    if (parse_index(r, tok, lv, r->m->n_v, "vertices", v)) return -1;
    *vt = *vn = -1;
    if (a) {
        size_t lt = b ? (size_t)(b - a - 1) : strlen(a + 1);
        if (lt > 0 && parse_index(r, a + 1, lt, r->m->n_vt, "texture coordinates", vt)) return -1;
        if (lt == 0 && !b) return fail(r, "bad corner '%s' in 'f' (nothing after '/')", tok);
    }
    if (b && parse_index(r, b + 1, strlen(b + 1), r->m->n_vn, "normals", vn)) return -1;
    return 0;
}

static int add_tri(reader *r, const long c[3][3])
{
    obj_mesh *m = r->m;
    if (grow(r, (void **)&m->tris, m->n_tris, &r->cap_tris, sizeof *m->tris, "triangles"))
        return -1;
    obj_triangle *t = &m->tris[m->n_tris++];
    for (int k = 0; k < 3; k++) {
        t->v[k] = c[k][0];
        t->vt[k] = c[k][1];
        t->vn[k] = c[k][2];
    }
    return 0;
}

static int parse_face(reader *r, char **s)
{
    long c[3][3]; /* first, previous and current corner: (v, vt, vn) */
    int n = 0;
    char *tok;
    while ((tok = next_token(s)) != NULL) {
        long cur[3];
        if (parse_corner(r, tok, &cur[0], &cur[1], &cur[2])) return -1;
        if (n < 2) {
            memcpy(c[n], cur, sizeof cur);
        } else {
            memcpy(c[2], cur, sizeof cur);
            if (add_tri(r, (const long(*)[3])c)) return -1; /* fan: (c1, previous, current) */
            memcpy(c[1], cur, sizeof cur);
        }
        n++;
    }
    if (n < 3) return fail(r, "'f' needs at least 3 corners, got %d", n);
    return 0;
}

static int parse_line(reader *r, char *s)
{
    obj_mesh *m = r->m;
    char *kw = next_token(&s);
    if (!kw || kw[0] == '#') return 0;
    double v[3];
    if (strcmp(kw, "v") == 0) {
        if (parse_nums(r, kw, &s, 3, 7, v)) return -1;
        if (grow(r, (void **)&m->v, m->n_v, &r->cap_v, sizeof *m->v, "vertices")) return -1;
        m->v[m->n_v++] = vec3_make(v[0], v[1], v[2]);
    } else if (strcmp(kw, "vt") == 0) {
        if (parse_nums(r, kw, &s, 1, 3, v)) return -1;
        if (grow(r, (void **)&m->vt, m->n_vt, &r->cap_vt, sizeof *m->vt, "texture coordinates"))
            return -1;
        m->vt[m->n_vt++] = (uv2){v[0], v[1]};
    } else if (strcmp(kw, "vn") == 0) {
        if (parse_nums(r, kw, &s, 3, 3, v)) return -1;
        if (grow(r, (void **)&m->vn, m->n_vn, &r->cap_vn, sizeof *m->vn, "normals")) return -1;
        m->vn[m->n_vn++] = vec3_make(v[0], v[1], v[2]);
    } else if (strcmp(kw, "f") == 0) {
        return parse_face(r, &s);
    } else {
        if (m->n_ignored++ == 0) {
            snprintf(m->first_ignored, sizeof m->first_ignored, "%s", kw);
            m->first_ignored_line = r->line;
        }
    }
    return 0;
}

static int parse(const char *text, size_t len, const char *name, long max_elems, obj_mesh *out,
                 budget *mem, error *err)
{
    memset(out, 0, sizeof *out);
    reader r;
    memset(&r, 0, sizeof r);
    r.m = out;
    r.mem = mem;
    r.name = name ? name : "<string>";
    r.err = err;
    r.max = max_elems > 0 && max_elems < OBJ_MAX_ELEMS ? max_elems : OBJ_MAX_ELEMS;
    int rc = -1;
    char *buf = malloc(OBJ_MAX_LINE + 1);
    if (!buf) {
        error_set(err, r.name, 0, "out of memory");
        goto done;
    }
    size_t pos = 0;
    /* a UTF-8 byte-order mark some editors write is not part of the first keyword */
    if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) pos = 3;
    while (pos < len) {
        r.line++;
        const char *nl = memchr(text + pos, '\n', len - pos);
        size_t n = (nl ? (size_t)(nl - text) : len) - pos;
        if (n > OBJ_MAX_LINE) {
            fail(&r, "line is longer than %d bytes", OBJ_MAX_LINE);
            goto done;
        }
        memcpy(buf, text + pos, n);
        buf[n] = '\0';
        pos += n + 1;
        if (memchr(buf, '\0', n)) {
            fail(&r, "NUL byte in the file (binary file?)");
            goto done;
        }
        if (parse_line(&r, buf)) goto done;
    }
    rc = 0;
done:
    free(buf);
    if (rc) {
        budget_release(mem, out->bytes);
        obj_free(out);
    }
    return rc;
}

int obj_load_string(const char *text, const char *name, long max_elems, obj_mesh *out, budget *mem,
                    error *err)
{
    return parse(text, strlen(text), name, max_elems, out, mem, err);
}

int obj_load(const char *path, long max_elems, obj_mesh *out, budget *mem, error *err)
{
    memset(out, 0, sizeof *out);
    unsigned char *data = NULL;
    size_t size = 0;
    if (fileio_read_all(path, &data, &size, mem, err)) return -1;
    int rc = parse((const char *)data, size, path, max_elems, out, mem, err);
    free(data);
    budget_release(mem, (double)size + 1); /* the file's bytes (fileio_read_all) */
    return rc;
}

void obj_free(obj_mesh *m)
{
    if (!m) return;
    free(m->v);
    free(m->vt);
    free(m->vn);
    free(m->tris);
    memset(m, 0, sizeof *m);
}
