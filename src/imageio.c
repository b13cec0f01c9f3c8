/* imageio.c - STUB until the image I/O modules land. */
#include "envtex/imageio.h"
int imageio_read(const char *path, image *out, error *err)
{
    out->w = out->h = 0; out->px = NULL;
    return error_set(err, path, 0, "image reading is not implemented yet");
}
int imageio_write(const char *path, const image *im, const tonemap_params *tm, error *err)
{
    (void)im; (void)tm;
    return error_set(err, path, 0, "image writing is not implemented yet");
}
int imageio_can_write(const char *path) { (void)path; return 0; }
int imageio_tmp_open(const char *path, char *tmp_path, error *err) { (void)tmp_path; return error_set(err, path, 0, "stub"); }
int imageio_tmp_commit(const char *tmp_path, const char *path, error *err) { (void)tmp_path; return error_set(err, path, 0, "stub"); }
void imageio_tmp_abandon(const char *tmp_path) { (void)tmp_path; }
