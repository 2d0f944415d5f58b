#include "app/stop_signal.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>

namespace particles::app {

namespace {

volatile std::sig_atomic_t receivedSignal = 0;
volatile std::sig_atomic_t graceArmed = 0;  // StopMode::pollWithGrace: the first signal starts the alarm
struct sigaction previousInt {
}, previousTerm{}, previousAlarm{};

// What the alarm's handler writes, formatted before any signal: a handler may not format.
char graceOverMessage[128];
size_t graceOverLength = 0;

extern "C" void onStopSignal(int signal) {
  if (receivedSignal == 0 && graceArmed) ::alarm(kStopGraceSeconds);
  receivedSignal = signal;
}

extern "C" void onStopGraceOver(int) {
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, graceOverMessage, graceOverLength);
  ::_exit(128 + receivedSignal);
}

void install(int signal, void (*handler)(int), int flags, struct sigaction* previous) {
  struct sigaction action {};
  action.sa_handler = handler;
  action.sa_flags = flags;
  sigemptyset(&action.sa_mask);
  sigaction(signal, &action, previous);
}

}  // namespace

StopSignals::StopSignals(StopMode mode) : mode_(mode) {
  receivedSignal = 0;
  const bool grace = mode == StopMode::pollWithGrace;
  graceArmed = grace;
  if (grace) {
    const auto end = fmt::format_to_n(
        graceOverMessage, sizeof graceOverMessage,
        "particles: not stopped within {} s of the signal (blocked writing an output?); ended at once\n",
        kStopGraceSeconds);
    graceOverLength = std::min(end.size, sizeof graceOverMessage);
    install(SIGALRM, onStopGraceOver, SA_RESTART, &previousAlarm);
  }
  const int flags = grace ? SA_RESTART : 0;
  install(SIGINT, onStopSignal, flags, &previousInt);
  install(SIGTERM, onStopSignal, flags, &previousTerm);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &previousInt, nullptr);
  sigaction(SIGTERM, &previousTerm, nullptr);
  if (mode_ != StopMode::pollWithGrace) return;
  // Once stopping, the grace period keeps running: it bounds what the command still does on its
  // way out too, such as closing a --trace FIFO whose last buffered lines wait for a reader.
  if (receivedSignal != 0) return;
  ::alarm(0);
  sigaction(SIGALRM, &previousAlarm, nullptr);
}

int stopSignal() {
  return receivedSignal;
}

}  // namespace particles::app
