#include "nmesh/cli/progress_bar.h"

#include <algorithm>
#include <chrono>
#include <string>

#include <unistd.h>

namespace nmesh::cli {

ProgressBar::Mode ProgressBar::detect(bool quiet) {
    if (quiet) return Mode::quiet;
    return isatty(fileno(stderr)) ? Mode::terminal : Mode::plain;
}

namespace {
std::string clock_text(double seconds) {
    const long s = long(seconds + 0.5);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
    return buf;
}
}  // namespace

std::function<bool(const Progress&)> ProgressBar::reconstruction(const std::atomic<bool>& stop) {
    return [this, &stop](const Progress& p) {
        update(p);
        return !stop.load();
    };
}

std::function<void(double)> ProgressBar::task(const char* what) {
    const auto start = std::chrono::steady_clock::now();
    return [this, what, start](double fraction) {
        task(what, fraction, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    };
}

void ProgressBar::update(const Progress& p) {
    if (mode_ == Mode::quiet) return;
    if (p.finishing) return task("finishing (regularisation and repair)", p.finish_fraction, p.seconds);
    // Redraw a terminal at most 10 times a second; log a plain line every 5 seconds.
    const double interval = mode_ == Mode::terminal ? 0.1 : 5.0;
    if (last_print_ >= 0.0 && p.seconds - last_print_ < interval) return;
    last_print_ = p.seconds;
    const double fraction = p.target_vertices ? std::min(1.0, double(p.vertices) / p.target_vertices) : 0.0;
    const double loop_seconds = p.seconds - p.setup_seconds;  // the rate of the loop, setup left out
    const double rate = loop_seconds > 0 ? double(p.iterations) / loop_seconds : 0.0;
    const double seconds_left = estimated_seconds_left(p);
    const std::string left = seconds_left >= 0.0 ? clock_text(seconds_left) : "-";
    if (mode_ == Mode::terminal) {
        constexpr int kWidth = 30;
        const int filled = int(fraction * kWidth);
        std::string bar(std::size_t(filled), '#');
        bar.append(std::size_t(kWidth - filled), '.');
        std::fprintf(out_, "\r[%s] %u / %u vertices%s  %.1f M it/s  %s elapsed  %s left   ", bar.c_str(), p.vertices,
                     p.target_vertices, p.settling ? " (settling)" : "", rate / 1e6, clock_text(p.seconds).c_str(),
                     left.c_str());
        drawn_ = true;
    } else {
        std::fprintf(out_, "nmesh: %u / %u vertices%s, %.1f M it/s, %s elapsed, %s left\n", p.vertices,
                     p.target_vertices, p.settling ? " (settling)" : "", rate / 1e6, clock_text(p.seconds).c_str(),
                     left.c_str());
    }
    std::fflush(out_);
}

void ProgressBar::task(const char* what, double fraction, double seconds) {
    if (mode_ == Mode::quiet) return;
    // The end is shown when anything was; before, a line at most every 0.1 s on a terminal (the
    // first after a second), every 5 seconds otherwise.
    const double interval = mode_ == Mode::terminal ? (task_shown_ ? 0.1 : 1.0) : 5.0;
    if (!(fraction >= 1.0 && task_shown_) && seconds - last_task_print_ < interval) return;
    last_task_print_ = seconds;
    task_shown_ = true;
    const int percent = int(std::min(1.0, std::max(0.0, fraction)) * 100.0);
    if (mode_ == Mode::terminal) {
        std::fprintf(out_, "\rnmesh: %s: %d%%, %s elapsed   ", what, percent, clock_text(seconds).c_str());
        drawn_ = true;
    } else {
        std::fprintf(out_, "nmesh: %s: %d%%, %s elapsed\n", what, percent, clock_text(seconds).c_str());
    }
    std::fflush(out_);
}

void ProgressBar::finish() {
    if (drawn_) std::fprintf(out_, "\n");
    drawn_ = false;
}

}  // namespace nmesh::cli
