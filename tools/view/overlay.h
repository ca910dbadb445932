// On-screen text and legends for the viewer: panels drawn on the CPU into an Image8 (with the
// bitmap font of hemirad/draw.h), uploaded to a texture and blitted into the default
// framebuffer. A blit needs no shader and leaves no GL state changed; panels are opaque.
#pragma once

#include <string>

#include "gl/objects.h"
#include "hemirad/image.h"

namespace hemirad::view {

class Overlay {
  public:
    /// Copies `panel` into the default framebuffer (fb_width x fb_height pixels) with its
    /// top-left corner at (x, y), y counted down from the top. Clips to the framebuffer.
    void blit(const Image8& panel, int x, int y, int fb_width, int fb_height);

  private:
    gl::Texture texture_;
    gl::Framebuffer framebuffer_;
    int width_ = 0, height_ = 0; ///< texture size; grown as needed
};

/// An 8-bit colour + 32-bit float depth framebuffer the size of the window, for
/// SolutionRenderer::draw(): the renderer's reversed-Z depth needs float depth, and a window's
/// default framebuffer has 24-bit fixed-point depth at best (with it the Cornell box's light,
/// 0.8 mm under the ceiling, z-fights). Drawn into, then copied to the window with a blit.
class SceneTarget {
  public:
    /// Binds it as the draw framebuffer with a viewport of width x height, (re)allocating it
    /// when the size changes.
    void bind(int width, int height);
    /// Copies its colour into the window's default framebuffer (same size) and binds that.
    void present();

  private:
    gl::Texture colour_;
    gl::Renderbuffer depth_;
    gl::Framebuffer framebuffer_;
    int width_ = 0, height_ = 0;
};

/// A panel of text lines on a dark background, `pad` pixels of margin, font scale `scale`.
Image8 text_panel(const std::string& text, int scale = 1, int pad = 4);

} // namespace hemirad::view
