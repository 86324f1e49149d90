// Screenshots (the accumulated linear image, with the legend in PNGs) and window captures (UI included).

#include <cstdio>

#include "core/image_io.h"
#include "core/strings.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/render_output.h"
#include "session/legend_image.h"
#include "viewer/panels.h"
#include "viewer/viewer_app_impl.h"

namespace amrvk::viewer {

// The presented image (UI included) into a host buffer: present layout -> copy -> present layout.
void ViewerApp::recordCapture(VkCommandBuffer cmd, VkImage image, VkExtent2D e) {
    const uint64_t bytes = uint64_t(e.width) * e.height * 4;
    if (!mCaptureBuffer.valid() || mCaptureBuffer.size() < bytes)
        mCaptureBuffer = gpu::Buffer(*mCtx, bytes, gpu::MemoryKind::HostRead, "windowCapture");
    const gpu::ImageUse present{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                VK_IMAGE_LAYOUT_PRESENT_SRC_KHR};
    const gpu::ImageUse copySrc{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    gpu::imageBarrier(cmd, image, present, copySrc);
    const VkBufferImageCopy region = gpu::wholeImageCopy(e);
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, mCaptureBuffer.handle(), 1, &region);
    gpu::imageBarrier(cmd, image, copySrc, {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR});
}

void ViewerApp::saveCapture(VkExtent2D e) {
    vkQueueWaitIdle(mCtx->queue());
    std::vector<uint8_t> bgra(size_t(e.width) * e.height * 4);
    mCaptureBuffer.download(bgra.data(), bgra.size());
    Image8 png{int(e.width), int(e.height), std::vector<uint8_t>(bgra.size())};
    for (size_t i = 0; i < bgra.size(); i += 4) {
        png.rgba[i] = bgra[i + 2];
        png.rgba[i + 1] = bgra[i + 1];
        png.rgba[i + 2] = bgra[i];
        png.rgba[i + 3] = 255;
    }
    writePng8(mCapturePath, png);
    std::fprintf(stderr, "amrvk view: captured the window to %s\n", mCapturePath.c_str());
    mCapturePath.clear();
}

void ViewerApp::screenshot(const fs::path& file) {
    // What the screen shows: the preview until the estimate is as clean (scene/preview_hold.h),
    // then the estimate with at least one complete sample. Right after an edit that is the new
    // picture's preview, made now.
    finishPreview();
    updateShown();
    Image image;
    std::string which;
    const auto noise = [](std::optional<double> n) { return n ? g3(*n) : std::string("not measured"); };
    if (mShown == scene::Shown::Preview) {
        image = scaledBilinear(mPreviewImage, mState.settings.width, mState.settings.height);
        which = "the ray-marched preview (" + std::to_string(mPreviewImage.width) + "x" +
                std::to_string(mPreviewImage.height) + ", noise " + noise(mHold.previewNoise()) +
                "; the estimate, at " + std::to_string(mPreviewing ? 0u : mPicture.renderer->accumulatedSpp()) +
                " spp with noise " + noise(mHold.estimateNoise()) + ", has not reached " + g3(mHold.threshold()) + ")";
    } else {
        finishSample();
        const scene::RenderOutput out = mPicture.renderer->output();
        image = out.mean;
        which = "the path-traced estimate (" + std::to_string(out.spp) + " spp" +
                (out.spp >= 2 ? ", noise " + g3(scene::meanRelativeError(out)) : std::string()) + ")";
    }
    if (mState.legend.show && toLower(file.extension().string()) == ".png") {
        if (!mLegendFont || mLegendFontFile != mState.legend.font) {
            mLegendFont = session::openLegendFont(mState.legend);
            mLegendFontFile = mState.legend.font;
        }
        const session::LegendContent legend = session::legendContent(mState, mVolume->field().units);
        image = session::drawLegend(image, legend, mState.legend.place, *mLegendFont);
    }
    writeImage(file, image);
    mPanel.message = "saved " + file.string() + ": " + which;
    std::fprintf(stderr, "amrvk view: %s\n", oneLineMessage(mPanel.message).c_str());
}

}  // namespace amrvk::viewer
