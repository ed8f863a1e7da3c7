// nmesh/pipeline/reporter.h — the progress callback of reconstruct() (Callbacks::progress), as
// the learning and the finishing stage report to it.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>

#include "nmesh/learn/neural_mesh.h"
#include "nmesh/reconstruct.h"

namespace nmesh::pipeline {

using Clock = std::chrono::steady_clock;

// The progress callback, asked about every 2^16 iterations and once when the learning ends; it
// remembers a cancellation.
class Reporter {
public:
    // `engine` is the engine of the moment (an output retry makes a new one).
    Reporter(const Callbacks& callbacks, const std::unique_ptr<NeuralMesh>& engine, std::uint32_t target,
             Clock::time_point start)
        : callbacks_(callbacks), engine_(engine), start_(start) {
        progress_.target_vertices = target;
        progress_.setup_seconds = elapsed();
    }
    double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
    double setup_seconds() const { return progress_.setup_seconds; }
    // After each iteration: false once the caller has cancelled.
    bool keep_going(bool settling) {
        constexpr std::uint64_t kReportMask = (1u << 16) - 1;  // a callback every 65,536 iterations
        if ((engine_->iteration() & kReportMask) == 0 && !report(settling)) cancelled_ = true;
        return !cancelled_;
    }
    bool report(bool settling) {
        if (!callbacks_.progress) return true;
        progress_.vertices = engine_->mesh().n_vertices();
        progress_.iterations = engine_->iteration();
        progress_.seconds = elapsed();
        progress_.settling = settling;
        progress_.finishing = false;  // learning (again, after an output retry)
        progress_.finish_fraction = 0.0;
        return callbacks_.progress(progress_);
    }
    // The finishing stage's progress, at most every 0.1 s and at its end.
    void report_finishing(double fraction) {
        if (!callbacks_.progress) return;
        const double now = elapsed();
        if (fraction < 1.0 && now - last_finish_report_ < 0.1) return;
        last_finish_report_ = now;
        progress_.seconds = now;
        progress_.finishing = true;
        progress_.finish_fraction = fraction;
        callbacks_.progress(progress_);
    }
    bool cancelled() const { return cancelled_; }

private:
    const Callbacks& callbacks_;
    const std::unique_ptr<NeuralMesh>& engine_;
    Clock::time_point start_;
    Progress progress_;
    bool cancelled_ = false;
    double last_finish_report_ = -1.0;
};

}  // namespace nmesh::pipeline
