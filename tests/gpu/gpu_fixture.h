#pragma once
// GPU test fixture: one Vulkan context per test process with the Khronos validation layer on;
// any validation error during a test fails it. Test shaders (tests/shaders) are registered.
#include <gtest/gtest.h>

#include <memory>
#include <span>

#include "gpu/context.h"
#include "gpu/shader_library.h"

namespace amrvk::shaders {
std::span<const gpu::EmbeddedShader> testShaders();
std::span<const gpu::EmbeddedShader> passShaders();
}  // namespace amrvk::shaders

namespace amrvk::test {

class GpuTest : public ::testing::Test {
protected:
    static gpu::Context& ctx() {
        static std::unique_ptr<gpu::Context> context = [] {
            gpu::ContextOptions o;
            o.validation = true;
            auto c = std::make_unique<gpu::Context>(o);
            gpu::registerShaders(shaders::testShaders());
            gpu::registerShaders(shaders::passShaders());
            return c;
        }();
        return *context;
    }
    void SetUp() override { mErrorsBefore = ctx().validationErrors(); }
    void TearDown() override {
        EXPECT_EQ(ctx().validationErrors(), mErrorsBefore)
            << "Vulkan validation errors; last: " << ctx().lastValidationMessage();
    }

private:
    uint64_t mErrorsBefore = 0;
};

}  // namespace amrvk::test
