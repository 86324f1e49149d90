#pragma once
// MP4 movies from numbered frames, encoded by Debian's ffmpeg (run through core/process.h: an
// argument vector, no shell). amrvk links no codec; where ffmpeg is absent a movie is one error
// that says so, and frames are written instead (docs/movies.md).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace amrvk {

// `ffmpeg` on PATH, or nullopt.
std::optional<std::string> findFfmpeg();

// Throws "OPTION PATH: ffmpeg was not found on PATH (...)" unless findFfmpeg() finds one; the message
// says how to install it and how to write frames instead.
void requireFfmpeg(const std::string& option, const std::filesystem::path& movie);

// Encodes PNG frames 0 .. count-1 of `pattern` (printf-style with one %d conversion, '%' written
// as %%, as ffmpeg's image2 reads it) at `fps` frames per second into `output`: H.264 (libx264),
// yuv420p, odd sizes padded by one black row or column. ffmpeg writes an AtomicFileWriter's
// temporary, renamed over `output` only once ffmpeg succeeded: a failed or interrupted encoding
// leaves nothing. Throws one line naming ffmpeg's last message when it fails.
void encodeMp4(const std::string& pattern, uint32_t count, double fps, const std::filesystem::path& output);

}  // namespace amrvk
