/* infile.h - the files a run reads: regular files only, opened without blocking, and known by
 * identity (device, inode): sky.exr, ./sky.exr and a hard link are one file.
 *
 *     int fd = infile_open("sky.exr", &id, &err);  // a FIFO: "cannot open: it is a FIFO, ..."
 *     const char *clash = infile_list_clash(&inputs, "out.exr");  // an input it names, or NULL
 *
 * Links are followed; FIFOs, sockets, folders, devices and link loops are refused, saying so.
 */
#ifndef ENVTEX_INFILE_H
#define ENVTEX_INFILE_H

#include <stdio.h>

#include "envtex/core/error.h"

/* Two names are one file exactly when both fields agree. */
typedef struct infile_id {
    unsigned long long dev, ino;
} infile_id;

static inline int infile_same(infile_id a, infile_id b) { return a.dev == b.dev && a.ino == b.ino; }

/* Open a regular file to read, never blocking: a descriptor (close it), its identity in *id
 * (may be NULL); or -1 with "cannot open: why" naming `path`. */
int infile_open(const char *path, infile_id *id, error *err);

/* The same, also accepting a pipe for a file read once (a scene: `envtex render <(gen)`); a
 * FIFO nobody writes to reads as empty. */
int infile_open_stream(const char *path, infile_id *id, error *err);

/* infile_open as a stdio stream ("rb"); NULL on failure. */
FILE *infile_fopen(const char *path, infile_id *id, error *err);

/* The identity of the file `path` names (stat, never opened): 0, or -1 if none. */
int infile_identify(const char *path, infile_id *id);

/* Each distinct input once, under its first name; zeroed is empty. */
typedef struct infile_list {
    struct infile_entry {
        infile_id id;
        char *path; /* owned */
    } * at;
    int n, cap;
} infile_list;

/* Add the file `path` names: 0 (also if listed already or missing), -1 out of memory. */
int infile_list_add(infile_list *l, const char *path, error *err);

/* The same for a file whose identity is known (as infile_open returned it). */
int infile_list_add_id(infile_list *l, const char *path, infile_id id, error *err);

/* The index of the file with identity id, or -1. */
int infile_list_find(const infile_list *l, infile_id id);

/* The input that writing `out` would replace (the same file), or NULL. */
const char *infile_list_clash(const infile_list *l, const char *out);

/* Free the names and the array; zero *l. */
void infile_list_free(infile_list *l);

#endif
