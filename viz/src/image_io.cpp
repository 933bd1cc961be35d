// OpenImageIO behind the C API of casteljau/image_io.h. Nothing here throws across the C
// boundary: every OIIO or standard-library failure becomes a cj_status via cj_fail.
#include "casteljau/image_io.h"

#include "error_internal.h"

#include <OpenImageIO/imageio.h>

#include <atomic>
#include <cassert>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace {

std::atomic<unsigned> tmp_counter{0};

// Creates a fresh, empty file next to `path` and returns its name in *tmp (mode 0666 minus
// umask, like a file created by fopen). Returns false with errno set on failure.
bool create_temp_beside(const std::string &path, std::string *tmp) {
    std::string dir, base;
    std::size_t slash = path.rfind('/');
    if (slash == std::string::npos) {
        dir = "";
        base = path;
    } else {
        dir = path.substr(0, slash + 1);
        base = path.substr(slash + 1);
    }
    unsigned long seed = (unsigned long)getpid() * 2654435761ul ^ (unsigned long)time(nullptr);
    for (int attempt = 0; attempt < 100; ++attempt) {
        char suffix[64];
        unsigned c = tmp_counter.fetch_add(1);
        std::snprintf(suffix, sizeof suffix, ".tmp-%lx-%x", seed % 0xfffffful, c);
        std::string name = dir + "." + base + suffix;
        int fd = open(name.c_str(), O_CREAT | O_EXCL | O_WRONLY, 0666);
        if (fd >= 0) {
            close(fd);
            *tmp = name;
            return true;
        }
        if (errno != EEXIST) return false;
    }
    errno = EEXIST;
    return false;
}

} // namespace

extern "C" cj_status cj_image_write_png(const char *path, int width, int height,
                                        const uint8_t *rgba, size_t row_stride) {
    assert(path && rgba);
    if (width < 1 || height < 1 || width > 65535 || height > 65535)
        return cj_fail(CJ_ERR_ARGUMENT, "image size %d x %d is not between 1 and 65535", width,
                       height);
    const std::size_t row_bytes = (std::size_t)width * 4;
    if (row_stride == 0) row_stride = row_bytes;
    if (row_stride < row_bytes)
        return cj_fail(CJ_ERR_ARGUMENT, "row stride %zu is smaller than 4*width = %zu", row_stride,
                       row_bytes);

    std::string tmp;
    if (!create_temp_beside(path, &tmp))
        return cj_fail(CJ_ERR_IO, "cannot create a temporary file beside '%s': %s", path,
                       std::strerror(errno));

    std::string why;
    bool ok = false;
    try {
        auto out = OIIO::ImageOutput::create("png");
        if (!out) {
            why = "OpenImageIO has no PNG writer: " + OIIO::geterror();
        } else {
            OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
            spec.attribute("oiio:UnassociatedAlpha", 1);
            if (!out->open(tmp, spec)) {
                why = out->geterror();
            } else {
                // Files are top row first: start at the last (top) row of the bottom-up buffer
                // and walk down with a negative stride.
                const uint8_t *top = rgba + (std::size_t)(height - 1) * row_stride;
                bool wrote =
                    out->write_image(OIIO::TypeDesc::UINT8, top, 4, -(OIIO::stride_t)row_stride);
                if (!wrote) why = out->geterror();
                bool closed = out->close();
                if (wrote && !closed) why = out->geterror();
                ok = wrote && closed;
            }
        }
    } catch (const std::exception &e) {
        why = e.what();
        ok = false;
    }
    if (ok && std::rename(tmp.c_str(), path) != 0) {
        why = std::string("rename failed: ") + std::strerror(errno);
        ok = false;
    }
    if (!ok) {
        std::remove(tmp.c_str());
        if (why.empty()) why = "unknown OpenImageIO error";
        return cj_fail(CJ_ERR_IO, "cannot write PNG '%s': %s", path, why.c_str());
    }
    return CJ_OK;
}

extern "C" cj_status cj_image_read(const char *path, int *width, int *height, uint8_t **rgba) {
    assert(path && width && height && rgba);
    std::string why;
    try {
        // Ask for the stored (unassociated) alpha, so that a round trip is exact.
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        auto in = OIIO::ImageInput::open(path, &config);
        if (!in) {
            why = OIIO::geterror();
            if (why.empty()) why = "cannot open";
            return cj_fail(CJ_ERR_IO, "cannot read image '%s': %s", path, why.c_str());
        }
        const OIIO::ImageSpec &spec = in->spec();
        const int w = spec.width, h = spec.height, nc = spec.nchannels;
        if (w < 1 || h < 1 || nc < 1) {
            in->close();
            return cj_fail(CJ_ERR_IO, "image '%s' has no pixels (%d x %d x %d)", path, w, h, nc);
        }
        std::vector<uint8_t> raw((std::size_t)w * h * nc);
        if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, raw.data())) {
            why = in->geterror();
            in->close();
            return cj_fail(CJ_ERR_IO, "cannot decode image '%s': %s", path, why.c_str());
        }
        in->close();
        uint8_t *buf = (uint8_t *)std::malloc((std::size_t)w * h * 4);
        if (!buf) return cj_fail(CJ_ERR_NOMEM, "no memory for a %d x %d image", w, h);
        for (int y = 0; y < h; ++y) {
            const uint8_t *src = raw.data() + (std::size_t)(h - 1 - y) * w * nc; // flip
            uint8_t *dst = buf + (std::size_t)y * w * 4;
            for (int x = 0; x < w; ++x, src += nc, dst += 4) {
                if (nc >= 3) {
                    dst[0] = src[0];
                    dst[1] = src[1];
                    dst[2] = src[2];
                    dst[3] = nc >= 4 ? src[3] : 255;
                } else {
                    dst[0] = dst[1] = dst[2] = src[0];
                    dst[3] = nc == 2 ? src[1] : 255;
                }
            }
        }
        *width = w;
        *height = h;
        *rgba = buf;
        return CJ_OK;
    } catch (const std::exception &e) {
        return cj_fail(CJ_ERR_IO, "cannot read image '%s': %s", path, e.what());
    }
}

extern "C" void cj_image_free(uint8_t *rgba) {
    std::free(rgba);
}
