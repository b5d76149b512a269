#include "experiment/run_journal.hpp"

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
#include "experiment/distributed_sweep.hpp"
#include "experiment/process_group.hpp"
#include "game/policy_io.hpp"

namespace peg3d::experiment {
namespace {

std::string errno_text() { return std::strerror(errno); }

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

int int_from(const nlohmann::json& j) { return j.get<int>(); }

/// An enumeration stored as its value, checked against the largest one.
template <class E>
E enum_from(const nlohmann::json& j, int largest, const char* what) {
  const int v = j.get<int>();
  require(v >= 0 && v <= largest, what);
  return static_cast<E>(v);
}

Vec3 vec_from(const nlohmann::json& j, std::size_t at) {
  return {number_from_json(j.at(at)), number_from_json(j.at(at + 1)), number_from_json(j.at(at + 2))};
}

const nlohmann::json& array_of(const nlohmann::json& j, std::size_t size, const char* what) {
  require(j.is_array() && j.size() == size, what);
  return j;
}

nlohmann::json collision_to_json(const game::CollisionEvent& c) {
  return nlohmann::json::array({c.step, number_to_json(c.time), c.agent, static_cast<int>(c.role),
                                static_cast<int>(c.kind), c.obstacle_id, c.triangle, number_to_json(c.point.x()),
                                number_to_json(c.point.y()), number_to_json(c.point.z()), number_to_json(c.normal.x()),
                                number_to_json(c.normal.y()), number_to_json(c.normal.z()), number_to_json(c.fraction),
                                number_to_json(c.penetration)});
}

game::CollisionEvent collision_from_json(const nlohmann::json& j) {
  array_of(j, 15, "a collision needs 15 values");
  game::CollisionEvent c;
  c.step = int_from(j[0]);
  c.time = number_from_json(j[1]);
  c.agent = int_from(j[2]);
  c.role = enum_from<game::Role>(j[3], 1, "a role is 0 (pursuer) or 1 (evader)");
  c.kind = enum_from<world::ObstacleKind>(j[4], static_cast<int>(world::ObstacleKind::kMover), "unknown obstacle kind");
  c.obstacle_id = int_from(j[5]);
  c.triangle = int_from(j[6]);
  c.point = vec_from(j, 7);
  c.normal = vec_from(j, 10);
  c.fraction = number_from_json(j[13]);
  c.penetration = number_from_json(j[14]);
  return c;
}

nlohmann::json capture_to_json(const game::CaptureEvent& c) {
  return nlohmann::json::array({c.step, number_to_json(c.time), c.pursuer, c.evader, number_to_json(c.distance)});
}

game::CaptureEvent capture_from_json(const nlohmann::json& j) {
  array_of(j, 5, "a capture needs 5 values");
  return {int_from(j[0]), number_from_json(j[1]), int_from(j[2]), int_from(j[3]), number_from_json(j[4])};
}

// One agent at one instant: position, heading, the whole percept, the command, reward and whether in play.
constexpr std::size_t kFrameValues = 20;

nlohmann::json frame_to_json(const game::AgentFrame& f) {
  const game::Percept& q = f.percept;
  return nlohmann::json::array(
      {number_to_json(f.state.position.x()), number_to_json(f.state.position.y()), number_to_json(f.state.position.z()),
       number_to_json(f.state.heading.alpha), number_to_json(f.state.heading.theta), number_to_json(q.target_distance),
       number_to_json(q.target.azimuth), number_to_json(q.target.elevation), number_to_json(q.obstacle.distance),
       number_to_json(q.obstacle.point.x()), number_to_json(q.obstacle.point.y()), number_to_json(q.obstacle.point.z()),
       static_cast<int>(q.obstacle.found), number_to_json(q.to_obstacle.azimuth), number_to_json(q.to_obstacle.elevation),
       static_cast<int>(q.pinned), number_to_json(f.command.d_alpha), number_to_json(f.command.d_theta),
       number_to_json(f.reward), static_cast<int>(f.active)});
}

game::AgentFrame frame_from_json(const nlohmann::json& j) {
  array_of(j, kFrameValues, "a trace frame needs 20 values");
  game::AgentFrame f;
  f.state.position = vec_from(j, 0);
  f.state.heading = {number_from_json(j[3]), number_from_json(j[4])};
  game::Percept& q = f.percept;
  q.target_distance = number_from_json(j[5]);
  q.target = {number_from_json(j[6]), number_from_json(j[7])};
  q.obstacle.distance = number_from_json(j[8]);
  q.obstacle.point = vec_from(j, 9);
  q.obstacle.found = int_from(j[12]) != 0;
  q.to_obstacle = {number_from_json(j[13]), number_from_json(j[14])};
  q.pinned = int_from(j[15]) != 0;
  f.command = {number_from_json(j[16]), number_from_json(j[17])};
  f.reward = number_from_json(j[18]);
  f.active = int_from(j[19]) != 0;
  return f;
}

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
      if (!j.is_object() || !j.contains("format") || j["format"] != kJournalFormat) {
        throw InputError(file, 1, "format", fmt::format("not a peg3d run journal (expected \"{}\")", kJournalFormat));
      }
      if (!j.contains("version") || j["version"] != kJournalVersion) {
        throw InputError(file, 1, "version",
                         fmt::format("journal version {} is not supported (this peg3d reads {})",
                                     shown_json(j.contains("version") ? j["version"] : nlohmann::json()), kJournalVersion));
      }
      if (const auto d = first_difference(j.contains("setup") ? j["setup"] : nlohmann::json(), expected)) {
        throw InputError(file, 1, d->field.empty() ? "setup" : "setup." + d->field,
                         fmt::format("the journal's sweep has {}, this one {}: a journal resumes only the sweep that "
                                     "wrote it",
                                     shown_json(d->a), shown_json(d->b)));
      }
      if (!j.contains("runs") || !j["runs"].is_number_unsigned() || j["runs"].get<std::size_t>() != runs) {
        throw InputError(file, 1, "runs",
                         fmt::format("the journal's sweep has {} runs, this one {}", shown_json(j["runs"]), runs));
      }
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

// --- the sweep ---

SweepInterrupted::SweepInterrupted(std::size_t kept, std::size_t total, std::filesystem::path journal)
    : std::runtime_error(fmt::format("sweep interrupted: {} of {} runs finished", kept, total)),
      kept_(kept),
      total_(total),
      journal_(std::move(journal)) {}

void run_journaled(std::size_t count, int threads, const SweepControl& control,
                   const std::function<void(std::size_t)>& run,
                   const std::function<nlohmann::json(std::size_t)>& encode,
                   const std::function<void(std::size_t, const nlohmann::json&)>& restore) {
  RunJournal* journal = control.journal;
  const bool distributed = control.group && control.group->size() > 1;
  if (journal && distributed && !control.group->is_root()) {
    throw std::logic_error("run_journaled: only the root of a process group keeps the journal");
  }
  if (journal && journal->runs() != count) {
    throw std::logic_error(fmt::format("run_journaled: the journal plans {} runs, the sweep {}", journal->runs(), count));
  }
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < count; ++i) {
    if (journal && journal->has(i)) {
      journal->restore(i, [&](const nlohmann::json& data) { restore(i, data); });
    } else {
      todo.push_back(i);
    }
  }
  if (journal) journal->release_restored();

  if (distributed) {
    const DistributedOutcome outcome = run_distributed(todo, threads, control, run, encode, restore);
    if (!control.group->is_root()) {
      if (outcome.stopped) throw SweepInterrupted(outcome.finished, count, {});
      return;
    }
    if (outcome.finished < todo.size()) {
      throw SweepInterrupted(journal ? journal->recorded() : count - todo.size() + outcome.finished, count,
                             journal ? journal->file() : std::filesystem::path());
    }
    return;
  }

  std::atomic<std::size_t> finished{0};
  run_indexed(
      todo.size(), threads,
      [&](std::size_t k) {
        const std::size_t i = todo[k];
        try {
          run(i);
        } catch (const RunCancelled&) {
          return;  // dropped: it reruns on resume
        }
        if (journal) journal->record(i, encode(i));
        finished.fetch_add(1, std::memory_order_relaxed);
      },
      control.stop);
  if (finished.load() < todo.size()) {
    throw SweepInterrupted(journal ? journal->recorded() : finished.load(), count,
                           journal ? journal->file() : std::filesystem::path());
  }
}

// --- codecs ---

nlohmann::json number_to_json(double v) {
  if (std::isfinite(v)) return v;
  if (std::isnan(v)) return std::signbit(v) ? "-nan" : "nan";
  return v > 0.0 ? "inf" : "-inf";
}

double number_from_json(const nlohmann::json& j) {
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    constexpr double kInf = std::numeric_limits<double>::infinity();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "-nan") return -std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return kInf;
    if (s == "-inf") return -kInf;
  }
  throw std::invalid_argument("expected a number, got " + brief(j));
}

nlohmann::json episode_to_json(const game::EpisodeResult& e) {
  return nlohmann::json::array(
      {static_cast<int>(e.outcome), e.steps, number_to_json(e.duration), number_to_json(e.final_distance),
       number_to_json(e.pursuer_path), number_to_json(e.evader_path), e.collisions,
       e.first_collision ? collision_to_json(*e.first_collision) : nlohmann::json(nullptr),
       number_to_json(e.pursuer_return), number_to_json(e.evader_return), e.pursuer_pinned_steps,
       e.evader_pinned_steps, e.pursuer_agent_steps, e.evader_agent_steps, e.pursuers, e.evaders, e.captures,
       number_to_json(e.capture_time_sum), number_to_json(e.last_capture_time)});
}

game::EpisodeResult episode_from_json(const nlohmann::json& j) {
  array_of(j, 19, "an episode needs 19 values");
  game::EpisodeResult e;
  e.outcome = enum_from<game::Outcome>(j[0], static_cast<int>(game::Outcome::kEvaderCollision), "unknown outcome");
  e.steps = int_from(j[1]);
  e.duration = number_from_json(j[2]);
  e.final_distance = number_from_json(j[3]);
  e.pursuer_path = number_from_json(j[4]);
  e.evader_path = number_from_json(j[5]);
  e.collisions = int_from(j[6]);
  if (!j[7].is_null()) e.first_collision = collision_from_json(j[7]);
  e.pursuer_return = number_from_json(j[8]);
  e.evader_return = number_from_json(j[9]);
  e.pursuer_pinned_steps = int_from(j[10]);
  e.evader_pinned_steps = int_from(j[11]);
  e.pursuer_agent_steps = int_from(j[12]);
  e.evader_agent_steps = int_from(j[13]);
  e.pursuers = int_from(j[14]);
  e.evaders = int_from(j[15]);
  e.captures = int_from(j[16]);
  e.capture_time_sum = number_from_json(j[17]);
  e.last_capture_time = number_from_json(j[18]);
  return e;
}

nlohmann::json episodes_to_json(const std::vector<game::EpisodeResult>& episodes) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : episodes) out.push_back(episode_to_json(e));
  return out;
}

std::vector<game::EpisodeResult> episodes_from_json(const nlohmann::json& j) {
  require(j.is_array(), "expected a list of episodes");
  std::vector<game::EpisodeResult> out;
  out.reserve(j.size());
  for (const auto& e : j) out.push_back(episode_from_json(e));
  return out;
}

nlohmann::json agent_summary_to_json(const game::AgentSummary& a) {
  return nlohmann::json::array({static_cast<int>(a.role), a.rank, number_to_json(a.path), number_to_json(a.total_reward),
                                a.steps, number_to_json(a.pinned_fraction), a.collisions, a.captures,
                                number_to_json(a.captured_at)});
}

game::AgentSummary agent_summary_from_json(const nlohmann::json& j) {
  array_of(j, 9, "an agent summary needs 9 values");
  game::AgentSummary a;
  a.role = enum_from<game::Role>(j[0], 1, "a role is 0 (pursuer) or 1 (evader)");
  a.rank = int_from(j[1]);
  a.path = number_from_json(j[2]);
  a.total_reward = number_from_json(j[3]);
  a.steps = int_from(j[4]);
  a.pinned_fraction = number_from_json(j[5]);
  a.collisions = int_from(j[6]);
  a.captures = int_from(j[7]);
  a.captured_at = number_from_json(j[8]);
  return a;
}

nlohmann::json trace_to_json(const game::Trace& t) {
  nlohmann::json roles = nlohmann::json::array(), times = nlohmann::json::array(), frames = nlohmann::json::array(),
                 collisions = nlohmann::json::array(), captures = nlohmann::json::array();
  for (const game::Role r : t.roles) roles.push_back(static_cast<int>(r));
  for (const double v : t.times) times.push_back(number_to_json(v));
  for (const game::AgentFrame& f : t.frames) frames.push_back(frame_to_json(f));
  for (const auto& c : t.collisions) collisions.push_back(collision_to_json(c));
  for (const auto& c : t.captures) captures.push_back(capture_to_json(c));
  return {{"agents", t.agents}, {"roles", std::move(roles)},           {"times", std::move(times)},
          {"frames", std::move(frames)}, {"collisions", std::move(collisions)}, {"captures", std::move(captures)}};
}

game::Trace trace_from_json(const nlohmann::json& j) {
  game::Trace t;
  t.agents = int_from(j.at("agents"));
  require(t.agents >= 0, "a trace's agent count is >= 0");
  const auto& roles = array_of(j.at("roles"), static_cast<std::size_t>(t.agents), "a trace needs one role per agent");
  for (const auto& r : roles) t.roles.push_back(enum_from<game::Role>(r, 1, "a role is 0 (pursuer) or 1 (evader)"));
  require(j.at("times").is_array(), "a trace's times are a list");
  for (const auto& v : j.at("times")) t.times.push_back(number_from_json(v));
  array_of(j.at("frames"), t.times.size() * static_cast<std::size_t>(t.agents), "a trace needs one frame per time and agent");
  t.frames.reserve(j.at("frames").size());
  for (const auto& f : j.at("frames")) t.frames.push_back(frame_from_json(f));
  require(j.at("collisions").is_array() && j.at("captures").is_array(), "a trace's events are lists");
  for (const auto& c : j.at("collisions")) t.collisions.push_back(collision_from_json(c));
  for (const auto& c : j.at("captures")) t.captures.push_back(capture_from_json(c));
  return t;
}

nlohmann::json role_models_to_json(const game::RoleModels& m) {
  nlohmann::json models = nlohmann::json::array();
  for (const auto& model : m.models) models.push_back(game::policy_to_json(*model));
  return {{"models", std::move(models)}, {"of_agent", m.of_agent}};
}

game::RoleModels role_models_from_json(const nlohmann::json& j, game::Role role) {
  game::RoleModels m;
  require(j.at("models").is_array(), "a role's models are a list");
  for (const auto& doc : j.at("models")) m.models.push_back(game::policy_from_json(doc, {}, role));
  m.of_agent = j.at("of_agent").get<std::vector<int>>();
  for (const int k : m.of_agent) require(k >= -1 && k < static_cast<int>(m.models.size()), "a model index out of range");
  return m;
}

}  // namespace peg3d::experiment
