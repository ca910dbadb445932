#include "overlay.h"

#include <algorithm>

#include "hemirad/draw.h"

namespace hemirad::view {

void Overlay::blit(const Image8& panel, int x, int y, int fb_width, int fb_height) {
    if (panel.empty() || fb_width <= 0 || fb_height <= 0) return;
    if (panel.width > width_ || panel.height > height_) {
        width_ = std::max(panel.width, width_);
        height_ = std::max(panel.height, height_);
        texture_ = gl::Texture::create(GL_TEXTURE_2D);
        texture_.storage_2d(1, GL_RGBA8, width_, height_);
        framebuffer_ = gl::Framebuffer::create();
        framebuffer_.attach(GL_COLOR_ATTACHMENT0, texture_);
        framebuffer_.check_complete();
    }
    GLint alignment = 4;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(texture_.id(), 0, 0, 0, panel.width, panel.height, GL_RGB, GL_UNSIGNED_BYTE,
                        panel.rgb.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    // Texture row 0 is the panel's top row: blit it to the top edge (GL's y runs up).
    const int top = fb_height - y;
    glBlitNamedFramebuffer(framebuffer_.id(), 0, 0, 0, panel.width, panel.height, x, top,
                           x + panel.width, top - panel.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void SceneTarget::bind(int width, int height) {
    if (!framebuffer_ || width != width_ || height != height_) {
        colour_ = gl::Texture::create(GL_TEXTURE_2D);
        colour_.storage_2d(1, GL_RGBA8, width, height);
        depth_ = gl::Renderbuffer::create();
        depth_.storage(GL_DEPTH_COMPONENT32F, width, height);
        framebuffer_ = gl::Framebuffer::create();
        framebuffer_.attach(GL_COLOR_ATTACHMENT0, colour_);
        framebuffer_.attach(GL_DEPTH_ATTACHMENT, depth_);
        framebuffer_.check_complete();
        width_ = width;
        height_ = height;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, width, height);
}

void SceneTarget::present() {
    glBlitNamedFramebuffer(framebuffer_.id(), 0, 0, 0, width_, height_, 0, 0, width_, height_,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Image8 text_panel(const std::string& text, int scale, int pad) {
    Image8 img(text_width(text, scale) + 2 * pad, text_height(text, scale) + 2 * pad, {24, 24, 28});
    draw_text(img, pad, pad, text, {235, 235, 235}, scale);
    return img;
}

} // namespace hemirad::view
