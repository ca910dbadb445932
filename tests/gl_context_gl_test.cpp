// The headless context on each backend: it must be created (a failure fails, never skips:
// Mesa llvmpipe is always there), give GL >= 4.5 core, render a known triangle exactly into
// a float framebuffer, and name the shader file in compile errors.
// One context at a time in this process: each test creates its own and destroys it.
#include <array>
#include <cstddef>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/objects.h"
#include "gl/program.h"
#include "hemirad/error.h"
#include "hemirad/gl/context.h"

namespace hemirad::gl {

// For gtest's messages, instead of the parameter's bytes.
void PrintTo(Backend backend, std::ostream* out) {
    *out << (backend == Backend::Egl ? "egl" : backend == Backend::OSMesa ? "osmesa" : "auto");
}

namespace {

class ContextTest : public ::testing::TestWithParam<Backend> {
  protected:
    void SetUp() override {
        ContextOptions options;
        options.backend = GetParam();
        ASSERT_NO_THROW(context_ = Context::create(options));
        ASSERT_TRUE(context_);
    }

    std::unique_ptr<Context> context_;
};

TEST_P(ContextTest, IsCore45WithARenderer) {
    EXPECT_EQ(context_->backend_name(), GetParam() == Backend::Egl ? "egl" : "osmesa");
    EXPECT_GE(context_->major_version() * 10 + context_->minor_version(), 45)
        << context_->version();
    EXPECT_FALSE(context_->renderer().empty());
    EXPECT_FALSE(context_->vendor().empty());
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    context_->make_current();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// A triangle whose vertical edge lies on x = 0 and whose other edges pass outside the
// viewport covers exactly the left half: columns 0..31 of 64, pixel centres never on an edge.
TEST_P(ContextTest, RendersKnownTriangleExactly) {
    constexpr int kSize = 64;
    constexpr std::array<float, 4> kColor = {0.25f, 0.5f, 1.0f, 0.75f};
    constexpr std::array<float, 4> kClear = {0.125f, 0.0f, 0.0625f, 1.0f};
    struct Vertex {
        float x, y;
        std::array<float, 4> color;
    };
    const Vertex vertices[] = {{0, -1, kColor}, {0, 3, kColor}, {-4, -1, kColor}};

    Texture color = Texture::create(GL_TEXTURE_2D);
    color.storage_2d(1, GL_RGBA32F, kSize, kSize);
    Renderbuffer depth = Renderbuffer::create();
    depth.storage(GL_DEPTH_COMPONENT24, kSize, kSize);
    Framebuffer fbo = Framebuffer::create();
    fbo.attach(GL_COLOR_ATTACHMENT0, color);
    fbo.attach(GL_DEPTH_ATTACHMENT, depth);
    ASSERT_NO_THROW(fbo.check_complete());

    Buffer buffer = Buffer::create();
    buffer.storage(sizeof vertices, vertices);
    VertexArray vao = VertexArray::create();
    vao.vertex_buffer(0, buffer, 0, sizeof(Vertex));
    vao.attribute(0, 0, 2, GL_FLOAT, offsetof(Vertex, x));
    vao.attribute(1, 0, 4, GL_FLOAT, offsetof(Vertex, color));
    Program program = link_program({"smoke.vert", "smoke.frag"});

    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, kSize, kSize);
    glEnable(GL_DEPTH_TEST);
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, kClear.data());
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
    glUseProgram(program.id());
    glBindVertexArray(vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);

    std::vector<float> pixels(kSize * kSize * 4, -1.0f);
    glNamedFramebufferReadBuffer(fbo.id(), GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_FLOAT, pixels.data());
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
    ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

    int wrong = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const std::array<float, 4>& want = x < kSize / 2 ? kColor : kClear;
            const float* got = &pixels[(y * kSize + x) * 4];
            for (int c = 0; c < 4; ++c)
                if (got[c] != want[c] && ++wrong <= 8)
                    ADD_FAILURE() << "pixel (" << x << ", " << y << ") channel " << c << ": "
                                  << got[c] << ", want " << want[c];
        }
    EXPECT_EQ(wrong, 0);
}

TEST_P(ContextTest, CompileErrorNamesTheShaderFile) {
    // shaders/broken_for_test.frag is broken on purpose, for this test.
    try {
        link_program({"smoke.vert", "broken_for_test.frag"});
        FAIL() << "a shader with a syntax error compiled";
    } catch (const RuntimeError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("broken_for_test.frag"), std::string::npos) << message;
        EXPECT_NE(message.find("error"), std::string::npos) << message;
    }
}

TEST_P(ContextTest, UnknownShaderFileIsNamed) {
    try {
        link_program({"no_such_shader.vert"});
        FAIL() << "an unknown shader file was accepted";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("no_such_shader.vert"), std::string::npos) << e.what();
    }
}

std::string backend_test_name(const ::testing::TestParamInfo<Backend>& info) {
    return info.param == Backend::Egl ? "Egl" : "OSMesa";
}

INSTANTIATE_TEST_SUITE_P(Backends, ContextTest, ::testing::Values(Backend::Egl, Backend::OSMesa),
                         backend_test_name);

TEST(ContextAuto, PrefersEgl) {
    std::unique_ptr<Context> context;
    ASSERT_NO_THROW(context = Context::create());
    EXPECT_EQ(context->backend_name(), "egl");
}

TEST(ContextEglDevices, NonEmptyOnMesa) {
    const std::vector<std::string> devices = Context::egl_devices();
    ASSERT_FALSE(devices.empty());
    for (const std::string& name : devices) EXPECT_FALSE(name.empty());
}

TEST(ParseBackend, NamesAndErrors) {
    EXPECT_EQ(parse_backend("auto"), Backend::Auto);
    EXPECT_EQ(parse_backend("egl"), Backend::Egl);
    EXPECT_EQ(parse_backend("osmesa"), Backend::OSMesa);
    try {
        parse_backend("vulkan");
        FAIL() << "parse_backend accepted 'vulkan'";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("vulkan"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace hemirad::gl
