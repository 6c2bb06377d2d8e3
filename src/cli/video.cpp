// ffmpeg as a child process: from numbered PNGs, or from raw RGB frames on its standard input.
#include "cli/video.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "io/io_error.h"

extern char** environ;

namespace weir {

namespace {

namespace fs = std::filesystem;

// A temporary beside `outFile`: NAME.tmp.PID.mp4 (a later run removes it if this one is killed).
std::string partialName(const std::string& outFile) {
    const fs::path out(outFile);
    if (out.has_parent_path()) {
        fs::create_directories(out.parent_path());
    }
    return (out.parent_path() /
            (out.stem().string() + ".tmp." + std::to_string(::getpid()) + ".mp4"))
        .string();
}

// ffmpeg's arguments after its input: H.264 in yuv420p, even sizes (the codec needs them).
std::vector<std::string> outputArguments(const std::string& partial) {
    return {"-vf",       "pad=ceil(iw/2)*2:ceil(ih/2)*2",
            "-c:v",      "libx264",
            "-pix_fmt",  "yuv420p",
            "-movflags", "+faststart",
            partial};
}

pid_t spawn(std::vector<std::string> args, posix_spawn_file_actions_t* actions) {
    std::vector<char*> argv;
    for (std::string& arg : args) {
        argv.push_back(arg.data());
    }
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawnp(&pid, "ffmpeg", actions, nullptr, argv.data(), environ) != 0) {
        throw IoError("cannot start ffmpeg (is it on PATH? Debian/Ubuntu: apt-get install ffmpeg)");
    }
    return pid;
}

bool waitSucceeded(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

std::string rateText(double fps) {
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.6g", fps);
    return rate;
}

}  // namespace

bool programOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path != nullptr ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
        if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) {
            return true;
        }
    }
    return false;
}

void checkVideoOutput(const std::string& option, const std::string& file) {
    if (fs::path(file).extension() != ".mp4") {
        throw std::invalid_argument(option + " '" + file + "': the file name must end in .mp4");
    }
    if (!programOnPath("ffmpeg")) {
        throw IoError(option +
                      " needs ffmpeg on PATH (Debian/Ubuntu: apt-get install ffmpeg); nothing was "
                      "done");
    }
}

void encodeImages(const std::string& imagesDir, int first, int count, double fps,
                  const std::string& outFile) {
    const std::string partial = partialName(outFile);
    std::vector<std::string> args = {"ffmpeg",
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-framerate",
                                     rateText(fps),
                                     "-start_number",
                                     std::to_string(first),
                                     "-i",
                                     (fs::path(imagesDir) / "frame_%05d.png").string(),
                                     "-frames:v",
                                     std::to_string(count)};
    for (std::string& arg : outputArguments(partial)) {
        args.push_back(std::move(arg));
    }
    if (!waitSucceeded(spawn(args, nullptr))) {
        std::error_code ignored;
        fs::remove(partial, ignored);
        throw IoError("ffmpeg could not make '" + outFile + "' from the images in '" + imagesDir +
                      "' (see its message above)");
    }
    fs::rename(partial, outFile);
}

VideoRecorder::VideoRecorder(const std::string& outFile, int width, int height, double fps)
    : outFile_(outFile), partial_(partialName(outFile)), width_(width), height_(height) {
    int fds[2];
    if (::pipe(fds) != 0) {
        throw IoError("cannot make a pipe to ffmpeg for '" + outFile + "'");
    }
    ::fcntl(fds[1], F_SETFD, FD_CLOEXEC);  // only ffmpeg's stdin stays open in the child
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
    std::vector<std::string> args = {"ffmpeg",
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-f",
                                     "rawvideo",
                                     "-pix_fmt",
                                     "rgb24",
                                     "-s",
                                     std::to_string(width) + "x" + std::to_string(height),
                                     "-framerate",
                                     rateText(fps),
                                     "-i",
                                     "-"};
    for (std::string& arg : outputArguments(partial_)) {
        args.push_back(std::move(arg));
    }
    try {
        pid_ = spawn(args, &actions);
    } catch (...) {
        posix_spawn_file_actions_destroy(&actions);
        ::close(fds[0]);
        ::close(fds[1]);
        throw;
    }
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    pipe_ = fds[1];
    ::signal(SIGPIPE, SIG_IGN);  // a failed ffmpeg shows as a write error, not a dead weir
}

VideoRecorder::~VideoRecorder() {
    if (pid_ != 0) {
        stop();
        waitSucceeded(pid_);
        std::error_code ignored;
        fs::remove(partial_, ignored);
    }
}

void VideoRecorder::add(const std::vector<std::uint8_t>& rgb) {
    const std::uint8_t* data = rgb.data();
    std::size_t left = std::size_t(width_) * std::size_t(height_) * 3;
    if (rgb.size() < left) {
        throw std::invalid_argument("VideoRecorder::add: frame smaller than width x height");
    }
    while (left > 0) {
        const ssize_t n = ::write(pipe_, data, left);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            throw IoError("ffmpeg stopped taking frames for '" + outFile_ +
                          "' (see its message above)");
        }
        data += n;
        left -= std::size_t(n);
    }
    ++frames_;
}

void VideoRecorder::stop() {
    if (pipe_ >= 0) {
        ::close(pipe_);
        pipe_ = -1;
    }
}

void VideoRecorder::finish() {
    stop();
    const bool ok = waitSucceeded(pid_);
    pid_ = 0;
    if (!ok || frames_ == 0) {
        std::error_code ignored;
        fs::remove(partial_, ignored);
        throw IoError("ffmpeg could not make '" + outFile_ + "'" +
                      (frames_ == 0 ? ": no frame was recorded" : " (see its message above)"));
    }
    fs::rename(partial_, outFile_);
}

}  // namespace weir
