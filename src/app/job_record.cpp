// Job records: see job_record.hpp.
#include "app/job_record.hpp"

#include <elf.h>
#include <fmt/format.h>
#include <link.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <map>

#include "input/text_file.hpp"
#include "output/output_error.hpp"
#include "output/output_file.hpp"

namespace particles::app {

namespace fs = std::filesystem;

namespace {

// The headline of this process's command; one process runs one command.
std::vector<std::pair<std::string, double>>& headline() {
  static std::vector<std::pair<std::string, double>> values;
  return values;
}

std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

constexpr std::string_view kHeader =
    "# particles job record: a rerun of this command by this version skips it while exit is 0 and its\n"
    "# outputs exist (--force reruns it); `particles gather` reads the values.\n";

}  // namespace

void addJobOptions(CLI::App& command, JobOptions& o) {
  command.add_option("--record", o.record,
                     "A sweep job's record: skip when it shows this command done by this version with its outputs "
                     "present; write it after running (exit code, message, headline numbers)");
  command.add_flag("--force", o.force, "With --record: run even when the record says the job is done");
}

void reportHeadline(const std::string& key, double value) {
  auto& values = headline();
  for (auto& [k, v] : values) {
    if (k == key) {
      v = value;
      return;
    }
  }
  values.emplace_back(key, value);
}

std::string commandText(const std::vector<std::string>& args) {
  std::string out;
  for (const std::string& a : args) {
    if (a == "--force") continue;
    if (!out.empty()) out += ' ';
    out += shellQuote(a);
  }
  return out;
}

std::optional<std::vector<std::string>> splitCommandText(std::string_view text) {
  std::vector<std::string> words;
  std::string word;
  bool inWord = false;
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
  };
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == ' ') {
      if (inWord) words.push_back(std::move(word));
      word.clear();
      inWord = false;
      ++i;
    } else if (c == '\'') {  // '…': every byte literal up to the next quote
      const size_t end = text.find('\'', i + 1);
      if (end == std::string_view::npos) return std::nullopt;
      word.append(text.substr(i + 1, end - i - 1));
      inWord = true;
      i = end + 1;
    } else if (c == '\\') {  // \': the quote between two quoted parts
      if (i + 1 >= text.size() || text[i + 1] != '\'') return std::nullopt;
      word += '\'';
      inWord = true;
      i += 2;
    } else if (c == '$' && i + 1 < text.size() && text[i + 1] == '\'') {  // $'…' with escapes
      i += 2;
      for (;;) {
        if (i >= text.size()) return std::nullopt;
        const char d = text[i++];
        if (d == '\'') break;
        if (d != '\\') {
          word += d;
          continue;
        }
        if (i >= text.size()) return std::nullopt;
        const char e = text[i++];
        if (e == 'n')
          word += '\n';
        else if (e == 't')
          word += '\t';
        else if (e == 'r')
          word += '\r';
        else if (e == '\\' || e == '\'')
          word += e;
        else if (e == 'x' && i + 1 < text.size() && hex(text[i]) >= 0 && hex(text[i + 1]) >= 0) {
          word += char(hex(text[i]) * 16 + hex(text[i + 1]));
          i += 2;
        } else {
          return std::nullopt;
        }
      }
      inWord = true;
    } else if (isPlainShellChar(c)) {
      word += c;
      inWord = true;
      ++i;
    } else {
      return std::nullopt;
    }
  }
  if (inWord) words.push_back(std::move(word));
  return words;
}

namespace {

// The GNU build ID of the running executable (the linker's SHA-1 of its contents, `-Wl,--build-id`),
// as hex; empty if it has none. The first object dl_iterate_phdr reports is the executable itself.
std::string executableBuildId() {
  std::string id;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) -> int {
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& ph = info->dlpi_phdr[i];
          if (ph.p_type != PT_NOTE) continue;
          const auto* p = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
          const unsigned char* end = p + ph.p_memsz;
          // Notes: header, name and descriptor, the latter two padded to 4 bytes.
          while (p + sizeof(ElfW(Nhdr)) <= end) {
            const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(p);
            const unsigned char* name = p + sizeof(ElfW(Nhdr));
            const unsigned char* desc = name + ((note->n_namesz + 3) & ~3u);
            if (desc + note->n_descsz > end) break;
            if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 && std::equal(name, name + 4, "GNU")) {
              auto* text = static_cast<std::string*>(out);
              for (unsigned k = 0; k < note->n_descsz; ++k) *text += fmt::format("{:02x}", desc[k]);
              return 1;
            }
            p = desc + ((note->n_descsz + 3) & ~3u);
          }
        }
        return 1;  // only the executable
      },
      &id);
  return id;
}

}  // namespace

std::string programVersion() {
  // The release number alone would let a rebuilt binary of changed code take old records as its
  // own; the build ID names this very binary, so any rebuild reruns the jobs.
  static const std::string version = [] {
    const std::string id = executableBuildId();
    return id.empty() ? std::string(PARTICLES_VERSION)
                      : fmt::format("{} build {}", PARTICLES_VERSION, id.substr(0, 16));
  }();
  return version;
}

std::optional<JobRecord> parseJobRecord(std::string_view text) {
  JobRecord r;
  bool sawVersion = false, sawExit = false;
  // Headline keys seen, for a key written twice (the last value counts, as reportHeadline keeps
  // it): a map keeps this linear in the number of keys.
  std::map<std::string, size_t, std::less<>> headlineAt;
  while (!text.empty()) {
    const size_t newline = text.find('\n');
    const std::string_view line = text.substr(0, newline);
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
    if (line.empty() || line[0] == '#') continue;
    const size_t colon = line.find(": ");
    const std::string_view key = line.substr(0, colon);
    const std::string_view value = colon == std::string_view::npos ? std::string_view() : line.substr(colon + 2);
    auto number = [&](double& x) {
      const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), x);
      return ec == std::errc() && end == value.data() + value.size();
    };
    if (key == "version") {
      r.version = value;
      sawVersion = true;
    } else if (key == "command") {
      r.command = value;
    } else if (key == "exit") {
      int code = 0;
      const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), code);
      if (ec != std::errc() || end != value.data() + value.size() || code < 0 || code > 255) return std::nullopt;
      r.exitCode = code;
      sawExit = true;
    } else if (key == "message") {
      r.message = value;
    } else if (key == "seconds") {
      if (!number(r.seconds)) return std::nullopt;
    } else if (key == "output") {
      r.outputs.emplace_back(value);
    } else if (key.substr(0, 6) == "value.") {
      double x = 0;
      if (!number(x)) return std::nullopt;
      const std::string_view name = key.substr(6);
      if (const auto it = headlineAt.find(name); it != headlineAt.end()) {
        r.headline[it->second].second = x;
      } else {
        headlineAt.emplace(name, r.headline.size());
        r.headline.emplace_back(name, x);
      }
    }
  }
  if (!sawVersion || !sawExit) return std::nullopt;
  return r;
}

std::optional<JobRecord> readJobRecord(const std::filesystem::path& file, std::uintmax_t maxInputMiB) {
  std::string text;
  try {
    text = input::readTextFile(file, maxInputMiB, input::Accept::regularOnly);
  } catch (const input::ReadError& e) {
    if (e.reason() == input::ReadError::Reason::cannotOpen &&
        !std::filesystem::exists(std::filesystem::symlink_status(file))) {
      return std::nullopt;
    }
    throw;
  }
  return parseJobRecord(text);
}

void writeJobRecord(const std::filesystem::path& file, const JobRecord& r) {
  output::OutputFile out(file);
  std::string text(kHeader);
  text += fmt::format("version: {}\ncommand: {}\nexit: {}\nseconds: {:.3f}\n", r.version, oneLine(r.command),
                      r.exitCode, r.seconds);
  if (!r.message.empty()) text += fmt::format("message: {}\n", oneLine(r.message));
  for (const std::string& o : r.outputs) text += fmt::format("output: {}\n", oneLine(o));
  for (const auto& [k, v] : r.headline) text += fmt::format("value.{}: {}\n", k, v);
  out.write(text);
  out.commit();
}

bool jobDone(const std::optional<JobRecord>& r, const std::string& command, std::string* why) {
  auto no = [&](std::string reason) {
    if (why) *why = std::move(reason);
    return false;
  };
  if (!r) return no("no record");
  if (r->exitCode != 0) return no(fmt::format("it failed (exit {})", r->exitCode));
  if (r->version != programVersion()) return no(fmt::format("it ran with version {}", r->version));
  if (r->command != command) return no("its command was different");
  for (const std::string& o : r->outputs) {
    std::error_code ec;
    if (!std::filesystem::exists(o, ec)) return no(fmt::format("its output {} is gone", o));
  }
  return true;
}

void requireRecordPath(const std::filesystem::path& record) {
  std::error_code ec;
  const auto status = std::filesystem::status(record, ec);  // links followed, as the write follows them
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw InputError(fmt::format("--record {}: {}; a record is a regular file", record.string(),
                                 std::filesystem::is_directory(status) ? "a directory" : "not a regular file"));
  }
  const std::filesystem::path folder = record.has_parent_path() ? record.parent_path() : ".";
  if (!std::filesystem::is_directory(folder, ec)) {
    throw InputError(fmt::format("--record {}: no folder {}", record.string(), folder.string()));
  }
}

int runRecordedJob(const JobOptions& options, const std::vector<std::string>& args,
                   const std::vector<std::string>& outputs, const ErrorContext& context,
                   const std::function<int()>& command) {
  const std::string text = commandText(args);
  std::optional<JobRecord> previous;
  try {
    previous = readJobRecord(options.record, options.maxInputMiB);
  } catch (const input::ReadError& e) {
    // Not a record this program wrote: refused before anything runs, and left as it is.
    return runReportingErrors(
        context, [&]() -> int { throw InputError(fmt::format("--record {}: {}", options.record, e.what())); });
  }
  std::error_code ec;
  if (!previous && fs::exists(fs::symlink_status(options.record, ec)) && fs::file_size(options.record, ec) > 0 && !ec) {
    // A file of its own that is no record (notes.txt, a figure): refused, never replaced.
    return runReportingErrors(context, [&]() -> int {
      throw InputError(
          fmt::format("--record {}: not a job record; it is left as it is (choose another file, or "
                      "remove it)",
                      options.record));
    });
  }
  if (!options.force && jobDone(previous, text)) {
    fmt::print(stderr, "{}: done before by this command and version; skipped (--force runs it again)\n",
               options.record);
    return kOk;
  }
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  ErrorContext withMessage = context;
  withMessage.printed = &message;
  const int code = runReportingErrors(withMessage, command);

  JobRecord r;
  r.version = programVersion();
  r.command = text;
  r.exitCode = code;
  r.message = message;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.outputs = outputs;
  if (code == kOk) r.headline = headline();
  try {
    writeJobRecord(options.record, r);
  } catch (const output::OutputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return code == kOk ? kOutputFailed : code;
  }
  return code;
}

}  // namespace particles::app
