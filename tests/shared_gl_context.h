// A test fixture whose tests share one GL context for the whole suite: shader programs
// compile once (code generation at the first draw costs ~100 ms per program on llvmpipe).
// A test fails, naming why, when no context could be created.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <memory>
#include <string>

#include "hemirad/gl/context.h"

class SharedGlContextTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        try {
            context_ = hemirad::gl::Context::create();
        } catch (const std::exception& e) {
            error_ = e.what();
        }
    }
    static void TearDownTestSuite() { context_.reset(); }
    void SetUp() override {
        ASSERT_TRUE(context_) << "no GL context: " << error_;
        context_->make_current();
    }

  private:
    inline static std::unique_ptr<hemirad::gl::Context> context_;
    inline static std::string error_;
};
