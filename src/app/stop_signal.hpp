#pragma once
// SIGINT and SIGTERM ask a long command (render, sweep) to stop: while a StopSignals lives, the
// first of them sets a flag the command's loop polls (stopSignal()), and the command removes what
// it started and exits 128 + the signal. The handlers before it are restored when it goes.

namespace particles::app {

enum class StopMode {
  // A loop that polls between pieces of work (a render's frames). System calls restart after the
  // handler, so an output being written is not cut short; but a command can be stuck where no
  // loop polls: writing to a pipe or FIFO whose reader has stopped reading, or to a filesystem
  // that hangs. So the first signal also starts a grace period (kStopGraceSeconds); a command that
  // has not stopped by its end exits at once, with the same code, from the alarm's handler. Its
  // output is an anonymous temporary that vanishes with the process (a named one, or a PNG
  // sequence's staging folder, is left for the next run to remove, as after SIGKILL).
  pollWithGrace,
  // A loop that waits for child processes (a sweep's jobs): the signal interrupts the wait (no
  // SA_RESTART), so that the loop sees it at once and stops its children; no grace period, since
  // each child has its own.
  interruptWaits,
};

// Several frames of the largest renders we make.
inline constexpr unsigned kStopGraceSeconds = 3;

class StopSignals {
 public:
  explicit StopSignals(StopMode mode);
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  StopMode mode_;
};

// The signal that asked to stop since the last StopSignals was made; 0 when none has.
int stopSignal();

}  // namespace particles::app
