// Reflectance textures (OBJ map_Kd, glTF baseColorTexture): decoded to linear reflectance with
// a box-filtered mipmap, for per-leaf averages (the solver) and per-pixel detail (rendered
// views, lightmaps).
//
// Texels are linear reflectance per RGB channel in [0, 1]: 8- and 16-bit images are sRGB
// encoded (as both formats specify for colour maps) and are decoded with the sRGB transfer
// function, never averaged in encoded space. Row 0 is the top of the image; texture
// coordinates (s, t) follow glTF: (0, 0) the top-left corner, t downwards (the OBJ loader
// flips vt's v). Lookups wrap (repeat), as OBJ and glTF's default sampler do.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hemirad/visibility.h"

namespace hemirad {

struct HEMIRAD_API Texture {
    struct Level {
        int width = 0, height = 0;
        std::vector<glm::vec3> texels; ///< row-major, row 0 the top; linear reflectance
    };
    std::string name;          ///< the file it came from (or "FILE: image N"), for messages
    std::vector<Level> levels; ///< levels[0] the image; each next level halves each side
                               ///< (at least 1), texel = mean of the 2x2 texels under it
    glm::vec3 max{0.f};        ///< per channel, the largest texel of level 0

    int width() const { return levels.empty() ? 0 : levels[0].width; }
    int height() const { return levels.empty() ? 0 : levels[0].height; }
    /// Texel (x, y) of `level`, both wrapped into range (repeat).
    glm::vec3 texel(int level, long x, long y) const;
    /// The texel of `level` that contains (s, t) (nearest, repeat).
    glm::vec3 fetch(int level, glm::dvec2 st) const;
    /// The level whose texels are about `side` texels of level 0 wide (floor of log2, clamped).
    int level_for(double side) const;
    /// The mean over the whole image (the last level, 1 x 1 for a power-of-two square).
    glm::dvec3 mean() const;
};

/// A texture from linear texels (row 0 the top), with its mipmap. width, height >= 1 and
/// texels.size() == width * height (checked).
HEMIRAD_API Texture make_texture(const std::string& name, int width, int height,
                                 std::vector<glm::vec3> linear);

/// Decodes a PNG or JPEG (anything stb_image reads: also BMP, TGA, GIF, PSD, HDR, PNM) held in
/// memory, sRGB to linear (HDR images are linear already). Throws InputError naming `name` and
/// stb_image's reason when it cannot be decoded, or when it has more than 4096 x 4096 texels
/// (12 bytes a texel, a third more for the mipmap, in memory and again on the GPU: about 270 MB
/// each at that size).
HEMIRAD_API Texture decode_texture(const std::string& name, const unsigned char* bytes,
                                   std::size_t size);
/// Reads and decodes a file (as decode_texture). Throws InputError naming the file.
HEMIRAD_API Texture load_texture(const std::string& path);

} // namespace hemirad
