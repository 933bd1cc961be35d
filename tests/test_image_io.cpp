// PNG files through the viz/ OpenImageIO adapter: exact round trip, row order in the file
// (checked by reading the file with OpenImageIO directly, independently of cj_image_read),
// strides, atomic writes (temporary file renamed into place, nothing left on failure), errors.
#include <csetjmp>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include "casteljau/image_io.h"
#include "casteljau/plot.h" // with text.h, framebuffer.h: must compile as C++ too

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

// cmocka last: its macros (fail, ...) clash with the C++ standard headers.
extern "C" {
#include <cmocka.h>
#include "rng.h"
}

static std::string scratch_dir() {
    char tmpl[] = "/tmp/cj_test_image_io_XXXXXX";
    const char *d = mkdtemp(tmpl);
    assert_non_null(d);
    return d;
}

// Names in a directory other than . and ..
static std::vector<std::string> list_dir(const std::string &dir) {
    std::vector<std::string> out;
    DIR *d = opendir(dir.c_str());
    assert_non_null(d);
    while (struct dirent *e = readdir(d))
        if (std::strcmp(e->d_name, ".") && std::strcmp(e->d_name, "..")) out.push_back(e->d_name);
    closedir(d);
    return out;
}

static void remove_tree(const std::string &dir) {
    for (const std::string &n : list_dir(dir)) {
        std::string p = dir + "/" + n;
        if (std::remove(p.c_str()) != 0) rmdir(p.c_str());
    }
    rmdir(dir.c_str());
}

static void test_round_trip_random(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_image_io round trip", 4242));
    std::string dir = scratch_dir();
    const int sizes[][2] = {{1, 1}, {37, 23}, {64, 1}, {1, 50}, {129, 67}};
    for (const auto &sz : sizes) {
        const int w = sz[0], h = sz[1];
        std::vector<uint8_t> px((size_t)w * h * 4);
        // Random bytes everywhere, including colour under alpha 0: straight alpha must survive.
        for (auto &b : px) b = (uint8_t)cj_rng_int(&rng, 0, 255);
        std::string path = dir + "/rt.png";
        assert_int_equal(cj_image_write_png(path.c_str(), w, h, px.data(), 0), CJ_OK);
        int rw = 0, rh = 0;
        uint8_t *back = nullptr;
        assert_int_equal(cj_image_read(path.c_str(), &rw, &rh, &back), CJ_OK);
        assert_int_equal(rw, w);
        assert_int_equal(rh, h);
        assert_memory_equal(back, px.data(), px.size());
        cj_image_free(back);
    }
    assert_int_equal((int)list_dir(dir).size(), 1); // only rt.png: no temporary left behind
    remove_tree(dir);
    std::printf("test_image_io: %zu random RGBA8 images written and read back bit-identically\n",
                sizeof sizes / sizeof sizes[0]);
}

static void test_file_is_top_row_first(void **state) {
    (void)state;
    std::string dir = scratch_dir();
    const int w = 5, h = 3, stride = w * 4 + 12; // padded rows
    std::vector<uint8_t> px((size_t)stride * h, 0xEE);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint8_t *p = &px[(size_t)y * stride + 4 * x];
            p[0] = (uint8_t)(10 * y); // row index of the bottom-up buffer in red
            p[1] = (uint8_t)(20 * x);
            p[2] = 7;
            p[3] = 255;
        }
    std::string path = dir + "/rows.png";
    assert_int_equal(cj_image_write_png(path.c_str(), w, h, px.data(), (size_t)stride), CJ_OK);
    // Independent reader: OpenImageIO itself, scanline 0 = top row of the file.
    auto in = OIIO::ImageInput::open(path);
    assert_non_null(in.get());
    assert_int_equal(in->spec().nchannels, 4);
    std::vector<uint8_t> file((size_t)w * h * 4);
    assert_true(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, file.data()));
    in->close();
    for (int fy = 0; fy < h; ++fy)
        for (int x = 0; x < w; ++x) {
            const uint8_t *p = &file[((size_t)fy * w + x) * 4];
            assert_int_equal(p[0], 10 * (h - 1 - fy)); // file row fy = buffer row h-1-fy
            assert_int_equal(p[1], 20 * x);
        }
    remove_tree(dir);
    std::printf("test_image_io: file rows are top first (buffer row h-1 first), stride honoured\n");
}

static void test_failed_write_leaves_nothing(void **state) {
    (void)state;
    std::string dir = scratch_dir();
    uint8_t px[4 * 4] = {0};
    // 1. Destination directory does not exist: the temporary cannot even be created.
    std::string missing = dir + "/no/such/dir/out.png";
    assert_int_equal(cj_image_write_png(missing.c_str(), 2, 2, px, 0), CJ_ERR_IO);
    assert_non_null(std::strstr(cj_last_error(), "no/such/dir/out.png"));
    struct stat st;
    assert_int_not_equal(stat(missing.c_str(), &st), 0);
    assert_true(list_dir(dir).empty());
    // 2. The temporary is written but the rename fails (the destination is a directory): the
    //    temporary must be removed and the directory left as it was.
    std::string blocker = dir + "/taken.png";
    assert_int_equal(mkdir(blocker.c_str(), 0755), 0);
    assert_int_equal(cj_image_write_png(blocker.c_str(), 2, 2, px, 0), CJ_ERR_IO);
    std::vector<std::string> names = list_dir(dir);
    assert_int_equal((int)names.size(), 1);
    assert_string_equal(names[0].c_str(), "taken.png");
    // 3. Overwriting an existing file replaces it whole.
    std::string path = dir + "/img.png";
    FILE *f = std::fopen(path.c_str(), "wb");
    assert_non_null(f);
    std::fputs("old content", f);
    std::fclose(f);
    uint8_t one[4] = {1, 2, 3, 4};
    assert_int_equal(cj_image_write_png(path.c_str(), 1, 1, one, 0), CJ_OK);
    int w = 0, h = 0;
    uint8_t *back = nullptr;
    assert_int_equal(cj_image_read(path.c_str(), &w, &h, &back), CJ_OK);
    assert_memory_equal(back, one, 4);
    cj_image_free(back);
    assert_int_equal((int)list_dir(dir).size(), 2);
    remove_tree(dir);
    std::printf("test_image_io: failed writes (missing dir, failed rename) leave no file; "
                "overwrite replaces\n");
}

static void test_bad_arguments_and_reads(void **state) {
    (void)state;
    std::string dir = scratch_dir();
    uint8_t px[16] = {0};
    std::string path = dir + "/x.png";
    assert_int_equal(cj_image_write_png(path.c_str(), 0, 2, px, 0), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_image_write_png(path.c_str(), 2, -1, px, 0), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_image_write_png(path.c_str(), 2, 2, px, 7), CJ_ERR_ARGUMENT);
    assert_true(list_dir(dir).empty());
    int w = -1, h = -1;
    uint8_t *buf = nullptr;
    assert_int_equal(cj_image_read((dir + "/missing.png").c_str(), &w, &h, &buf), CJ_ERR_IO);
    assert_non_null(std::strstr(cj_last_error(), "missing.png"));
    assert_int_equal(w, -1);
    assert_null(buf);
    std::string text = dir + "/not_an_image.png";
    FILE *f = std::fopen(text.c_str(), "wb");
    std::fputs("this is not a PNG file\n", f);
    std::fclose(f);
    assert_int_equal(cj_image_read(text.c_str(), &w, &h, &buf), CJ_ERR_IO);
    assert_null(buf);
    remove_tree(dir);
    std::printf("test_image_io: bad sizes/strides refused, missing and non-image files reported\n");
}

// The raster/ plot and text headers (and what they include) compile and link from C++.
static void test_plot_headers_from_cxx(void **state) {
    (void)state;
    cj_plot *plot = nullptr;
    assert_int_equal(cj_plot_create(nullptr, &plot), CJ_OK);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    const double pts[6] = {0, 0, 1, 2, 2, 0};
    cj_bezier c = cj_bezier_view(2, 2, pts);
    assert_int_equal(cj_plot_add_bezier(plot, &c, &o), CJ_OK);
    cj_framebuffer *fb = nullptr;
    assert_int_equal(cj_framebuffer_create(64, 48, 0, nullptr, &fb), CJ_OK);
    assert_int_equal(cj_plot_render(plot, fb, 0, 0, 64, 48, nullptr), CJ_OK);
    cj_framebuffer_destroy(fb);
    cj_plot_destroy(plot);
    std::printf("test_image_io: plot.h/text.h/framebuffer.h used from C++\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip_random),
        cmocka_unit_test(test_file_is_top_row_first),
        cmocka_unit_test(test_failed_write_leaves_nothing),
        cmocka_unit_test(test_bad_arguments_and_reads),
        cmocka_unit_test(test_plot_headers_from_cxx),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
