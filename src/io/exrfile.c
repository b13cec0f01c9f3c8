/* exrfile.c - OpenEXR read / write through OpenEXRCore 3.1 (see include/envtex/io/exrfile.h).
 *
 * Reading decodes whole chunks (scanline blocks or tiles): the library converts each chunk's
 * half / float / uint samples into an interleaved RGB float buffer in one call, and we copy that
 * buffer's rows into the image, clipped to the display window.  We do our own file I/O
 * (pread on a descriptor we opened) so that "cannot open" errors are ours and so that the
 * library's error messages reach our error struct through user_data instead of stderr.
 */
#include "envtex/io/exrfile.h"

#include <errno.h>
#include <fcntl.h>
#include <openexr.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/io/fileio.h"
#include "envtex/io/infile.h"

/* ---- our stream: a file descriptor plus the first message the library reported ------------- */

typedef struct exr_stream {
    int fd;
    int64_t size;  /* file size for reading (lets the library validate offsets); -1 for writing */
    char msg[512]; /* first message from OpenEXRCore, "" if none */
} exr_stream;

/* Reading (a read context takes no lock to report an error); writing uses stream_on_write_error. */
static void stream_on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *ud = NULL;
    if (!ctxt || exr_get_user_data(ctxt, &ud) != EXR_ERR_SUCCESS || !ud) return;
    exr_stream *s = ud;
    if (s->msg[0]) return; /* keep the first: later ones are usually consequences */
    snprintf(s->msg, sizeof s->msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

/* Writing needs another handler: OpenEXRCore 3.1 holds a write context's lock while it reports
 * an error, and exr_get_user_data takes that same lock, so stream_on_error deadlocked (a disk
 * that filled up during exr_write_header hung envtex for good).  exrfile_write points this
 * file-scope slot at its stream for the duration of the write (envtex is single-threaded). */
static exr_stream *writing;

static void stream_on_write_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    if (!writing || writing->msg[0]) return; /* keep the first */
    snprintf(writing->msg, sizeof writing->msg, "%s",
             msg ? msg : exr_get_default_error_message(code));
}

static int64_t stream_read(exr_const_context_t ctxt, void *ud, void *buffer, uint64_t sz,
                           uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    exr_stream *s = ud;
    uint8_t *p = buffer;
    uint64_t done = 0;
    while (done < sz) {
        ssize_t n = pread(s->fd, p + done, (size_t)(sz - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            error_cb(ctxt, EXR_ERR_READ_IO, "read error: %s", strerror(errno));
            return -1;
        }
        if (n == 0) break; /* end of file: the library reports the short read */
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

static int64_t stream_size(exr_const_context_t ctxt, void *ud)
{
    (void)ctxt;
    return ((exr_stream *)ud)->size;
}

static int64_t stream_write(exr_const_context_t ctxt, void *ud, const void *buffer, uint64_t sz,
                            uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    exr_stream *s = ud;
    const uint8_t *p = buffer;
    uint64_t done = 0;
    while (done < sz) {
        ssize_t n = pwrite(s->fd, p + done, (size_t)(sz - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error_cb(ctxt, EXR_ERR_WRITE_IO, "write error: %s",
                     n < 0 ? strerror(errno) : "no progress");
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

/* The library's message if it gave one, else its text for the code. */
static const char *exr_why(const exr_stream *s, exr_result_t r)
{
    return s->msg[0] ? s->msg : exr_get_default_error_message(r);
}

/* ---- reading ------------------------------------------------------------------------------- */

/* The most any OpenEXR compression expands (unpacked / packed bytes of a chunk), with a wide
 * margin: zlib (ZIP, ZIPS, PXR24) at most 1032 : 1 (1376 : 1 counting PXR24's 24-bit floats),
 * RLE 64 : 1, B44 about 11 : 1, PIZ's run-length Huffman codes about 450 : 1. */
#define EXR_MAX_EXPANSION 4096.0
/* A display window larger than the data window is padded with black; beyond this many pixels
 * (4096 x 4096) the padding must be backed by a data window that large. */
#define EXR_MAX_PADDING_PIXELS (1L << 24)

/* Which channels feed r, g, b: indices into the channel list; grey = 1 when only Y is read. */
typedef struct exr_pick {
    int idx[3];
    int grey;
} exr_pick;

static int find_channel(const exr_attr_chlist_t *cl, const char *name)
{
    for (int i = 0; i < cl->num_channels; i++)
        if (strcmp(cl->entries[i].name.str, name) == 0) return i;
    return -1;
}

/* R,G,B; else Y alone; else the one layer "L.R","L.G","L.B".  0 ok, -1 with a message. */
static int pick_channels(const exr_attr_chlist_t *cl, exr_pick *pk, const char *path, error *err)
{
    pk->grey = 0;
    pk->idx[0] = find_channel(cl, "R");
    pk->idx[1] = find_channel(cl, "G");
    pk->idx[2] = find_channel(cl, "B");
    if (pk->idx[0] < 0 || pk->idx[1] < 0 || pk->idx[2] < 0) {
        int y = find_channel(cl, "Y");
        if (y >= 0 && (find_channel(cl, "RY") >= 0 || find_channel(cl, "BY") >= 0))
            return error_set(err, path, 0,
                             "OpenEXR luminance-chroma images (Y, RY, BY) are not supported; "
                             "re-save as RGB");
        if (y >= 0) {
            pk->grey = 1;
            pk->idx[0] = y;
            pk->idx[1] = pk->idx[2] = -1;
        } else {
            /* one layer that has .R .G .B, e.g. "beauty.R": accepted only if it is the only one */
            int found = 0;
            for (int i = 0; i < cl->num_channels; i++) {
                const char *n = cl->entries[i].name.str;
                size_t len = strlen(n);
                if (len < 3 || strcmp(n + len - 2, ".R") != 0) continue;
                char g[256], b[256];
                if (len >= sizeof g) continue;
                memcpy(g, n, len + 1);
                memcpy(b, n, len + 1);
                g[len - 1] = 'G';
                b[len - 1] = 'B';
                int ig = find_channel(cl, g), ib = find_channel(cl, b);
                if (ig < 0 || ib < 0) continue;
                if (found++) break;
                pk->idx[0] = i;
                pk->idx[1] = ig;
                pk->idx[2] = ib;
            }
            if (found != 1) {
                char names[400] = "";
                size_t at = 0;
                for (int i = 0; i < cl->num_channels && at + 2 < sizeof names; i++) {
                    int n = snprintf(names + at, sizeof names - at, "%s%s", i ? " " : "",
                                     cl->entries[i].name.str);
                    if (n < 0) break;
                    at += (size_t)n;
                }
                return error_set(err, path, 0,
                                 found ? "several layers have R, G, B channels (%s); envtex "
                                         "reads one: keep only one layer"
                                       : "no R, G, B or Y channels (channels: %s)",
                                 names);
            }
        }
    }
    for (int k = 0; k < 3; k++) {
        if (pk->idx[k] < 0) continue;
        const exr_attr_chlist_entry_t *e = &cl->entries[pk->idx[k]];
        if (e->x_sampling != 1 || e->y_sampling != 1)
            return error_set(err, path, 0, "channel %s is sub-sampled (%d x %d); not supported",
                             e->name.str, e->x_sampling, e->y_sampling);
        if (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT &&
            e->pixel_type != EXR_PIXEL_UINT)
            return error_set(err, path, 0, "channel %s has an unknown pixel type", e->name.str);
    }
    return 0;
}

/* Where decoded chunks go. */
typedef struct exr_target {
    image *im;
    exr_attr_box2i_t disp; /* display window: image pixel (0,0) is disp.min */
    float *buf;            /* one chunk, interleaved RGB float, row stride buf_w pixels */
    int buf_w;
    exr_pick pick;
} exr_target;

/* Decode the chunk `ci` whose top-left pixel is (x0, y0) in file coordinates into t->buf and copy
 * it into the image, clipped to the display window. */
static int decode_chunk(exr_context_t ctx, const exr_chunk_info_t *ci, int x0, int y0,
                        exr_decode_pipeline_t *dec, int *dec_ready, exr_target *t, exr_stream *s,
                        const char *path, error *err)
{
    exr_result_t r = *dec_ready ? exr_decoding_update(ctx, 0, ci, dec)
                                : exr_decoding_initialize(ctx, 0, ci, dec);
    if (r != EXR_ERR_SUCCESS) goto fail;
    *dec_ready = 1;
    if (ci->width > t->buf_w) {
        r = EXR_ERR_CORRUPT_CHUNK;
        goto fail;
    }
    for (int c = 0; c < dec->channel_count; c++) {
        exr_coding_channel_info_t *ch = &dec->channels[c];
        ch->decode_to_ptr = NULL;
        for (int k = 0; k < 3; k++) {
            if (t->pick.idx[k] != c) continue;
            ch->decode_to_ptr = (uint8_t *)(t->buf + k);
            ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
            ch->user_line_stride = 3 * (int32_t)sizeof(float) * t->buf_w;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = (int16_t)sizeof(float);
        }
    }
    r = exr_decoding_choose_default_routines(ctx, 0, dec);
    if (r != EXR_ERR_SUCCESS) goto fail;
    r = exr_decoding_run(ctx, 0, dec);
    if (r != EXR_ERR_SUCCESS) goto fail;

    /* copy rows, clipped to the display window */
    image *im = t->im;
    for (int j = 0; j < ci->height; j++) {
        long y = (long)y0 + j - t->disp.min.y;
        if (y < 0 || y >= im->h) continue;
        long xa = (long)x0 - t->disp.min.x, xb = xa + ci->width; /* [xa, xb) in image columns */
        long skip = xa < 0 ? -xa : 0;
        if (xa < 0) xa = 0;
        if (xb > im->w) xb = im->w;
        if (xa >= xb) continue;
        const float *src = t->buf + 3 * ((size_t)j * (size_t)t->buf_w + (size_t)skip);
        float *dst = image_px(im, (int)xa, (int)y);
        size_t n = (size_t)(xb - xa);
        if (!t->pick.grey) {
            memcpy(dst, src, n * 3 * sizeof *dst);
        } else {
            for (size_t i = 0; i < n; i++)
                dst[3 * i] = dst[3 * i + 1] = dst[3 * i + 2] = src[3 * i];
        }
    }
    return 0;
fail:
    return error_set(err, path, 0, "cannot decode OpenEXR pixels near (%d, %d): %s", x0, y0,
                     exr_why(s, r));
}

/* Before anything is allocated, the header's claims must fit in the file (docs/robustness.md):
 * every chunk lies inside the file, and the chunks together cannot decode to more than
 * EXR_MAX_EXPANSION times their stored size (exactly their size when uncompressed).  So the data
 * window of a 100-byte file cannot ask for gigabytes: a truncated or forged file is refused
 * here, not after a 3 GB allocation.  One pass over the chunk headers (the library reads the
 * chunk table once and a few bytes per chunk). */
static int check_claims(exr_context_t ctx, exr_storage_t storage, exr_compression_t comp,
                        const exr_attr_box2i_t *dw, int32_t tile_w, int32_t tile_h, int32_t lines,
                        exr_stream *s, double *largest_chunk, const char *path, error *err)
{
    double packed = 0.0, unpacked = 0.0; /* sums of bytes, double: no overflow */
    *largest_chunk = 0.0; /* packed + unpacked bytes: what the library holds to decode it */
    long data_w = (long)dw->max.x - dw->min.x + 1, data_h = (long)dw->max.y - dw->min.y + 1;
    long ntx = 1, nty = (data_h + lines - 1) / lines;
    if (storage == EXR_STORAGE_TILED) {
        ntx = (data_w + tile_w - 1) / tile_w;
        nty = (data_h + tile_h - 1) / tile_h;
    }
    for (long ty = 0; ty < nty; ty++)
        for (long tx = 0; tx < ntx; tx++) {
            exr_chunk_info_t ci;
            exr_result_t r =
                storage == EXR_STORAGE_TILED
                    ? exr_read_tile_chunk_info(ctx, 0, (int)tx, (int)ty, 0, 0, &ci)
                    : exr_read_scanline_chunk_info(ctx, 0, (int)(dw->min.y + ty * lines), &ci);
            if (r != EXR_ERR_SUCCESS)
                return error_set(err, path, 0, "bad OpenEXR chunk %ld of %ld: %s",
                                 ty * ntx + tx + 1, ntx * nty, exr_why(s, r));
            if (ci.data_offset > (uint64_t)s->size ||
                ci.packed_size > (uint64_t)s->size - ci.data_offset)
                return error_set(
                    err, path, 0,
                    "truncated OpenEXR file: chunk %ld of %ld ends past the end of the file",
                    ty * ntx + tx + 1, ntx * nty);
            packed += (double)ci.packed_size;
            unpacked += (double)ci.unpacked_size;
            double chunk = (double)ci.packed_size + (double)ci.unpacked_size;
            if (chunk > *largest_chunk) *largest_chunk = chunk;
        }
    double most = comp == EXR_COMPRESSION_NONE ? packed : EXR_MAX_EXPANSION * packed;
    if (unpacked > most)
        return error_set(err, path, 0,
                         "corrupt or truncated OpenEXR file: %ld x %ld pixels need %.0f bytes, "
                         "more than its %.0f bytes of chunks can hold",
                         data_w, data_h, unpacked, packed);
    return 0;
}

/* Open `path` and start an OpenEXRCore read context on it (the header is parsed): 0, or -1 with
 * *err set and nothing left open.  `s` must outlive *ctx (the library keeps a pointer to it). */
static int open_for_read(const char *path, exr_stream *s, exr_context_t *ctx, error *err)
{
    *ctx = NULL;
    s->fd = infile_open(path, NULL, err);
    if (s->fd < 0) return -1;
    struct stat st;
    if (fstat(s->fd, &st) != 0) {
        error_set(err, path, 0, "cannot open: %s", strerror(errno));
        goto fail;
    }
    s->size = (int64_t)st.st_size;

    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = stream_on_error;
    init.user_data = s;
    init.read_fn = stream_read;
    init.size_fn = stream_size;
    init.max_image_width = init.max_image_height = (int)IMAGE_MAX_SIDE;
    init.max_tile_width = init.max_tile_height = (int)IMAGE_MAX_SIDE;
    /* A damaged chunk table is an error, not something to rebuild by scanning the file. */
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    exr_result_t r = exr_start_read(ctx, path, &init);
    if (r == EXR_ERR_SUCCESS) return 0;
    error_set(err, path, 0, "not a readable OpenEXR file: %s", exr_why(s, r));
    if (*ctx) exr_finish(ctx);
    *ctx = NULL;
fail:
    close(s->fd);
    s->fd = -1;
    return -1;
}

/* Part 0's layout as the header gives it, checked: sizes in long so that a hostile window
 * cannot overflow before the check. */
typedef struct exr_layout {
    exr_storage_t storage;
    exr_compression_t comp;
    exr_attr_box2i_t dw;
    long disp_w, disp_h, data_w, data_h;
    int32_t tile_w, tile_h; /* tiled: level 0's tile size; scanline: 0 */
    int32_t lines;          /* rows a chunk decodes (a scanline block, or a tile's height) */
} exr_layout;

/* The storage, compression, channels (into t->pick) and windows (t->disp) of part 0: what
 * envtex can decode, or -1 with *err saying why not. */
static int read_header(exr_context_t ctx, exr_stream *s, exr_layout *L, exr_target *t,
                       const char *path, error *err)
{
    const exr_attr_chlist_t *chans = NULL;
    exr_result_t r;
    if ((r = exr_get_storage(ctx, 0, &L->storage)) || (r = exr_get_compression(ctx, 0, &L->comp)) ||
        (r = exr_get_channels(ctx, 0, &chans)) || (r = exr_get_data_window(ctx, 0, &L->dw)) ||
        (r = exr_get_display_window(ctx, 0, &t->disp)) || !chans)
        return error_set(err, path, 0, "OpenEXR header is incomplete: %s", exr_why(s, r));
    if (L->storage != EXR_STORAGE_SCANLINE && L->storage != EXR_STORAGE_TILED)
        return error_set(err, path, 0, "deep OpenEXR images are not supported");
    if (L->comp == EXR_COMPRESSION_DWAA || L->comp == EXR_COMPRESSION_DWAB)
        return error_set(err, path, 0,
                         "%s compression: OpenEXR 3.1's C API cannot decode DWAA/DWAB; re-save "
                         "the file with ZIP compression (e.g. `oiiotool in.exr --compression zip "
                         "-o out.exr`, or from any image editor)",
                         L->comp == EXR_COMPRESSION_DWAA ? "DWAA" : "DWAB");
    if (pick_channels(chans, &t->pick, path, err)) return -1;
    L->disp_w = (long)t->disp.max.x - t->disp.min.x + 1;
    L->disp_h = (long)t->disp.max.y - t->disp.min.y + 1;
    L->data_w = (long)L->dw.max.x - L->dw.min.x + 1;
    L->data_h = (long)L->dw.max.y - L->dw.min.y + 1;
    if (image_check_size(L->disp_w, L->disp_h, path, err))
        return error_prefix(err, "display window");
    if (image_check_size(L->data_w, L->data_h, path, err)) return error_prefix(err, "data window");
    return 0;
}

/* Chunk geometry: scanline blocks of L->lines rows, or tiles of level 0; sets t->buf_w. */
static int read_chunk_geometry(exr_context_t ctx, exr_stream *s, exr_layout *L, exr_target *t,
                               const char *path, error *err)
{
    exr_result_t r;
    L->tile_w = L->tile_h = L->lines = 0;
    if (L->storage == EXR_STORAGE_TILED) {
        if ((r = exr_get_tile_sizes(ctx, 0, 0, 0, &L->tile_w, &L->tile_h)) || L->tile_w < 1 ||
            L->tile_h < 1)
            return error_set(err, path, 0, "bad OpenEXR tile description: %s", exr_why(s, r));
        t->buf_w = (int)(L->tile_w < L->data_w ? L->tile_w : L->data_w);
        L->lines = (int32_t)(L->tile_h < L->data_h ? L->tile_h : L->data_h);
        return 0;
    }
    if ((r = exr_get_scanlines_per_chunk(ctx, 0, &L->lines)) || L->lines < 1)
        return error_set(err, path, 0, "bad OpenEXR compression block size: %s", exr_why(s, r));
    t->buf_w = (int)L->data_w;
    if (L->lines > L->data_h) L->lines = (int32_t)L->data_h;
    return 0;
}

/* What the header claims must fit in the file (check_claims) and in the budget: the image
 * (float RGB), our chunk buffer (the same) and the library's buffers for the largest chunk.
 * On success *image_bytes and *scratch_bytes are charged to `mem`; on failure nothing is. */
static int charge_claims(exr_context_t ctx, exr_stream *s, const exr_layout *L, const exr_target *t,
                         budget *mem, double *image_bytes, double *scratch_bytes, const char *path,
                         error *err)
{
    double largest_chunk;
    *image_bytes = *scratch_bytes = 0;
    if (check_claims(ctx, L->storage, L->comp, &L->dw, L->tile_w, L->tile_h, L->lines, s,
                     &largest_chunk, path, err))
        return -1;
    long disp = L->disp_w * L->disp_h, data = L->data_w * L->data_h;
    if (disp > data && disp > EXR_MAX_PADDING_PIXELS)
        return error_set(err, path, 0,
                         "display window %ld x %ld is far larger than the data "
                         "window %ld x %ld (envtex pads a data window with at most %ld pixels "
                         "of black)",
                         L->disp_w, L->disp_h, L->data_w, L->data_h, EXR_MAX_PADDING_PIXELS);
    double img = (double)L->disp_w * L->disp_h * IMAGE_TEXEL_BYTES;
    double scratch = (double)t->buf_w * L->lines * IMAGE_TEXEL_BYTES + largest_chunk;
    if (budget_charge(mem, img + scratch, path, 0, err,
                      "%ld x %ld texels x %d bytes, and %.0f bytes to decode a chunk", L->disp_w,
                      L->disp_h, IMAGE_TEXEL_BYTES, scratch))
        return -1;
    *image_bytes = img;
    *scratch_bytes = scratch;
    return 0;
}

/* Decode every chunk of part 0 into t->im, in file order. */
static int decode_all(exr_context_t ctx, exr_stream *s, const exr_layout *L, exr_target *t,
                      exr_decode_pipeline_t *dec, int *dec_ready, const char *path, error *err)
{
    exr_chunk_info_t ci;
    exr_result_t r;
    const exr_attr_box2i_t *dw = &L->dw;
    if (L->storage == EXR_STORAGE_TILED) {
        long ntx = (L->data_w + L->tile_w - 1) / L->tile_w;
        long nty = (L->data_h + L->tile_h - 1) / L->tile_h;
        for (long ty = 0; ty < nty; ty++)
            for (long tx = 0; tx < ntx; tx++) {
                r = exr_read_tile_chunk_info(ctx, 0, (int)tx, (int)ty, 0, 0, &ci);
                if (r != EXR_ERR_SUCCESS)
                    return error_set(err, path, 0, "bad OpenEXR tile (%ld, %ld): %s", tx, ty,
                                     exr_why(s, r));
                if (decode_chunk(ctx, &ci, (int)(dw->min.x + tx * L->tile_w),
                                 (int)(dw->min.y + ty * L->tile_h), dec, dec_ready, t, s, path,
                                 err))
                    return -1;
            }
        return 0;
    }
    for (long y = dw->min.y; y <= dw->max.y; y += L->lines) {
        r = exr_read_scanline_chunk_info(ctx, 0, (int)y, &ci);
        if (r != EXR_ERR_SUCCESS)
            return error_set(err, path, 0, "bad OpenEXR scanline block at y = %ld: %s", y,
                             exr_why(s, r));
        if (decode_chunk(ctx, &ci, dw->min.x, ci.start_y, dec, dec_ready, t, s, path, err))
            return -1;
    }
    return 0;
}

int exrfile_read(const char *path, image *out, budget *mem, error *err)
{
    out->w = out->h = 0;
    out->px = NULL;
    int rc = -1, dec_ready = 0;
    exr_stream s = {.fd = -1, .size = 0, .msg = ""};
    exr_context_t ctx = NULL;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_target t = {0};
    exr_layout L;
    image im = {0};
    double image_bytes = 0, scratch_bytes = 0; /* charged to the budget */

    if (open_for_read(path, &s, &ctx, err)) return -1;
    if (read_header(ctx, &s, &L, &t, path, err) ||
        read_chunk_geometry(ctx, &s, &L, &t, path, err) ||
        charge_claims(ctx, &s, &L, &t, mem, &image_bytes, &scratch_bytes, path, err))
        goto done;
    if (image_alloc(&im, (int)L.disp_w, (int)L.disp_h, err)) {
        error_prefix(err, "%s", path);
        goto done;
    }
    t.im = &im;
    t.buf = malloc((size_t)t.buf_w * (size_t)L.lines * 3 * sizeof *t.buf);
    if (!t.buf) {
        error_set(err, path, 0, "out of memory for a %d x %d OpenEXR chunk", t.buf_w, (int)L.lines);
        goto done;
    }
    if (decode_all(ctx, &s, &L, &t, &dec, &dec_ready, path, err)) goto done;
    *out = im;
    im.px = NULL;
    rc = 0;
done:
    if (dec_ready) exr_decoding_destroy(ctx, &dec);
    if (ctx) exr_finish(&ctx);
    if (s.fd >= 0) close(s.fd);
    free(t.buf);
    image_free(&im);
    budget_release(mem, scratch_bytes + (rc ? image_bytes : 0)); /* what was freed */
    return rc;
}

/* ---- writing ------------------------------------------------------------------------------- */

/* OpenEXRCore 3.1's ZIP compressor works in place: when a chunk does not compress (noise: a
 * path-traced image at low spp), the chunk is stored "uncompressed" -- but what it stores is
 * the predictor-and-interleave transformed bytes, not the raw pixels, so every reader gets
 * garbage for that chunk.  raw_guard wraps the library's compress step: it keeps a copy of the
 * packed (raw) chunk and puts it back when the chunk ends up stored as is. */
typedef struct raw_guard {
    exr_result_t (*compress)(exr_encode_pipeline_t *p); /* the library's */
    unsigned char *copy;
    size_t size;
} raw_guard;

static exr_result_t guarded_compress(exr_encode_pipeline_t *p)
{
    raw_guard *g = p->encoding_user_data;
    size_t n = (size_t)p->packed_bytes;
    if (n > g->size) return EXR_ERR_OUT_OF_MEMORY; /* cannot happen: sized for the largest chunk */
    memcpy(g->copy, p->packed_buffer, n);
    exr_result_t r = g->compress(p);
    if (r == EXR_ERR_SUCCESS && p->compressed_bytes >= n) {
        /* stored uncompressed: the bytes written must be the raw ones */
        memcpy(p->packed_buffer, g->copy, n);
        if (p->compressed_buffer && p->compressed_buffer != p->packed_buffer &&
            p->compressed_alloc_size >= n)
            memcpy(p->compressed_buffer, g->copy, n);
        p->compressed_bytes = n;
    }
    return r;
}

/* One scanline part "rgb": the required attributes, R, G, B of `ptype`, `at`, then the header. */
static exr_result_t write_header(exr_context_t ctx, const image *im, exr_pixel_type_t ptype,
                                 const exrfile_attrs *at, int *part)
{
    static const char *const names[3] = {"R", "G", "B"};
    exr_result_t r = exr_add_part(ctx, "rgb", EXR_STORAGE_SCANLINE, part);
    if (r == EXR_ERR_SUCCESS)
        r = exr_initialize_required_attr_simple(ctx, *part, im->w, im->h, EXR_COMPRESSION_ZIP);
    for (int k = 0; k < 3 && r == EXR_ERR_SUCCESS; k++)
        r = exr_add_channel(ctx, *part, names[k], ptype, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (r == EXR_ERR_SUCCESS) r = exrattrs_set(ctx, *part, at);
    if (r == EXR_ERR_SUCCESS) r = exr_write_header(ctx);
    return r;
}

/* Encode and write im's rows in blocks of `lines`, in increasing y (see raw_guard). */
static exr_result_t write_chunks(exr_context_t ctx, int part, const image *im, int32_t lines,
                                 raw_guard *guard, exr_encode_pipeline_t *enc, int *enc_ready)
{
    exr_result_t r = EXR_ERR_SUCCESS;
    for (int y = 0; y < im->h && r == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t ci;
        r = exr_write_scanline_chunk_info(ctx, part, y, &ci);
        if (r == EXR_ERR_SUCCESS)
            r = *enc_ready ? exr_encoding_update(ctx, part, &ci, enc)
                           : exr_encoding_initialize(ctx, part, &ci, enc);
        if (r != EXR_ERR_SUCCESS) return r;
        *enc_ready = 1;
        for (int c = 0; c < enc->channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc->channels[c];
            int k = ch->channel_name[0] == 'R' ? 0 : ch->channel_name[0] == 'G' ? 1 : 2;
            ch->encode_from_ptr = (const uint8_t *)(image_px(im, 0, y) + k);
            ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
            ch->user_line_stride = 3 * (int32_t)sizeof(float) * im->w;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = (int16_t)sizeof(float);
        }
        if ((r = exr_encoding_choose_default_routines(ctx, part, enc))) return r;
        if (enc->compress_fn) { /* see raw_guard */
            guard->compress = enc->compress_fn;
            enc->compress_fn = guarded_compress;
            enc->encoding_user_data = guard;
        }
        r = exr_encoding_run(ctx, part, enc);
    }
    return r;
}

int exrfile_write(const char *path, const image *im, int half, error *err)
{
    return exrfile_write_attrs(path, im, half, NULL, err);
}

int exrfile_write_attrs(const char *path, const image *im, int half, const exrfile_attrs *at,
                        error *err)
{
    if (!im || !im->px || image_check_size(im->w, im->h, path, err))
        return error_set(err, path, 0, "cannot write an empty or invalid image");
    char tmp[ERROR_FILE_MAX];
    exr_stream s = {.fd = -1, .size = -1, .msg = ""};
    exr_context_t ctx = NULL;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    raw_guard guard = {NULL, NULL, 0};
    int enc_ready = 0, rc = -1, part = 0;
    int32_t lines = 0;
    exr_result_t r;

    s.fd = fileio_tmp_open(path, tmp, err);
    if (s.fd < 0) return -1;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = stream_on_write_error; /* not stream_on_error: see `writing` */
    init.user_data = &s;
    init.write_fn = stream_write;
    writing = &s;
    r = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (r == EXR_ERR_SUCCESS)
        r = write_header(ctx, im, half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT, at, &part);
    if (r != EXR_ERR_SUCCESS) {
        error_set(err, path, 0, "cannot write OpenEXR header: %s", exr_why(&s, r));
        goto done;
    }
    if ((r = exr_get_scanlines_per_chunk(ctx, part, &lines)) || lines < 1) {
        error_set(err, path, 0, "cannot write OpenEXR: %s", exr_why(&s, r));
        goto done;
    }
    guard.size = (size_t)lines * (size_t)im->w * 3 * (half ? 2 : 4);
    guard.copy = malloc(guard.size);
    if (!guard.copy) {
        error_set(err, path, 0, "out of memory writing OpenEXR");
        goto done;
    }
    if ((r = write_chunks(ctx, part, im, lines, &guard, &enc, &enc_ready))) goto fail;
    if (enc_ready) exr_encoding_destroy(ctx, &enc);
    enc_ready = 0;
    r = exr_finish(&ctx); /* writes the chunk offset table */
    ctx = NULL;
    if (r != EXR_ERR_SUCCESS) goto fail;
    int fd = s.fd;
    s.fd = -1;
    if (close(fd) != 0) {
        error_set(err, path, 0, "cannot write: %s", strerror(errno));
        goto done;
    }
    rc = fileio_tmp_commit(tmp, path, err);
    tmp[0] = '\0'; /* commit removes the temporary file itself when it fails */
    goto done;
fail:
    error_set(err, path, 0, "cannot write OpenEXR pixels: %s", exr_why(&s, r));
done:
    if (enc_ready) exr_encoding_destroy(ctx, &enc);
    if (ctx) exr_finish(&ctx);
    if (s.fd >= 0) close(s.fd);
    if (rc != 0 && tmp[0]) fileio_tmp_abandon(tmp);
    free(guard.copy);
    writing = NULL;
    return rc;
}

/* ---- the envtex attributes ----------------------------------------------------------------- */

int exrfile_read_attrs(const char *path, exrfile_attrs *at, error *err)
{
    memset(at, 0, sizeof *at);
    exr_stream s = {.fd = -1, .size = 0, .msg = ""};
    exr_context_t ctx = NULL;
    if (open_for_read(path, &s, &ctx, err)) return -1;
    int rc = exrattrs_get(ctx, at, path, err);
    if (rc) memset(at, 0, sizeof *at);
    exr_finish(&ctx);
    close(s.fd);
    return rc;
}
