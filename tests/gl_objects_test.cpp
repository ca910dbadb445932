// The GL object wrappers' contract, checked without a context (after Magnum's
// GL/Test/BufferTest.cpp): move-only, noexcept moves, empty when default-constructed.
#include <type_traits>

#include <gtest/gtest.h>

#include "gl/objects.h"

namespace hemirad::gl {
namespace {

template <class T> class GlObjectTest : public ::testing::Test {};

using Wrappers =
    ::testing::Types<Buffer, Texture, Framebuffer, Renderbuffer, VertexArray, Shader, Program>;
TYPED_TEST_SUITE(GlObjectTest, Wrappers);

TYPED_TEST(GlObjectTest, IsMoveOnly) {
    EXPECT_FALSE(std::is_copy_constructible_v<TypeParam>);
    EXPECT_FALSE(std::is_copy_assignable_v<TypeParam>);
    EXPECT_TRUE(std::is_nothrow_move_constructible_v<TypeParam>);
    EXPECT_TRUE(std::is_nothrow_move_assignable_v<TypeParam>);
    EXPECT_TRUE(std::is_nothrow_default_constructible_v<TypeParam>);
}

TYPED_TEST(GlObjectTest, DefaultConstructedIsEmpty) {
    // Creates and deletes nothing: no GL call may be made here, there is no context.
    TypeParam object;
    EXPECT_EQ(object.id(), 0u);
    EXPECT_FALSE(object);
    TypeParam moved = std::move(object);
    EXPECT_EQ(moved.id(), 0u);
    moved = TypeParam();
    EXPECT_EQ(moved.id(), 0u);
}

} // namespace
} // namespace hemirad::gl
