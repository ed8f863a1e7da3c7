// nmesh/cli/progress_bar.h — progress of a reconstruction on stderr.
//
// On a terminal: one line redrawn in place (a bar, vertices reached / target, iterations per
// second, elapsed and estimated time left). Otherwise (a log file, CI): a plain line every few
// seconds. Quiet: nothing.
#pragma once

#include <atomic>
#include <cstdio>
#include <functional>

#include "nmesh/reconstruct.h"

namespace nmesh::cli {

class ProgressBar {
public:
    enum class Mode { quiet, terminal, plain };
    explicit ProgressBar(Mode mode, std::FILE* out = stderr) : mode_(mode), out_(out) {}
    // Picks terminal or plain from whether stderr is a terminal.
    static Mode detect(bool quiet);

    // The callbacks that draw on this bar, the one place where the tool sets them up: a
    // reconstruction's (Callbacks::progress), which draws each report and cancels once `stop` is
    // set; another long task's (EvalOptions::progress, the share done), timed from this call.
    std::function<bool(const Progress&)> reconstruction(const std::atomic<bool>& stop);
    std::function<void(double fraction)> task(const char* what);

    void update(const Progress& p);
    // Progress of another long task (measuring the mesh for --stats or eval): `what`, the share
    // done and the time it has taken. Nothing for a task that ends within a second on a terminal
    // or within five seconds otherwise.
    void task(const char* what, double fraction, double seconds);
    void finish();  // ends the terminal line

private:
    Mode mode_;
    std::FILE* out_;
    double last_print_ = -1.0;
    double last_task_print_ = 0.0;
    bool task_shown_ = false;
    bool drawn_ = false;
};

}  // namespace nmesh::cli
