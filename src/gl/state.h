// The one GL-state policy of the library: whoever changes GL state restores it. A renderer
// (the solution renderer, the hemicube) holds a StateGuard for as long as it draws; the guard
// saves, on construction, every piece of state either of them changes, and puts it back on
// destruction. So the library leaves a context as it found it, whether the context is its own
// or the caller's (a viewer's window: GpuProviderOptions::use_current_context), and no drawing
// code depends on what another one left behind: each sets what it needs (Dear ImGui's GL
// backends follow the same rule).
#pragma once

#include <glad/gl.h>

namespace hemirad::gl {

class StateGuard {
  public:
    StateGuard() {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fb_);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fb_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
        glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_);
        glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_);
        glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
        glGetIntegerv(GL_FRONT_FACE, &front_face_);
        glGetIntegerv(GL_CULL_FACE_MODE, &cull_face_mode_);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
        glGetIntegerv(GL_BLEND_SRC_RGB, &blend_func_[0]);
        glGetIntegerv(GL_BLEND_DST_RGB, &blend_func_[1]);
        glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_func_[2]);
        glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_func_[3]);
        depth_test_ = glIsEnabled(GL_DEPTH_TEST);
        cull_ = glIsEnabled(GL_CULL_FACE);
        blend_ = glIsEnabled(GL_BLEND);
        scissor_ = glIsEnabled(GL_SCISSOR_TEST);
        glGetIntegerv(GL_SCISSOR_BOX, scissor_box_);
    }
    ~StateGuard() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_fb_));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_fb_));
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
        glUseProgram(GLuint(program_));
        glBindVertexArray(GLuint(vao_));
        glClipControl(GLenum(clip_origin_), GLenum(clip_depth_));
        glDepthFunc(GLenum(depth_func_));
        glFrontFace(GLenum(front_face_));
        glCullFace(GLenum(cull_face_mode_));
        glDepthMask(depth_mask_);
        glBlendFuncSeparate(GLenum(blend_func_[0]), GLenum(blend_func_[1]), GLenum(blend_func_[2]),
                            GLenum(blend_func_[3]));
        set(GL_DEPTH_TEST, depth_test_);
        set(GL_CULL_FACE, cull_);
        set(GL_BLEND, blend_);
        set(GL_SCISSOR_TEST, scissor_);
        glScissor(scissor_box_[0], scissor_box_[1], scissor_box_[2], scissor_box_[3]);
    }
    StateGuard(const StateGuard&) = delete;
    StateGuard& operator=(const StateGuard&) = delete;

  private:
    static void set(GLenum cap, GLboolean on) { on ? glEnable(cap) : glDisable(cap); }

    GLint draw_fb_ = 0, read_fb_ = 0, viewport_[4] = {}, scissor_box_[4] = {}, program_ = 0,
          vao_ = 0;
    GLint clip_origin_ = GL_LOWER_LEFT, clip_depth_ = GL_NEGATIVE_ONE_TO_ONE;
    GLint depth_func_ = GL_LESS, front_face_ = GL_CCW, cull_face_mode_ = GL_BACK;
    GLint blend_func_[4] = {GL_ONE, GL_ZERO, GL_ONE, GL_ZERO}; ///< src/dst RGB, src/dst alpha
    GLboolean depth_mask_ = GL_TRUE, depth_test_ = GL_FALSE, cull_ = GL_FALSE, blend_ = GL_FALSE,
              scissor_ = GL_FALSE;
};

} // namespace hemirad::gl
