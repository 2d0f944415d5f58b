// The `particles` program (docs/physics.md §12): parses the command line and runs it (program.hpp).
#include <malloc.h>

#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "app/exit_codes.hpp"
#include "app/program.hpp"

namespace {

// glibc gives the top of its heap back to the system once 128 KiB or more of it is free, and takes
// it again on the next frame: a render of the cloth made ~8 brk calls per frame, and with
// transparent huge pages each regrowth zeroes 2 MiB pages again (page faults were 10 % of the
// CPU time of `render -o cloth.mp4`, 5 % of its wall time, bench/README.md). Keeping up to 512 MiB
// of free heap, growing it 64 MiB at a time, and mapping only blocks of 32 MiB and more on their
// own ends the churn.
void keepHeapBetweenFrames() {
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
}

}  // namespace

int main(int argc, char** argv) {
  keepHeapBetweenFrames();
  try {
    return particles::app::runProgram(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::bad_alloc&) {
    // Memory ran out before a command ran (or after it reported): the options themselves, under a
    // tight cap (`ulimit -v`). The same code and words as runReportingErrors', allocating nothing.
    std::fputs("error: out of memory: an allocation failed (std::bad_alloc)\n", stderr);
    return particles::app::kOutputFailed;
  }
}
