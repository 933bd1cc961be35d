// EXR output (issue 21, docs/light.md), read back with OpenImageIO itself:
//  - cj_image_write_float stores 32-bit floats by default: 1e5 and 3.4e38 come back exactly;
//  - CJ_IMAGE_FLOAT_HALF stores half floats: 1.5 comes back exactly, the file's channel type
//    is half; a value above 65504 (which half would turn into +inf) is refused with
//    CJ_ERR_RANGE naming the pixel, and no file is left;
//  - an infinite or NaN sample is refused in every float format with CJ_ERR_NONFINITE naming
//    the pixel (x, y from the lower-left corner) and the channel; no file is left.
#include "casteljau/image_io.h"
#include "casteljau/status.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <csetjmp>
#include <cstdarg>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

// cmocka last: its macros (fail, ...) clash with the C++ standard headers.
extern "C" {
#include <cmocka.h>
}

static const int W = 5, H = 3;

static std::string scratch(const char *name) {
    static char dir[64] = "";
    if (!dir[0]) {
        std::snprintf(dir, sizeof dir, "/tmp/cj_test_light_exr_XXXXXX");
        assert_non_null(mkdtemp(dir));
    }
    return std::string(dir) + "/" + name;
}

static bool exists(const std::string &p) {
    struct stat st;
    return stat(p.c_str(), &st) == 0;
}

// Reads pixel (x, y from the bottom) channel c and the stored channel type.
static float read_back(const std::string &path, int x, int y, int c, OIIO::TypeDesc *type) {
    auto in = OIIO::ImageInput::open(path);
    assert_true(in != nullptr);
    const OIIO::ImageSpec &spec = in->spec();
    *type = spec.format;
    std::vector<float> px((size_t)spec.width * spec.height * spec.nchannels);
    assert_true(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
    in->close();
    const int row = spec.height - 1 - y; // files are top-down
    return px[((size_t)row * spec.width + x) * spec.nchannels + c];
}

static std::vector<float> image(float fill) {
    std::vector<float> v((size_t)W * H * 4, fill);
    for (int i = 0; i < W * H; ++i) v[4 * i + 3] = 1.0f;
    return v;
}

static void test_float_by_default(void **) {
    std::vector<float> px = image(0.25f);
    px[4 * (1 * W + 3) + 0] = 1e5f;
    px[4 * (2 * W + 4) + 2] = 3.4e38f;
    const std::string path = scratch("full.exr");
    assert_int_equal(cj_image_write_float(path.c_str(), W, H, px.data(), 0), CJ_OK);
    OIIO::TypeDesc t;
    const float a = read_back(path, 3, 1, 0, &t), b = read_back(path, 4, 2, 2, &t);
    std::printf("32-bit default: stored type %s, 1e5 -> %g, 3.4e38 -> %g\n", t.c_str(), (double)a,
                (double)b);
    assert_true(t == OIIO::TypeDesc::FLOAT);
    assert_true(a == 1e5f);
    assert_true(b == 3.4e38f);
}

static void test_half_on_request(void **) {
    std::vector<float> px = image(1.5f);
    const std::string path = scratch("half.exr");
    assert_int_equal(
        cj_image_write_float_with_flags(path.c_str(), W, H, px.data(), 0, CJ_IMAGE_FLOAT_HALF),
        CJ_OK);
    OIIO::TypeDesc t;
    const float a = read_back(path, 2, 2, 1, &t);
    std::printf("half on request: stored type %s, 1.5 -> %g\n", t.c_str(), (double)a);
    assert_true(t == OIIO::TypeDesc::HALF);
    assert_true(a == 1.5f);

    px[4 * (0 * W + 2) + 1] = 70000.0f; // beyond the largest half
    const std::string big = scratch("big_half.exr");
    assert_int_equal(
        cj_image_write_float_with_flags(big.c_str(), W, H, px.data(), 0, CJ_IMAGE_FLOAT_HALF),
        CJ_ERR_RANGE);
    std::printf("70000 in half: refused: %s\n", cj_last_error());
    assert_non_null(std::strstr(cj_last_error(), "pixel (2, 0) G"));
    assert_non_null(std::strstr(cj_last_error(), "65504"));
    assert_false(exists(big));
}

static void test_no_infinity(void **) {
    const float inf = std::numeric_limits<float>::infinity();
    const char *names[] = {"inf.exr", "inf.tif", "inf_half.exr", "nan.exr"};
    for (int k = 0; k < 4; ++k) {
        std::vector<float> px = image(0.5f);
        px[4 * (2 * W + 1) + 2] = k == 3 ? std::nanf("") : inf;
        const std::string path = scratch(names[k]);
        cj_status st = cj_image_write_float_with_flags(path.c_str(), W, H, px.data(), 0,
                                                       k == 2 ? (unsigned)CJ_IMAGE_FLOAT_HALF : 0u);
        std::printf("%s: status %d: %s\n", names[k], (int)st, cj_last_error());
        assert_int_equal(st, CJ_ERR_NONFINITE);
        assert_non_null(std::strstr(cj_last_error(), "pixel (1, 2) B"));
        assert_false(exists(path));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_float_by_default),
        cmocka_unit_test(test_half_on_request),
        cmocka_unit_test(test_no_infinity),
    };
    const int failed = cmocka_run_group_tests(tests, NULL, NULL);
    for (const char *name : {"full.exr", "half.exr"}) std::remove(scratch(name).c_str());
    rmdir(scratch("").c_str());
    return failed;
}
