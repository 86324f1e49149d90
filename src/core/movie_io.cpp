#include "core/movie_io.h"

#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/file_io.h"
#include "core/process.h"
#include "core/strings.h"

namespace amrvk {

std::optional<std::string> findFfmpeg() { return findExecutable("ffmpeg"); }

void requireFfmpeg(const std::string& option, const std::filesystem::path& movie) {
    AMRVK_CHECK(findFfmpeg().has_value(), option, " ", movie.string(),
                ": ffmpeg was not found on PATH, so no movie can be encoded (install it: apt-get install ffmpeg), or "
                "write numbered frames instead: -o frames/f_%04d.png");
}

void encodeMp4(const std::string& pattern, uint32_t count, double fps, const std::filesystem::path& output) {
    AMRVK_CHECK(count > 0, output.string(), ": a movie needs at least one frame");
    AMRVK_CHECK(fps > 0, output.string(), ": frame rate ", fps, " must be positive");
    const std::optional<std::string> ffmpeg = findFfmpeg();
    AMRVK_CHECK(ffmpeg.has_value(), output.string(),
                ": ffmpeg was not found on PATH (install it: apt-get install ffmpeg)");
    AtomicFileWriter writer(output);
    writer.finish();  // ffmpeg writes the (empty) temporary; a device or FIFO is written through
    const std::string target = writer.temporaryPath().empty() ? output.string() : writer.temporaryPath().string();
    const std::vector<std::string> args = {
        *ffmpeg, "-nostdin", "-hide_banner", "-loglevel", "error", "-y", "-framerate", formatDouble(fps),
        "-start_number", "0", "-i", pattern, "-frames:v", std::to_string(count),
        // yuv420p (what players expect) needs even sizes: pad rather than resample.
        "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p", "-f", "mp4", target};
    const ProcessResult run = runProcess(args, ProcessOutput::CaptureAll);
    if (run.status != 0) {
        std::string last;  // ffmpeg's last message
        std::istringstream lines(run.out);
        for (std::string line; std::getline(lines, line);)
            if (!line.empty()) last = line;
        throw Error(strCat(
            output.string(), ": ffmpeg ",
            run.status < 0 ? std::string("could not be started") : "ended with status " + std::to_string(run.status),
            last.empty() ? std::string() : ": " + last));
    }
    writer.commit();
}

}  // namespace amrvk
