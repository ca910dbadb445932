// Image files (EXR, PNG), tone mapping and atomic writes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>

#include <unistd.h>

#include "core/colour.h"
#include "hemirad/error.h"
#include "hemirad/image.h"
#include "output/atomic_file.h"

namespace fs = std::filesystem;
using namespace hemirad;

namespace {

/// A fresh, empty directory for one test, removed at the end.
class TempDir {
  public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() /
                ("hemirad_image_io_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    const fs::path& path() const { return path_; }
    /// Names of the entries in the directory (to catch stray temporary files).
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename());
        std::sort(names.begin(), names.end());
        return names;
    }

  private:
    fs::path path_;
};

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

ImageRGB test_image(int w, int h) {
    ImageRGB image(w, h);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> exponent(-6.0f, 4.0f);
    for (float& v : image.pixels) v = std::pow(10.0f, exponent(rng));
    image.at(0, 0)[0] = 0.0f;
    image.at(1, 0)[1] = 1.0f;
    image.at(2, 0)[2] = 1234.5f;
    return image;
}

Image8 grey_ramp(const std::vector<float>& values, const ToneMap& tm, ImageRGB* out = nullptr) {
    ImageRGB image(int(values.size()), 1);
    for (std::size_t i = 0; i < values.size(); ++i)
        image.at(int(i), 0)[0] = image.at(int(i), 0)[1] = image.at(int(i), 0)[2] = values[i];
    if (out) *out = image;
    return tone_map(image, tm);
}

} // namespace

// --- EXR -------------------------------------------------------------------------------------

TEST(ImageExr, FloatRoundTripIsExact) {
    TempDir dir;
    const ImageRGB image = test_image(13, 7);
    write_exr(dir.file("a.exr"), image, /*half=*/false);
    const ImageRGB back = read_exr(dir.file("a.exr"));
    ASSERT_EQ(back.width, 13);
    ASSERT_EQ(back.height, 7);
    EXPECT_EQ(back.pixels, image.pixels);
    EXPECT_EQ(back.at(2, 0)[2], 1234.5f); // row 0 is the top row in both
}

TEST(ImageExr, HalfRoundTripIsWithinHalfPrecision) {
    TempDir dir;
    ImageRGB image = test_image(9, 11);
    image.at(3, 3)[0] = 1e6f; // beyond the largest half: clamped, not infinite
    image.at(3, 3)[1] = -1e6f;
    write_exr(dir.file("h.exr"), image); // half by default
    const ImageRGB back = read_exr(dir.file("h.exr"));
    ASSERT_EQ(back.width, 9);
    ASSERT_EQ(back.height, 11);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const float v = image.pixels[i], r = back.pixels[i];
        if (std::abs(v) > 65504.0f) {
            EXPECT_EQ(r, std::copysign(65504.0f, v)) << i;
        } else if (std::abs(v) >= 6.1035e-5f) { // normal halves: 11 significant bits
            EXPECT_NEAR(r, v, std::abs(v) * std::ldexp(1.0f, -11)) << i;
        } else { // subnormal halves: absolute spacing 2^-24
            EXPECT_NEAR(r, v, std::ldexp(1.0f, -25)) << i;
        }
    }
    // Half files are smaller than float ones.
    write_exr(dir.file("f.exr"), image, false);
    EXPECT_LT(fs::file_size(dir.file("h.exr")), fs::file_size(dir.file("f.exr")));
}

TEST(ImageExr, BytesAreDeterministic) {
    TempDir dir;
    const ImageRGB image = test_image(16, 16);
    write_exr(dir.file("1.exr"), image);
    write_exr(dir.file("2.exr"), image);
    EXPECT_EQ(read_bytes(dir.file("1.exr")), read_bytes(dir.file("2.exr")));
}

TEST(ImageExr, ReadingAMissingFileThrowsNamingIt) {
    TempDir dir;
    const std::string path = dir.file("missing.exr");
    try {
        read_exr(path);
        FAIL() << "no exception";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}

TEST(ImageExr, ReadingAPngAsExrThrows) {
    TempDir dir;
    write_png(dir.file("x.png"), Image8(4, 4));
    EXPECT_THROW(read_exr(dir.file("x.png")), RuntimeError);
}

// --- PNG -------------------------------------------------------------------------------------

TEST(ImagePng, RoundTripIsExact) {
    TempDir dir;
    Image8 image(17, 5);
    std::mt19937 rng(3);
    for (auto& b : image.rgb) b = std::uint8_t(rng() & 0xFF);
    write_png(dir.file("a.png"), image);
    const Image8 back = read_png(dir.file("a.png"));
    EXPECT_EQ(back.width, 17);
    EXPECT_EQ(back.height, 5);
    EXPECT_EQ(back.rgb, image.rgb);
}

TEST(ImagePng, BytesAreDeterministicWithoutTimeOrText) {
    TempDir dir;
    Image8 image(32, 8, {10, 200, 30});
    image.set(5, 5, {255, 0, 0});
    write_png(dir.file("1.png"), image);
    write_png(dir.file("2.png"), image);
    const std::string bytes = read_bytes(dir.file("1.png"));
    EXPECT_EQ(bytes, read_bytes(dir.file("2.png")));
    for (const char* chunk : {"tIME", "tEXt", "zTXt", "iTXt"})
        EXPECT_EQ(bytes.find(chunk), std::string::npos) << chunk;
    EXPECT_NE(bytes.find("sRGB"), std::string::npos);
}

TEST(ImagePng, ReadingGarbageThrowsNamingTheFile) {
    TempDir dir;
    const std::string path = dir.file("garbage.png");
    write_file_atomically(path, "not a png at all");
    try {
        read_png(path);
        FAIL() << "no exception";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}

// --- tone mapping ----------------------------------------------------------------------------

TEST(ImageToneMap, SrgbTransferFunction) {
    EXPECT_EQ(srgb_encode(0.0), 0.0);
    EXPECT_EQ(srgb_encode(1.0), 1.0);
    EXPECT_DOUBLE_EQ(srgb_encode(0.001), 0.01292);        // linear segment
    EXPECT_NEAR(srgb_encode(0.5), 0.735356983, 1e-8);     // power segment
    EXPECT_NEAR(srgb_encode(0.0031308), 0.0404500, 1e-6); // the two segments meet
    EXPECT_NEAR(srgb_encode(0.0031308 + 1e-12), 0.0404500, 1e-6);
    for (double v : {0.0, 0.002, 0.01, 0.2, 0.7, 1.0})
        EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-12) << v;
    EXPECT_EQ(srgb_encode(std::nan("")), 0.0);
    EXPECT_EQ(srgb_encode(-1.0), 0.0);
    EXPECT_EQ(srgb_encode(7.0), 1.0);
}

TEST(ImageToneMap, UnitExposureClampMapsZeroAndOneToBlackAndWhite) {
    ToneMap tm;
    tm.auto_exposure = false;
    tm.op = ToneMap::Clamp;
    const Image8 out = grey_ramp({0.0f, 1.0f, 0.5f, 2.0f, 0.001f}, tm);
    EXPECT_EQ(out.get(0, 0), (Rgb8{0, 0, 0}));
    EXPECT_EQ(out.get(1, 0), (Rgb8{255, 255, 255}));
    EXPECT_EQ(out.get(2, 0).r, 188); // 255 * 0.73536 = 187.5
    EXPECT_EQ(out.get(3, 0).r, 255);
    EXPECT_EQ(out.get(4, 0).r, 3); // 255 * 0.01292 = 3.29
}

TEST(ImageToneMap, ExposureIsInStops) {
    ToneMap tm;
    tm.auto_exposure = false;
    tm.op = ToneMap::Clamp;
    tm.exposure = 1.0;
    const Image8 up = grey_ramp({0.25f}, tm);
    tm.exposure = 0.0;
    const Image8 same = grey_ramp({0.5f}, tm);
    EXPECT_EQ(up.rgb, same.rgb);
    tm.exposure = std::nan("");
    EXPECT_THROW(grey_ramp({0.5f}, tm), InputError);
}

TEST(ImageToneMap, EveryOperatorIsMonotoneAndStartsAtBlack) {
    std::vector<float> ramp;
    for (int i = 0; i <= 2000; ++i) ramp.push_back(float(std::pow(10.0, -4.0 + i * 0.003)));
    ramp.insert(ramp.begin(), 0.0f);
    ramp.push_back(1e6f); // far above any exposure reference: white
    for (auto op : {ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Aces})
        for (bool autoexp : {false, true}) {
            ToneMap tm;
            tm.op = op;
            tm.auto_exposure = autoexp;
            const Image8 out = grey_ramp(ramp, tm);
            EXPECT_EQ(out.get(0, 0), (Rgb8{0, 0, 0})) << op;
            for (int x = 1; x < out.width; ++x) {
                ASSERT_GE(out.get(x, 0).r, out.get(x - 1, 0).r) << "op " << op << " x " << x;
                ASSERT_EQ(out.get(x, 0).r, out.get(x, 0).g);
            }
            EXPECT_EQ(out.get(out.width - 1, 0).r, 255) << op;
        }
}

TEST(ImageToneMap, ReinhardWhitePointAndSpecialValues) {
    ToneMap tm;
    tm.auto_exposure = false; // default operator: Reinhard
    const float inf = std::numeric_limits<float>::infinity();
    const Image8 out = grey_ramp({float(kReinhardWhite), 1.0f, std::nanf(""), -3.0f, inf}, tm);
    EXPECT_EQ(out.get(0, 0).r, 255);
    EXPECT_EQ(out.get(1, 0).r, int(srgb_encode(1.0 * (1 + 1 / 16.0) / 2.0) * 255 + 0.5));
    EXPECT_EQ(out.get(2, 0), (Rgb8{0, 0, 0}));
    EXPECT_EQ(out.get(3, 0), (Rgb8{0, 0, 0}));
    EXPECT_EQ(out.get(4, 0), (Rgb8{255, 255, 255}));
}

TEST(ImageToneMap, ReinhardKeepsHue) {
    ToneMap tm;
    tm.auto_exposure = false;
    ImageRGB image(1, 1);
    image.at(0, 0)[0] = 0.8f;
    image.at(0, 0)[1] = 0.4f;
    image.at(0, 0)[2] = 0.2f;
    const Rgb8 c = tone_map(image, tm).get(0, 0);
    const double r = srgb_decode(c.r / 255.0), g = srgb_decode(c.g / 255.0),
                 b = srgb_decode(c.b / 255.0);
    EXPECT_NEAR(r / g, 2.0, 0.05);
    EXPECT_NEAR(g / b, 2.0, 0.1);
}

TEST(ImageToneMap, AutoExposureIgnoresBlackBackgroundAndSmallBrightLights) {
    // 1000 pixels: 500 black background, 480 lit at luminance 0.25, 20 lights at 1000
    // (4% of the lit pixels, under the 5% that the 95th percentile tolerates).
    ImageRGB image(1000, 1);
    for (int x = 0; x < 1000; ++x) {
        const float v = x < 500 ? 0.0f : x < 980 ? 0.25f : 1000.0f;
        image.at(x, 0)[0] = image.at(x, 0)[1] = image.at(x, 0)[2] = v;
    }
    EXPECT_DOUBLE_EQ(auto_exposure_scale(image), 4.0);
    image.at(0, 0)[0] = std::nanf(""); // non-finite and negative pixels do not count
    image.at(1, 0)[1] = -std::numeric_limits<float>::infinity();
    EXPECT_DOUBLE_EQ(auto_exposure_scale(image), 4.0);
    EXPECT_EQ(auto_exposure_scale(ImageRGB(4, 4)), 1.0); // all black
    EXPECT_EQ(auto_exposure_scale(ImageRGB()), 1.0);     // empty
    // And the picture is invariant to the overall scale of the input.
    ToneMap tm;
    ImageRGB brighter = image;
    for (float& v : brighter.pixels) v *= 64.0f;
    EXPECT_EQ(tone_map(image, tm).rgb, tone_map(brighter, tm).rgb);
}

// --- atomic writes ---------------------------------------------------------------------------

TEST(ImageAtomicWrite, WritingIntoAMissingDirectoryThrowsNamingThePath) {
    TempDir dir;
    const std::string path = dir.file("no/such/dir/out.png");
    try {
        write_png(path, Image8(2, 2));
        FAIL() << "no exception";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageAtomicWrite, WritingIntoAnUnwritableDirectoryThrowsAndLeavesNothing) {
    TempDir dir;
    const fs::path locked = dir.path() / "locked";
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    // Root may write anywhere but in /proc, which stands in for an unwritable directory.
    const bool root = ::access(locked.c_str(), W_OK) == 0;
    const std::string path =
        root ? "/proc/hemirad-image-io-test.exr" : (locked / "out.exr").string();
    try {
        write_exr(path, ImageRGB(2, 2));
        FAIL() << "no exception";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    fs::permissions(locked, fs::perms::owner_all);
    EXPECT_TRUE(fs::is_empty(locked));
    EXPECT_FALSE(fs::exists(path));
}

TEST(ImageAtomicWrite, FailedRenameRemovesTheTemporaryFile) {
    // The target is a directory: the temporary file is written, the rename fails.
    TempDir dir;
    const std::string path = dir.file("target");
    fs::create_directory(path);
    try {
        write_png(path, Image8(3, 3));
        FAIL() << "no exception";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"target"});
    EXPECT_TRUE(fs::is_directory(path));
}

TEST(ImageAtomicWrite, UncommittedFileLeavesNothingAndKeepsTheOldFile) {
    TempDir dir;
    const std::string path = dir.file("data.csv");
    {
        AtomicFile file(path);
        EXPECT_TRUE(fs::exists(file.temp_path()));
        EXPECT_EQ(file.temp_path().rfind(path + ".tmp-", 0), 0u) << file.temp_path();
        file.write("partial,");
        std::fputs("more", file.stream());
    }
    EXPECT_TRUE(dir.entries().empty());

    write_file_atomically(path, "old\n");
    {
        AtomicFile file(path);
        file.write("new but never committed\n");
    }
    EXPECT_EQ(read_bytes(path), "old\n");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"data.csv"});
}

TEST(ImageAtomicWrite, CommitReplacesTheFileWhole) {
    TempDir dir;
    const std::string path = dir.file("report.json");
    write_file_atomically(path, "{\"a\": 1}\n");
    AtomicFile file(path);
    file.write("{\"a\": ");
    std::fprintf(file.stream(), "%d}\n", 2);
    EXPECT_EQ(read_bytes(path), "{\"a\": 1}\n"); // not visible before commit
    file.commit();
    EXPECT_TRUE(file.committed());
    EXPECT_EQ(read_bytes(path), "{\"a\": 2}\n");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"report.json"});
}

TEST(ImageAtomicWrite, MovedFromFileDoesNothing) {
    TempDir dir;
    const std::string path = dir.file("moved.txt");
    AtomicFile a(path);
    a.write("abc");
    AtomicFile b(std::move(a));
    b.write("def");
    b.commit();
    EXPECT_EQ(read_bytes(path), "abcdef");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"moved.txt"});
}

TEST(ImageAtomicWrite, EmptyImagesAreRefusedBeforeAnyFileIsMade) {
    TempDir dir;
    EXPECT_THROW(write_png(dir.file("e.png"), Image8()), RuntimeError);
    EXPECT_THROW(write_exr(dir.file("e.exr"), ImageRGB()), RuntimeError);
    EXPECT_TRUE(dir.entries().empty());
}
