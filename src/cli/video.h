// Videos through ffmpeg (an external program, found on PATH): images on disk encoded into an
// MP4 (`weir render --video`), or frames streamed to it as they are drawn (`weir view --record`).
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace weir {

// Whether an executable of this name is on PATH.
bool programOnPath(const std::string& program);

// Throws IoError saying that `option` needs ffmpeg (and how to install it) when it is not on
// PATH, and std::invalid_argument when `file` does not end in .mp4.
void checkVideoOutput(const std::string& option, const std::string& file);

// Encodes images <dir>/frame_<first..first+count-1>.png into an H.264 MP4 (yuv420p, so that
// every player takes it), written to a temporary name and renamed.
void encodeImages(const std::string& imagesDir, int first, int count, double fps,
                  const std::string& outFile);

// An MP4 made from RGB frames as they come: ffmpeg reads them from a pipe. The file appears
// (renamed from a temporary) on finish(); a recorder destroyed unfinished removes the temporary.
class VideoRecorder {
   public:
    VideoRecorder(const std::string& outFile, int width, int height, double fps);
    ~VideoRecorder();
    VideoRecorder(const VideoRecorder&) = delete;
    VideoRecorder& operator=(const VideoRecorder&) = delete;

    int width() const { return width_; }
    int height() const { return height_; }
    // One frame of width x height pixels, 3 bytes each, rows top to bottom. Throws IoError when
    // ffmpeg stopped taking frames.
    void add(const std::vector<std::uint8_t>& rgb);
    std::int64_t frames() const { return frames_; }
    // Ends the stream, waits for ffmpeg and renames the file into place; throws IoError if
    // ffmpeg failed.
    void finish();

   private:
    void stop();

    std::string outFile_, partial_;
    int width_, height_;
    int pipe_ = -1;
    pid_t pid_ = 0;
    std::int64_t frames_ = 0;
};

}  // namespace weir
