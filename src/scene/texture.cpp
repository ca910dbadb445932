// Reflectance textures: decoding (stb_image, Debian's libstb), sRGB to linear, box mipmap.
#include "hemirad/texture.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>

#include <stb_image.h>

#include "core/colour.h"
#include "hemirad/error.h"

namespace hemirad {

namespace {
/// Most texels of an image read (texture.h, decode_texture).
constexpr long long kMaxTexels = 4096LL * 4096LL;
} // namespace

glm::vec3 Texture::texel(int level, long x, long y) const {
    const Level& l = levels[std::size_t(level)];
    x %= l.width;
    y %= l.height;
    if (x < 0) x += l.width;
    if (y < 0) y += l.height;
    return l.texels[std::size_t(y) * std::size_t(l.width) + std::size_t(x)];
}

glm::vec3 Texture::fetch(int level, glm::dvec2 st) const {
    const Level& l = levels[std::size_t(level)];
    // floor of a huge or non-finite coordinate: wrap first, in double.
    double s = st.x - std::floor(st.x), t = st.y - std::floor(st.y);
    if (!std::isfinite(s)) s = 0;
    if (!std::isfinite(t)) t = 0;
    return texel(level, long(s * l.width), long(t * l.height));
}

int Texture::level_for(double side) const {
    if (!(side > 1)) return 0;
    const int level = int(std::floor(std::log2(side)));
    return std::clamp(level, 0, int(levels.size()) - 1);
}

glm::dvec3 Texture::mean() const {
    const Level& l = levels.back();
    glm::dvec3 sum(0.0);
    for (const glm::vec3& t : l.texels) sum += glm::dvec3(t);
    return sum / double(l.texels.size());
}

Texture make_texture(const std::string& name, int width, int height,
                     std::vector<glm::vec3> linear) {
    HEMIRAD_CHECK(width >= 1 && height >= 1);
    HEMIRAD_CHECK_EQ(linear.size(), std::size_t(width) * std::size_t(height));
    Texture t;
    t.name = name;
    for (glm::vec3& c : linear) {
        for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) ? std::clamp(c[k], 0.f, 1.f) : 0.f;
        t.max = glm::max(t.max, c);
    }
    t.levels.push_back({width, height, std::move(linear)});
    // Box filter: each texel of the next level is the mean of the 2 x 2 texels it covers (an
    // odd last row or column is folded into the one before: its texels count in two means).
    while (t.levels.back().width > 1 || t.levels.back().height > 1) {
        const Texture::Level& a = t.levels.back();
        Texture::Level b;
        b.width = std::max(1, a.width / 2);
        b.height = std::max(1, a.height / 2);
        b.texels.resize(std::size_t(b.width) * std::size_t(b.height));
        for (int y = 0; y < b.height; ++y)
            for (int x = 0; x < b.width; ++x) {
                const int x0 = std::min(2 * x, a.width - 1), x1 = std::min(2 * x + 1, a.width - 1);
                const int y0 = std::min(2 * y, a.height - 1),
                          y1 = std::min(2 * y + 1, a.height - 1);
                const auto at = [&](int i, int j) {
                    return a.texels[std::size_t(j) * std::size_t(a.width) + std::size_t(i)];
                };
                b.texels[std::size_t(y) * std::size_t(b.width) + std::size_t(x)] =
                    0.25f * (at(x0, y0) + at(x1, y0) + at(x0, y1) + at(x1, y1));
            }
        t.levels.push_back(std::move(b));
    }
    return t;
}

Texture decode_texture(const std::string& name, const unsigned char* bytes, std::size_t size) {
    if (size == 0) throw InputError(name, 0, "empty image file");
    if (size > std::size_t(1) << 30) throw InputError(name, 0, "image file larger than 1 GiB");
    const int len = int(size);
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, len, &w, &h, &comp))
        throw InputError(name, 0,
                         std::string("cannot decode the image (") + stbi_failure_reason() + ")");
    if (w < 1 || h < 1 || (long long)w * h > kMaxTexels)
        throw InputError(name, 0,
                         "image of " + std::to_string(w) + " x " + std::to_string(h) +
                             " texels is too large (at most " + std::to_string(kMaxTexels) +
                             " texels)");
    std::vector<glm::vec3> texels(std::size_t(w) * std::size_t(h));
    const auto fail = [&] {
        return InputError(name, 0,
                          std::string("cannot decode the image (") + stbi_failure_reason() + ")");
    };
    if (stbi_is_hdr_from_memory(bytes, len)) {
        std::unique_ptr<float, void (*)(void*)> data(
            stbi_loadf_from_memory(bytes, len, &w, &h, &comp, 3), stbi_image_free);
        if (!data) throw fail();
        for (std::size_t i = 0; i < texels.size(); ++i)
            texels[i] = glm::vec3(data.get()[3 * i], data.get()[3 * i + 1], data.get()[3 * i + 2]);
    } else if (stbi_is_16_bit_from_memory(bytes, len)) {
        std::unique_ptr<stbi_us, void (*)(void*)> data(
            stbi_load_16_from_memory(bytes, len, &w, &h, &comp, 3), stbi_image_free);
        if (!data) throw fail();
        for (std::size_t i = 0; i < texels.size(); ++i)
            for (int k = 0; k < 3; ++k)
                texels[i][k] = float(srgb_decode(data.get()[3 * i + std::size_t(k)] / 65535.0));
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> data(
            stbi_load_from_memory(bytes, len, &w, &h, &comp, 3), stbi_image_free);
        if (!data) throw fail();
        float table[256];
        for (int v = 0; v < 256; ++v) table[v] = float(srgb_decode(v / 255.0));
        for (std::size_t i = 0; i < texels.size(); ++i)
            for (int k = 0; k < 3; ++k) texels[i][k] = table[data.get()[3 * i + std::size_t(k)]];
    }
    return make_texture(name, w, h, std::move(texels));
}

Texture load_texture(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open the texture");
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                           std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(path, 0, "cannot read the texture");
    return decode_texture(path, bytes.data(), bytes.size());
}

} // namespace hemirad
