/* infile.h - the files a run reads: opened only when they are regular files, without ever
 * blocking, and known by their identity (device and inode), so that sky.exr, ./sky.exr and a
 * hard link to it are one file (docs/robustness.md, "Inputs and outputs").
 *
 *     infile_id id;
 *     int fd = infile_open("sky.exr", &id, &err);   // err: "sky.exr: cannot open: it is a FIFO,
 *     if (fd < 0) return -1;                         //       not a regular file"
 *     ... read(fd, ...) ...; close(fd);
 *
 *     infile_list in = {0};                          // every input of the run, by identity
 *     if (infile_list_add(&in, "sky.exr", &err)) ...
 *     const char *clash = infile_list_clash(&in, "out.exr");  // the input out.exr names, or NULL
 *     infile_list_free(&in);
 *
 * Opening: open(O_RDONLY | O_NONBLOCK), so a FIFO without a writer cannot block the open, then
 * fstat on the descriptor (not the name, which may change in between), then O_NONBLOCK cleared
 * for the reads.  Anything else is refused with what it is: a FIFO, a socket, a directory, a
 * character or block device, a loop of symbolic links.  Symbolic links are followed.
 */
#ifndef ENVTEX_INFILE_H
#define ENVTEX_INFILE_H

#include <stdio.h>

#include "envtex/core/error.h"

/* A file's identity: two names are one file exactly when both fields agree. */
typedef struct infile_id {
    unsigned long long dev, ino;
} infile_id;

static inline int infile_same(infile_id a, infile_id b) { return a.dev == b.dev && a.ino == b.ino; }

/* Open a regular file for reading: a descriptor (close it), with its identity in *id (may be
 * NULL); or -1 with "cannot open: why" naming `path` in *err. */
int infile_open(const char *path, infile_id *id, error *err);

/* The same for a file read once from start to end (a scene): a regular file or a pipe (a FIFO,
 * `envtex render <(make-scene)`).  A FIFO nobody writes to reads as empty: it never blocks. */
int infile_open_stream(const char *path, infile_id *id, error *err);

/* infile_open as a stdio stream ("rb"); NULL on failure. */
FILE *infile_fopen(const char *path, infile_id *id, error *err);

/* The identity of the file `path` names now (stat, following links): 0, or -1 when there is
 * none (no such file).  Never opens it. */
int infile_identify(const char *path, infile_id *id);

/* The inputs of a run: each distinct file once, with the first name it was read under. */
typedef struct infile_list {
    struct infile_entry {
        infile_id id;
        char *path; /* owned */
    } *at;
    int n, cap;
} infile_list;

/* Add the file `path` names (infile_identify): 0 (also when it is in the list already, or when
 * it does not exist: nothing to protect), -1 out of memory. */
int infile_list_add(infile_list *l, const char *path, error *err);

/* The same for a file whose identity is known (as infile_open returned it). */
int infile_list_add_id(infile_list *l, const char *path, infile_id id, error *err);

/* The index of the file with identity id, or -1. */
int infile_list_find(const infile_list *l, infile_id id);

/* The name of the input that writing `out` would replace (out names the same file), or NULL
 * (out does not exist yet, or is no input). */
const char *infile_list_clash(const infile_list *l, const char *out);

/* Free the names and the array; zero *l. */
void infile_list_free(infile_list *l);

#endif
