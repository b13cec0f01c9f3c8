/* infile.c - the files a run reads (see include/envtex/io/infile.h). */
#include "envtex/io/infile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* What a file that is not regular is, for the message. */
static const char *kind_of(mode_t m)
{
    if (S_ISDIR(m)) return "a directory";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISSOCK(m)) return "a socket";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    return "not a regular file";
}

static infile_id id_of(const struct stat *st)
{
    return (infile_id){(unsigned long long)st->st_dev, (unsigned long long)st->st_ino};
}

/* Open path without blocking and keep it when it is a regular file, or (pipes = 1) a pipe. */
static int open_input(const char *path, int pipes, infile_id *id, error *err)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        struct stat st;
        if (e == ELOOP)
            return error_set(err, path, 0, "cannot open: a loop of symbolic links (%s)",
                             strerror(e));
        if (e == ENXIO && stat(path, &st) == 0 && S_ISSOCK(st.st_mode)) /* sockets do not open */
            return error_set(err, path, 0, "cannot open: it is a socket, not a regular file%s",
                             pipes ? " or a pipe" : "");
        return error_set(err, path, 0, "cannot open: %s", strerror(e));
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int e = errno;
        close(fd);
        return error_set(err, path, 0, "cannot open: %s", strerror(e));
    }
    if (!S_ISREG(st.st_mode) && !(pipes && S_ISFIFO(st.st_mode))) {
        close(fd);
        return error_set(err, path, 0, "cannot open: it is %s, not a regular file%s",
                         kind_of(st.st_mode), pipes ? " or a pipe" : "");
    }
    /* reads block as usual: a pipe's writer may be slow (a FIFO nobody opened reads as empty) */
    int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
        int e = errno;
        close(fd);
        return error_set(err, path, 0, "cannot open: %s", strerror(e));
    }
    if (id) *id = id_of(&st);
    return fd;
}

int infile_open(const char *path, infile_id *id, error *err)
{
    return open_input(path, 0, id, err);
}

int infile_open_stream(const char *path, infile_id *id, error *err)
{
    return open_input(path, 1, id, err);
}

FILE *infile_fopen(const char *path, infile_id *id, error *err)
{
    int fd = infile_open(path, id, err);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        int e = errno;
        close(fd);
        error_set(err, path, 0, "cannot open: %s", strerror(e));
    }
    return f;
}

int infile_identify(const char *path, infile_id *id)
{
    struct stat st;
    if (!path || !path[0] || stat(path, &st) != 0) return -1;
    *id = id_of(&st);
    return 0;
}

int infile_list_find(const infile_list *l, infile_id id)
{
    for (int i = 0; i < l->n; i++)
        if (infile_same(l->at[i].id, id)) return i;
    return -1;
}

int infile_list_add_id(infile_list *l, const char *path, infile_id id, error *err)
{
    if (infile_list_find(l, id) >= 0) return 0;
    if (l->n == l->cap) {
        int cap = l->cap > 0 ? 2 * l->cap : 8;
        struct infile_entry *at = realloc(l->at, (size_t)cap * sizeof *at);
        if (!at) return error_set(err, path, 0, "out of memory for the list of inputs");
        l->at = at;
        l->cap = cap;
    }
    char *copy = strdup(path);
    if (!copy) return error_set(err, path, 0, "out of memory for the list of inputs");
    l->at[l->n++] = (struct infile_entry){id, copy};
    return 0;
}

int infile_list_add(infile_list *l, const char *path, error *err)
{
    infile_id id;
    if (infile_identify(path, &id)) return 0;
    return infile_list_add_id(l, path, id, err);
}

const char *infile_list_clash(const infile_list *l, const char *out)
{
    infile_id id;
    if (infile_identify(out, &id)) return NULL;
    int i = infile_list_find(l, id);
    return i >= 0 ? l->at[i].path : NULL;
}

void infile_list_free(infile_list *l)
{
    if (!l) return;
    for (int i = 0; i < l->n; i++) free(l->at[i].path);
    free(l->at);
    memset(l, 0, sizeof *l);
}
