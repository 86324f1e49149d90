// Other programs and movies (core/process.h, core/movie_io.h): arguments reach the child as they
// are (no shell), PATH lookup, and an MP4 whose frame count (ffprobe) and per-frame colours
// (decoded back by ffmpeg) are those of the frames given, in order; the errors without ffmpeg and
// on a failed encoding leave no file. The movie tests skip where ffmpeg is not installed.
#include "core/movie_io.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "core/error.h"
#include "core/image_io.h"
#include "core/process.h"
#include "test_data.h"

using namespace amrvk;
namespace fs = std::filesystem;

namespace {

// Sets PATH for one scope.
class ScopedPath {
public:
    explicit ScopedPath(const std::string& path) {
        const char* old = std::getenv("PATH");
        mOld = old ? old : "";
        ::setenv("PATH", path.c_str(), 1);
    }
    ~ScopedPath() { ::setenv("PATH", mOld.c_str(), 1); }

private:
    std::string mOld;
};

// Frame k's colour: distinct, far apart, in sRGB 8-bit after PNG encoding.
glm::vec3 frameColour(int k) {
    const glm::vec3 colours[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}};
    return colours[k % 5];
}

}  // namespace

TEST(Process, ArgumentsAreNotInterpretedByAShell) {
    const ProcessResult r = runProcess({"printf", "%s|", "$HOME; echo no", "a b", "*"}, ProcessOutput::Capture);
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, "$HOME; echo no|a b|*|");
    EXPECT_EQ(runProcess({"false"}, ProcessOutput::Discard).status, 1);
    EXPECT_EQ(runProcess({"amrvk-no-such-program"}, ProcessOutput::Discard).status, -1);
    const ProcessResult both = runProcess({"sh", "-c", "echo out; echo err >&2"}, ProcessOutput::CaptureAll);
    EXPECT_EQ(both.out, "out\nerr\n");
    EXPECT_EQ(runProcess({"sh", "-c", "kill -TERM $$"}, ProcessOutput::Discard).status, 128 + 15);
}

TEST(Process, FindExecutableSearchesPath) {
    const fs::path dir = test::scratchDir();
    std::ofstream(dir / "tool") << "#!/bin/sh\n";
    std::ofstream(dir / "plain") << "data\n";
    fs::permissions(dir / "tool", fs::perms::owner_all);
    ScopedPath path("/nonexistent:" + dir.string());
    EXPECT_EQ(findExecutable("tool"), (dir / "tool").string());
    EXPECT_FALSE(findExecutable("plain").has_value()) << "not executable";
    EXPECT_FALSE(findExecutable("sh").has_value()) << "not on this PATH";
    EXPECT_EQ(findExecutable("/bin/sh"), std::optional<std::string>("/bin/sh"));
}

TEST(MovieIo, WithoutFfmpegOneErrorSaysHowToGetFrames) {
    const fs::path dir = test::scratchDir();
    ScopedPath path(dir.string());
    EXPECT_FALSE(findFfmpeg().has_value());
    const std::string e = test::errorOf([&] { requireFfmpeg("-o", dir / "m.mp4"); });
    EXPECT_NE(e.find("m.mp4: ffmpeg was not found on PATH"), std::string::npos) << e;
    EXPECT_NE(e.find("apt-get install ffmpeg"), std::string::npos) << e;
    EXPECT_NE(e.find("-o frames/f_%04d.png"), std::string::npos) << e;
    EXPECT_NE(test::errorOf([&] { encodeMp4((dir / "f_%d.png").string(), 2, 24, dir / "m.mp4"); }).find("ffmpeg"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "m.mp4"));
}

TEST(MovieIo, EncodesTheFramesInOrder) {
    if (!findFfmpeg() || !findExecutable("ffprobe"))
        GTEST_SKIP() << "ffmpeg/ffprobe not installed (apt-get install ffmpeg)";
    const fs::path dir = test::scratchDir();
    const int frames = 5, width = 33, height = 17;  // odd sizes: padded to even for yuv420p
    for (int k = 0; k < frames; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "f_%03d.png", k);
        writeImage(dir / name, Image(width, height, glm::vec4(frameColour(k), 1)));
    }
    const fs::path movie = dir / "m.mp4";
    encodeMp4((dir / "f_%03d.png").string(), frames, 10, movie);
    ASSERT_TRUE(fs::is_regular_file(movie));
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << "temporary left: " << e.path();
    const ProcessResult probe = runProcess(
        {"ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
         "stream=nb_read_frames,width,height,codec_name,r_frame_rate", "-of", "default=nw=1", movie.string()},
        ProcessOutput::Capture);
    ASSERT_EQ(probe.status, 0);
    EXPECT_NE(probe.out.find("nb_read_frames=5"), std::string::npos) << probe.out;
    EXPECT_NE(probe.out.find("codec_name=h264"), std::string::npos) << probe.out;
    EXPECT_NE(probe.out.find("width=34"), std::string::npos) << probe.out;
    EXPECT_NE(probe.out.find("height=18"), std::string::npos) << probe.out;
    EXPECT_NE(probe.out.find("r_frame_rate=10/1"), std::string::npos) << probe.out;
    // Decoded back (34x18, padding included): each frame's mean colour over the pixels whose 2x2
    // chroma block holds no padding (32x16) is its frame's, in order.
    const ProcessResult raw =
        runProcess({"ffmpeg", "-v", "error", "-i", movie.string(), "-f", "rawvideo", "-pix_fmt", "rgb24", "-"},
                   ProcessOutput::Capture);
    ASSERT_EQ(raw.status, 0);
    const int paddedW = 34, paddedH = 18;
    ASSERT_EQ(raw.out.size(), size_t(frames * paddedW * paddedH * 3));
    for (int k = 0; k < frames; ++k) {
        glm::dvec3 mean(0.0);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 32; ++x)
                for (int c = 0; c < 3; ++c)
                    mean[c] += double(uint8_t(raw.out[size_t(((k * paddedH + y) * paddedW + x) * 3 + c)]));
        mean /= 32.0 * 16.0 * 255.0;
        // H.264 in yuv420p is lossy: within 0.1 of each channel, far less than the 1.0 between colours.
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], frameColour(k)[c], 0.1) << "frame " << k << " channel " << c;
    }
    // A failed encoding (frames that are not there) names ffmpeg's message and leaves no file.
    const std::string e = test::errorOf([&] { encodeMp4((dir / "g_%03d.png").string(), 3, 10, dir / "n.mp4"); });
    EXPECT_NE(e.find("n.mp4: ffmpeg ended with status"), std::string::npos) << e;
    EXPECT_FALSE(fs::exists(dir / "n.mp4"));
    for (const fs::directory_entry& f : fs::directory_iterator(dir))
        EXPECT_EQ(f.path().string().find(".tmp-"), std::string::npos) << "temporary left: " << f.path();
}
