#include "sweep/run_journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"

namespace peg3d::sweep {
namespace {

std::string errno_text() { return std::strerror(errno); }

/// The first difference below `path`.
std::optional<JsonDifference> difference_at(const nlohmann::json& a, const nlohmann::json& b, const std::string& path) {
  if (a == b) return std::nullopt;
  const auto child = [&](const std::string& key) { return path.empty() ? key : path + "." + key; };
  if (a.is_object() && b.is_object()) {
    // Keys of both, in sorted order (nlohmann::json keeps objects sorted).
    auto ia = a.begin();
    auto ib = b.begin();
    while (ia != a.end() || ib != b.end()) {
      if (ib == b.end() || (ia != a.end() && ia.key() < ib.key())) return JsonDifference{child(ia.key()), *ia, nullptr};
      if (ia == a.end() || ib.key() < ia.key()) return JsonDifference{child(ib.key()), nullptr, *ib};
      if (auto d = difference_at(*ia, *ib, child(ia.key()))) return d;
      ++ia, ++ib;
    }
  }
  if (a.is_array() && b.is_array()) {
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
      if (auto d = difference_at(a[i], b[i], fmt::format("{}[{}]", path, i))) return d;
    }
  }
  return JsonDifference{path, a, b};
}

std::string shown_json(const nlohmann::json& j) { return j.is_null() ? std::string("(none)") : brief(j); }

// The header line `j` of `file`: a journal of this format and version, of the sweep with `setup` and `runs`.
void check_header(const std::filesystem::path& file, nlohmann::json& j, const nlohmann::json& setup, std::size_t runs) {
  if (!j.is_object() || !j.contains("format") || j["format"] != kJournalFormat) {
    throw InputError(file, 1, "format", fmt::format("not a peg3d run journal (expected \"{}\")", kJournalFormat));
  }
  if (!j.contains("version") || j["version"] != kJournalVersion) {
    throw InputError(file, 1, "version",
                     fmt::format("journal version {} is not supported (this peg3d reads {})",
                                 shown_json(j.contains("version") ? j["version"] : nlohmann::json()), kJournalVersion));
  }
  if (const auto d = first_difference(j.contains("setup") ? j["setup"] : nlohmann::json(), setup)) {
    throw InputError(file, 1, d->field.empty() ? "setup" : "setup." + d->field,
                     fmt::format("the journal's sweep has {}, this one {}: a journal resumes only the sweep that "
                                 "wrote it",
                                 shown_json(d->a), shown_json(d->b)));
  }
  if (!j.contains("runs") || !j["runs"].is_number_unsigned() || j["runs"].get<std::size_t>() != runs) {
    throw InputError(file, 1, "runs", fmt::format("the journal's sweep has {} runs, this one {}", shown_json(j["runs"]), runs));
  }
}

}  // namespace

std::optional<JsonDifference> first_difference(const nlohmann::json& a, const nlohmann::json& b) {
  return difference_at(a, b, "");
}

// --- RunJournal ---

RunJournal::RunJournal(std::filesystem::path file, std::size_t runs)
    : file_(std::move(file)), runs_(runs), done_(runs, 0) {}

RunJournal::~RunJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void RunJournal::open_for_append() {
  fd_ = ::open(file_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(fmt::format("{}: cannot open for appending: {}", file_.string(), errno_text()));
}

std::unique_ptr<RunJournal> RunJournal::create(const std::filesystem::path& file, std::size_t runs,
                                               const nlohmann::json& setup) {
  std::error_code ec;
  if (std::filesystem::exists(std::filesystem::symlink_status(file, ec))) {
    throw InputError(file, 0, "",
                     "a journal of an unfinished sweep is already there: resume that sweep, or write into another "
                     "folder (a journal is never mixed with another sweep's runs)");
  }
  const nlohmann::json header{
      {"format", kJournalFormat}, {"version", kJournalVersion}, {"runs", runs}, {"setup", setup}};
  // The whole header is written under a name of this process's own, then linked to the journal's name, which
  // fails when that name exists: of two sweeps started into one folder at the same moment (two terminals, or
  // srun starting tasks without an MPI plug-in), exactly one gets the journal, and it always has its header.
  static std::atomic<unsigned> creations{0};
  const std::filesystem::path staged = file.string() + fmt::format(".{}-{}.new", ::getpid(), creations++);
  write_file_atomically(staged, header.dump() + "\n");
  int linked = ::link(staged.c_str(), file.c_str());
  int link_errno = errno;
  if (linked != 0 && (link_errno == EPERM || link_errno == EOPNOTSUPP || link_errno == ENOSYS)) {
    // A file system without hard links: rename, exclusive only against a journal that was there before.
    std::filesystem::rename(staged, file, ec);
    linked = ec ? -1 : 0;
    link_errno = ec.value();
  }
  std::filesystem::remove(staged, ec);
  if (linked != 0) {
    if (link_errno == EEXIST) {
      throw InputError(file, 0, "",
                       "a journal of another sweep appeared while this one started: two sweeps were started into "
                       "one folder at once; this one stops (a journal is never mixed with another sweep's runs)");
    }
    throw std::runtime_error(fmt::format("{}: cannot create: {}", file.string(), std::strerror(link_errno)));
  }
  std::unique_ptr<RunJournal> journal(new RunJournal(file, runs));
  journal->open_for_append();
  return journal;
}

std::unique_ptr<RunJournal> RunJournal::resume(const std::filesystem::path& file, std::size_t runs,
                                               const nlohmann::json& setup) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) throw InputError(file, 0, "", "no journal to resume");
  if (!std::filesystem::is_regular_file(status)) throw InputError(file, 0, "", "not a regular file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, 0, "", "cannot be read: " + errno_text());

  // The setup as it reads back from text, so that numbers compare as the journal's do.
  const nlohmann::json expected = nlohmann::json::parse(setup.dump());
  std::unique_ptr<RunJournal> journal(new RunJournal(file, runs));
  std::string line;
  std::uintmax_t good_end = 0;  // bytes up to the end of the last line kept
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const bool complete = !in.eof();  // ended by '\n'
    const bool last = !complete || in.peek() == std::char_traits<char>::eof();
    nlohmann::json j;
    bool parsed = true;
    std::string why;
    try {
      j = parse_json_text(line, file);
    } catch (const InputError& e) {
      parsed = false;
      why = e.message();
    }
    if (number == 1) {
      if (!complete || !parsed) throw InputError(file, 1, "", complete ? why : "the header line is incomplete");
      check_header(file, j, expected, runs);
      good_end += line.size() + 1;
      continue;
    }
    if (last && (!complete || !parsed)) {
      // Torn by a crash mid-write: that run was in flight, it reruns.
      journal->dropped_torn_line_ = true;
      break;
    }
    if (!parsed) throw InputError(file, number, "", why);
    if (!j.is_object() || !j.contains("run") || !j.contains("data")) {
      throw InputError(file, number, "", "a run line holds {\"run\": index, \"data\": {...}}");
    }
    if (!j["run"].is_number_unsigned() || j["run"].get<std::size_t>() >= runs) {
      throw InputError(file, number, "run", fmt::format("{} is not a run index below {}", shown_json(j["run"]), runs));
    }
    const std::size_t run = j["run"].get<std::size_t>();
    if (journal->done_[run]) {
      throw InputError(file, number, "run",
                       fmt::format("run {} is recorded twice (first on line {})", run, journal->restored_[run].line));
    }
    journal->done_[run] = 1;
    ++journal->recorded_;
    journal->restored_[run] = {number, std::move(j["data"])};
    good_end += line.size() + 1;
  }
  if (in.bad()) throw std::runtime_error(fmt::format("{}: read failed: {}", file.string(), errno_text()));
  if (number == 0) throw InputError(file, 1, "", "empty: not a peg3d run journal");
  in.close();
  if (journal->dropped_torn_line_) {
    std::filesystem::resize_file(file, good_end, ec);
    if (ec) throw std::runtime_error(fmt::format("{}: cannot cut the torn last line: {}", file.string(), ec.message()));
  }
  journal->open_for_append();
  return journal;
}

std::size_t RunJournal::recorded() const {
  const std::lock_guard lock(mutex_);
  return recorded_;
}

bool RunJournal::has(std::size_t run) const {
  const std::lock_guard lock(mutex_);
  return run < runs_ && done_[run] != 0;
}

void RunJournal::restore(std::size_t run, const std::function<void(const nlohmann::json&)>& decode) const {
  const auto it = restored_.find(run);
  if (it == restored_.end()) throw std::logic_error(fmt::format("RunJournal::restore: run {} was not read back", run));
  const std::string field = fmt::format("run {}", run);
  try {
    decode(it->second.data);
  } catch (const InputError& e) {
    throw InputError(file_, it->second.line, field, e.what());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file_, it->second.line, field, fmt::format("unreadable record: {}", e.what()));
  } catch (const std::logic_error& e) {  // std::invalid_argument, std::out_of_range of the decoders
    throw InputError(file_, it->second.line, field, fmt::format("unreadable record: {}", e.what()));
  }
}

void RunJournal::release_restored() { restored_.clear(); }

void RunJournal::record(std::size_t run, const nlohmann::json& data) {
  if (run >= runs_) throw std::logic_error(fmt::format("RunJournal::record: run {} of {}", run, runs_));
  // The index first, so a reader sees which run a (long) line holds at a glance.
  const std::string line = fmt::format("{{\"run\":{},\"data\":{}}}\n", run, data.dump());
  const std::lock_guard lock(mutex_);
  if (done_[run]) throw std::logic_error(fmt::format("RunJournal::record: run {} is recorded already", run));
  const char* p = line.data();
  std::size_t left = line.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("{}: cannot append run {}: {}", file_.string(), run, errno_text()));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fdatasync(fd_) != 0) {
    throw std::runtime_error(fmt::format("{}: cannot sync run {} to the disk: {}", file_.string(), run, errno_text()));
  }
  done_[run] = 1;
  ++recorded_;
}

void RunJournal::remove() {
  const std::lock_guard lock(mutex_);
  if (fd_ >= 0) ::close(fd_), fd_ = -1;
  std::error_code ec;
  std::filesystem::remove(file_, ec);
  if (ec) throw std::runtime_error(fmt::format("{}: cannot remove: {}", file_.string(), ec.message()));
}

}  // namespace peg3d::sweep
