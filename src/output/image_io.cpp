// EXR (OpenEXR) and PNG (libpng's simplified API) files. Both are encoded in memory and
// written with write_file_atomically(), so a failed write never leaves a partial file.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <png.h>

#include "hemirad/error.h"
#include "hemirad/image.h"
#include "output/atomic_file.h"

namespace hemirad {

namespace {

constexpr float kHalfMax = 65504.0f; ///< largest finite 16-bit float

void check_buffer(const std::string& path, int width, int height, std::size_t size) {
    if (width <= 0 || height <= 0)
        throw RuntimeError(path + ": cannot write an empty image (" + std::to_string(width) +
                           " x " + std::to_string(height) + ")");
    HEMIRAD_CHECK_EQ(size, std::size_t(width) * std::size_t(height) * 3);
}

/// Images larger than this many pixels are refused on reading (a corrupt header, most likely).
constexpr std::size_t kMaxPixels = std::size_t(1) << 28;

} // namespace

// --- OpenEXR ---------------------------------------------------------------------------------

void write_exr(const std::string& path, const ImageRGB& image, bool half) {
    check_buffer(path, image.width, image.height, image.pixels.size());
    // Half files get half slices (OpenEXR does not convert float slices to half channels).
    std::vector<Imath::half> halves;
    if (half) {
        halves.resize(image.pixels.size());
        for (std::size_t i = 0; i < halves.size(); ++i) {
            float v = image.pixels[i];
            if (std::isfinite(v)) v = std::clamp(v, -kHalfMax, kHalfMax); // not +-inf
            halves[i] = Imath::half(v);                                   // rounds to nearest
        }
    }

    std::string bytes;
    try {
        Imf::Header header(image.width, image.height); // display window = data window
        header.compression() = Imf::ZIP_COMPRESSION;
        const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
        const std::size_t size = half ? sizeof(Imath::half) : sizeof(float);
        char* base = half ? reinterpret_cast<char*>(halves.data())
                          : reinterpret_cast<char*>(const_cast<float*>(image.pixels.data()));
        const char* names[3] = {"R", "G", "B"};
        Imf::FrameBuffer frame;
        const std::size_t xstride = 3 * size, ystride = xstride * std::size_t(image.width);
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(names[c], Imf::Channel(type));
            frame.insert(names[c], Imf::Slice(type, base + c * size, xstride, ystride));
        }
        Imf::StdOSStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frame);
            file.writePixels(image.height);
        }
        bytes = stream.str();
    } catch (const std::exception& e) {
        throw RuntimeError(path + ": cannot encode OpenEXR: " + e.what());
    }
    write_file_atomically(path, bytes);
}

ImageRGB read_exr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const long long w = (long long)dw.max.x - dw.min.x + 1;
        const long long h = (long long)dw.max.y - dw.min.y + 1;
        if (w <= 0 || h <= 0 || std::size_t(w) * std::size_t(h) > kMaxPixels)
            throw RuntimeError(path + ": unsupported OpenEXR data window " + std::to_string(w) +
                               " x " + std::to_string(h));
        ImageRGB image{int(w), int(h)};
        const Imf::ChannelList& channels = file.header().channels();
        const bool rgb =
            channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
        const bool grey = !rgb && channels.findChannel("Y");
        const char* names[3] = {"R", "G", "B"};
        const int count = grey ? 1 : 3;
        Imf::FrameBuffer frame;
        for (int c = 0; c < count; ++c) {
            const char* name = grey ? "Y" : names[c];
            const Imf::Channel* channel = channels.findChannel(name);
            if (channel && (channel->xSampling != 1 || channel->ySampling != 1))
                throw RuntimeError(path + ": subsampled OpenEXR channel " + name +
                                   " is not supported");
            frame.insert(name, Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, dw,
                                                3 * sizeof(float), 3 * sizeof(float) * w));
        }
        file.setFrameBuffer(frame);
        file.readPixels(dw.min.y, dw.max.y);
        if (grey)
            for (std::size_t i = 0; i < image.pixels.size(); i += 3)
                image.pixels[i + 1] = image.pixels[i + 2] = image.pixels[i];
        return image;
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::exception& e) {
        throw RuntimeError(path + ": cannot read OpenEXR: " + e.what());
    }
}

// --- PNG -------------------------------------------------------------------------------------

void write_png(const std::string& path, const Image8& image) {
    check_buffer(path, image.width, image.height, image.rgb.size());
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    png.width = png_uint_32(image.width);
    png.height = png_uint_32(image.height);
    png.format = PNG_FORMAT_RGB; // 8-bit sRGB: libpng writes sRGB and gAMA, nothing timed
    std::string bytes(PNG_IMAGE_PNG_SIZE_MAX(png), '\0');
    png_alloc_size_t size = bytes.size();
    const bool ok =
        png_image_write_to_memory(&png, bytes.data(), &size, 0, image.rgb.data(), 0, nullptr);
    const std::string message = png.message;
    png_image_free(&png);
    if (!ok) throw RuntimeError(path + ": cannot encode PNG: " + message);
    bytes.resize(size);
    write_file_atomically(path, bytes);
}

Image8 read_png(const std::string& path) {
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str())) {
        const std::string message = png.message;
        png_image_free(&png);
        throw RuntimeError(path + ": cannot read PNG: " + message);
    }
    if (std::size_t(png.width) * png.height > kMaxPixels) {
        png_image_free(&png);
        throw RuntimeError(path + ": PNG too large (" + std::to_string(png.width) + " x " +
                           std::to_string(png.height) + ")");
    }
    png.format = PNG_FORMAT_RGB;
    // Zero-filled: an alpha channel is composited onto this (black) buffer.
    Image8 image{int(png.width), int(png.height)};
    if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
        const std::string message = png.message;
        png_image_free(&png);
        throw RuntimeError(path + ": cannot read PNG: " + message);
    }
    png_image_free(&png);
    return image;
}

} // namespace hemirad
