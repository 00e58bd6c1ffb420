#pragma once
// Every GL test runs in one headless debug context per test binary and fails on any GL
// message of type error, whatever the test itself checks.
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "gl/debug_output.hpp"
#include "gl/headless_context.hpp"

namespace iblab::testing {

class GlTest : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        if (!context_) {
            context_ = std::make_unique<gl::HeadlessContext>(gl::HeadlessContextOptions{.debug = true});
            ASSERT_TRUE(gl::currentContextHasDebugOutput()) << "the headless context has no KHR_debug output";
            debug_ = std::make_unique<gl::DebugOutput>();
            debug_->install();
        }
    }
    void SetUp() override { debug_->clear(); }
    void TearDown() override
    {
        std::string all;
        for (const auto& m : debug_->messages())
            if (m.isError) all += m.text + "\n";
        EXPECT_EQ(debug_->errorCount(), 0) << "GL errors during the test:\n" << all;
    }

    static std::string shaderDirectory() { return IBLAB_SHADER_DIR; }
    static gl::DebugOutput& debugOutput() { return *debug_; }

private:
    static inline std::unique_ptr<gl::HeadlessContext> context_;
    static inline std::unique_ptr<gl::DebugOutput> debug_;
};

} // namespace iblab::testing
