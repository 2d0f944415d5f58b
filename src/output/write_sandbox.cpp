// Landlock: see write_sandbox.hpp. The calls are made by number: glibc 2.36 has no wrappers.
#include "output/write_sandbox.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <linux/landlock.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "output/confined_folder.hpp"
#include "output/output_error.hpp"

// Landlock's ABI 3 (Linux 6.2) right, newer than Debian 12's kernel headers; its value is the
// kernel's, fixed by its ABI.
#ifndef LANDLOCK_ACCESS_FS_TRUNCATE
#define LANDLOCK_ACCESS_FS_TRUNCATE (1ULL << 14)
#endif

namespace particles::output {

namespace {

// What Landlock's ABI `abi` can restrict of writing (landlock.h: TRUNCATE from ABI 3, REFER from
// ABI 2). Reading and executing are left alone.
std::uint64_t writeAccesses(long abi) {
  std::uint64_t access = LANDLOCK_ACCESS_FS_WRITE_FILE | LANDLOCK_ACCESS_FS_REMOVE_DIR |
                         LANDLOCK_ACCESS_FS_REMOVE_FILE | LANDLOCK_ACCESS_FS_MAKE_CHAR | LANDLOCK_ACCESS_FS_MAKE_DIR |
                         LANDLOCK_ACCESS_FS_MAKE_REG | LANDLOCK_ACCESS_FS_MAKE_SOCK | LANDLOCK_ACCESS_FS_MAKE_FIFO |
                         LANDLOCK_ACCESS_FS_MAKE_BLOCK | LANDLOCK_ACCESS_FS_MAKE_SYM;
  if (abi >= 2) access |= LANDLOCK_ACCESS_FS_REFER;
  if (abi >= 3) access |= LANDLOCK_ACCESS_FS_TRUNCATE;
  return access;
}

void allowBeneath(int ruleset, const std::filesystem::path& folder, std::uint64_t access) {
  const FileDescriptor fd(::open(folder.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  if (!fd.valid()) throw OutputError(fmt::format("cannot open {}: {}", folder.string(), std::strerror(errno)));
  landlock_path_beneath_attr rule{};
  rule.allowed_access = access;
  rule.parent_fd = fd.get();
  if (::syscall(SYS_landlock_add_rule, ruleset, LANDLOCK_RULE_PATH_BENEATH, &rule, 0) != 0) {
    throw OutputError(fmt::format("landlock_add_rule for {}: {}", folder.string(), std::strerror(errno)));
  }
}

}  // namespace

bool restrictWritesBeneath(const std::filesystem::path& folder) {
  const long abi = ::syscall(SYS_landlock_create_ruleset, nullptr, 0, LANDLOCK_CREATE_RULESET_VERSION);
  if (abi < 1) return false;  // ENOSYS (an older kernel) or EOPNOTSUPP (not enabled at boot)
  const std::uint64_t access = writeAccesses(abi);
  landlock_ruleset_attr attributes{};
  attributes.handled_access_fs = access;
  const FileDescriptor ruleset(int(::syscall(SYS_landlock_create_ruleset, &attributes, sizeof attributes, 0)));
  if (!ruleset.valid()) throw OutputError(fmt::format("landlock_create_ruleset: {}", std::strerror(errno)));
  allowBeneath(ruleset.get(), folder, access);
  allowBeneath(ruleset.get(), "/dev", access & (LANDLOCK_ACCESS_FS_WRITE_FILE | LANDLOCK_ACCESS_FS_TRUNCATE));
  // Landlock requires it of a process without CAP_SYS_ADMIN: no exec may gain privileges after.
  if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) {
    throw OutputError(fmt::format("prctl(PR_SET_NO_NEW_PRIVS): {}", std::strerror(errno)));
  }
  if (::syscall(SYS_landlock_restrict_self, ruleset.get(), 0) != 0) {
    throw OutputError(fmt::format("landlock_restrict_self: {}", std::strerror(errno)));
  }
  return true;
}

}  // namespace particles::output
