// The OpenImageIO image plug-in (a shared module, see image_plugin.h): encoding and decoding
// only. Files, temporary names, renames and error messages belong to the loader (image_io.c).
// Nothing here throws across the C boundary.
#include "image_plugin.h"

#include "casteljau/image_io.h"
#include "casteljau/status.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>
#include <exception>
#include <string>
#include <vector>

namespace {

// One line: OpenImageIO joins the messages of a failure with newlines.
void say(char *why, std::size_t n, const std::string &s) {
    std::string line = s.empty() ? "unknown OpenImageIO error" : s;
    while (!line.empty() && line.back() == '\n') line.pop_back();
    for (std::size_t at; (at = line.find('\n')) != std::string::npos;) line.replace(at, 1, "; ");
    std::snprintf(why, n, "%s", line.c_str());
}

// While it lives, whatever the decoders print on stderr (libpng's "libpng error: ..." lines)
// goes to a temporary file instead, so that the tool prints one line of its own. Reading
// happens before the renderers start their threads, so no other thread's output is caught.
class stderr_capture {
  public:
    stderr_capture() {
        std::fflush(stderr);
        tmp_ = std::tmpfile();
        saved_ = tmp_ ? dup(2) : -1;
        if (saved_ >= 0 && dup2(fileno(tmp_), 2) < 0) {
            close(saved_);
            saved_ = -1;
        }
    }
    ~stderr_capture() {
        restore();
        if (tmp_) std::fclose(tmp_);
    }
    void restore() {
        if (saved_ < 0) return;
        std::fflush(stderr);
        dup2(saved_, 2);
        close(saved_);
        saved_ = -1;
    }

  private:
    std::FILE *tmp_ = nullptr;
    int saved_ = -1;
};

// The extension of the last path component, lower case, without the dot ("" if none).
std::string extension_of(const char *name) {
    const char *base = std::strrchr(name, '/');
    base = base ? base + 1 : name;
    const char *dot = std::strrchr(base, '.');
    if (!dot || dot == base) return "";
    std::string e(dot + 1);
    for (char &c : e)
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    return e;
}

// Formats that store floating-point samples, and the type they store them in. Anything else
// holds 8-bit (or integer) samples, which a linear float image must not be squeezed into
// silently (no transfer curve would be applied).
bool float_storage(const std::string &format, OIIO::TypeDesc *type) {
    if (format == "openexr") {
        *type = OIIO::TypeDesc::HALF;
        return true;
    }
    if (format == "tiff" || format == "hdr" || format == "pfm" || format == "fits") {
        *type = OIIO::TypeDesc::FLOAT;
        return true;
    }
    return false;
}

// Copies the bottom-up source rows into a top-down buffer of `nch` channels; without alpha the
// colour is composited over black (rgb * alpha), as a viewer would show it.
template <typename T>
void pack_rows(const cj_image_pixels *px, int nch, float alpha_one, std::vector<T> *dst) {
    const int w = px->width, h = px->height;
    dst->resize((std::size_t)w * h * nch);
    for (int y = 0; y < h; ++y) {
        const T *src = (const T *)((const unsigned char *)px->pixels +
                                   (std::size_t)(h - 1 - y) * px->row_stride);
        T *out = dst->data() + (std::size_t)y * w * nch;
        for (int x = 0; x < w; ++x, src += 4, out += nch) {
            if (nch == 4) {
                out[0] = src[0], out[1] = src[1], out[2] = src[2], out[3] = src[3];
            } else {
                const float a = (float)src[3] / alpha_one;
                for (int c = 0; c < 3; ++c) {
                    float v = (float)src[c] * a;
                    if (alpha_one > 1.0f) v = v + 0.5f; // round 8-bit values
                    out[c] = (T)v;
                }
            }
        }
    }
}

int encode(const char *name, const char *tmp_path, const cj_image_pixels *px, unsigned char **bytes,
           std::size_t *size, char *why, std::size_t why_size) {
    *bytes = nullptr;
    *size = 0;
    try {
        const std::string ext = extension_of(name);
        if (ext.empty()) {
            std::snprintf(why, why_size, "no file extension to choose the image format from");
            return CJ_ERR_ARGUMENT;
        }
        auto out = OIIO::ImageOutput::create(ext);
        if (!out) {
            (void)OIIO::geterror(); // clear it: the message below says it better
            std::snprintf(why, why_size, "'.%s' is not an image format OpenImageIO can write",
                          ext.c_str());
            return CJ_ERR_ARGUMENT;
        }
        const std::string format = out->format_name();
        const int nch = out->supports("alpha") ? 4 : 3;
        OIIO::TypeDesc stored = OIIO::TypeDesc::UINT8;
        if (px->is_float && !float_storage(format, &stored)) {
            std::snprintf(why, why_size,
                          "the %s format stores no floating-point samples (use .exr, .tif, "
                          ".hdr or .pfm for a linear float image)",
                          format.c_str());
            return CJ_ERR_ARGUMENT;
        }
        OIIO::ImageSpec spec(px->width, px->height, nch, stored);
        if (!px->is_float) spec.attribute("oiio:UnassociatedAlpha", 1);
        if (format == "jpeg") spec.attribute("Compression", "jpeg:95");

        std::vector<unsigned char> u8;
        std::vector<float> f32;
        const void *data;
        OIIO::TypeDesc given;
        if (px->is_float) {
            pack_rows<float>(px, nch, 1.0f, &f32);
            data = f32.data();
            given = OIIO::TypeDesc::FLOAT;
        } else {
            pack_rows<unsigned char>(px, nch, 255.0f, &u8);
            data = u8.data();
            given = OIIO::TypeDesc::UINT8;
        }

        std::vector<unsigned char> mem;
        OIIO::Filesystem::IOVecOutput proxy(mem);
        const bool to_memory = out->supports("ioproxy") && out->set_ioproxy(&proxy);
        if (!out->open(to_memory ? std::string(name) : std::string(tmp_path), spec)) {
            say(why, why_size, out->geterror());
            return CJ_ERR_IO;
        }
        bool ok = out->write_image(given, data);
        std::string err = ok ? "" : out->geterror();
        if (!out->close() && ok) {
            ok = false;
            err = out->geterror();
        }
        if (!ok) {
            say(why, why_size, err);
            return CJ_ERR_IO;
        }
        if (to_memory) {
            unsigned char *buf = (unsigned char *)std::malloc(mem.size() ? mem.size() : 1);
            if (!buf) {
                std::snprintf(why, why_size, "no memory for %zu encoded bytes", mem.size());
                return CJ_ERR_NOMEM;
            }
            if (!mem.empty()) std::memcpy(buf, mem.data(), mem.size());
            *bytes = buf;
            *size = mem.size();
        }
        return CJ_OK;
    } catch (const std::bad_alloc &) {
        std::snprintf(why, why_size, "out of memory encoding a %d x %d image", px->width,
                      px->height);
        return CJ_ERR_NOMEM;
    } catch (const std::exception &e) {
        say(why, why_size, e.what());
        return CJ_ERR_IO;
    }
}

int check_file(const char *path, int width, int height, char *why, std::size_t why_size) {
    try {
        auto in = OIIO::ImageInput::open(path);
        if (!in) {
            say(why, why_size, "the file written cannot be read back: " + OIIO::geterror());
            return CJ_ERR_IO;
        }
        const OIIO::ImageSpec &spec = in->spec();
        if (spec.width != width || spec.height != height) {
            std::snprintf(why, why_size, "the file written reads back as %d x %d", spec.width,
                          spec.height);
            return CJ_ERR_IO;
        }
        std::vector<float> all((std::size_t)width * height * spec.nchannels);
        bool ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data());
        std::string err = ok ? "" : in->geterror();
        in->close();
        if (!ok) {
            say(why, why_size, "the file written cannot be decoded again: " + err);
            return CJ_ERR_IO;
        }
        return CJ_OK;
    } catch (const std::exception &e) {
        say(why, why_size, e.what());
        return CJ_ERR_IO;
    }
}

int read_rgba8(const char *path, int *width, int *height, uint8_t **rgba, char *why,
               std::size_t why_size) {
    try {
        // Ask for the stored (unassociated) alpha, so that a round trip is exact.
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        stderr_capture quiet;
        auto in = OIIO::ImageInput::open(path, &config);
        if (!in) {
            std::string e = OIIO::geterror();
            say(why, why_size, e.empty() ? "cannot open" : e);
            return CJ_ERR_IO;
        }
        const OIIO::ImageSpec &spec = in->spec();
        const int w = spec.width, h = spec.height, nc = spec.nchannels;
        if (w < 1 || h < 1 || nc < 1) {
            in->close();
            std::snprintf(why, why_size, "no pixels (%d x %d x %d)", w, h, nc);
            return CJ_ERR_IO;
        }
        // The header's claim, checked before decoding: a small file can declare a huge image.
        if (w > CJ_IMAGE_MAX_SIDE || h > CJ_IMAGE_MAX_SIDE ||
            (long long)w * h > CJ_IMAGE_MAX_PIXELS || nc > 64) {
            in->close();
            std::snprintf(why, why_size,
                          "%d x %d pixels (%d channels) is over the limit of %d pixels a side "
                          "and %lld pixels in all",
                          w, h, nc, CJ_IMAGE_MAX_SIDE, (long long)CJ_IMAGE_MAX_PIXELS);
            return CJ_ERR_RANGE;
        }
        std::vector<uint8_t> raw((std::size_t)w * h * nc);
        if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, raw.data())) {
            say(why, why_size, in->geterror());
            in->close();
            return CJ_ERR_IO;
        }
        in->close();
        uint8_t *buf = (uint8_t *)std::malloc((std::size_t)w * h * 4);
        if (!buf) {
            std::snprintf(why, why_size, "no memory for a %d x %d image", w, h);
            return CJ_ERR_NOMEM;
        }
        for (int y = 0; y < h; ++y) {
            const uint8_t *src = raw.data() + (std::size_t)(h - 1 - y) * w * nc; // flip
            uint8_t *dst = buf + (std::size_t)y * w * 4;
            for (int x = 0; x < w; ++x, src += nc, dst += 4) {
                if (nc >= 3) {
                    dst[0] = src[0], dst[1] = src[1], dst[2] = src[2];
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
    } catch (const std::bad_alloc &) {
        std::snprintf(why, why_size, "out of memory");
        return CJ_ERR_NOMEM;
    } catch (const std::exception &e) {
        say(why, why_size, e.what());
        return CJ_ERR_IO;
    }
}

const char *version() {
    return "OpenImageIO " OIIO_VERSION_STRING;
}

const cj_image_plugin table = {CJ_IMAGE_PLUGIN_ABI, encode, check_file, read_rgba8, version};

} // namespace

extern "C" __attribute__((visibility("default"))) const cj_image_plugin *cj_image_plugin_v1(void);
extern "C" const cj_image_plugin *cj_image_plugin_v1(void) {
    return &table;
}
