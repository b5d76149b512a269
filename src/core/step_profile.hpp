#pragma once
// Where a training step's time goes, for peg-throughput (docs/performance.md). The hot loop marks its parts
// with StepProfile::Scope; a thread that wants the breakdown installs a StepProfile for itself, every other
// thread pays one thread-local load and a predictable branch per scope. Times are in time-stamp-counter
// ticks (rdtsc, a few nanoseconds to read), converted to nanoseconds by whoever reads them against a clock.
// A scope opened inside another (an agent's map queried while its observation is made) counts its time to its
// own part only: the enclosing one's part gets its time less that of the scopes within it.

#include <array>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#else
#include <chrono>
#endif

namespace peg3d {

class StepProfile {
 public:
  /// The parts of a step and of the learners around it.
  enum Part : int {
    kConstraints,  ///< bounded steering, motion space, obstacle guard
    kCollisions,   ///< swept collisions with the map's obstacles and between agents (Bullet)
    kMovers,       ///< moving obstacles: contacts on their timeline, the octree that follows them
    kSensing,      ///< sensors reading the world: casting their rays, noise and dropout
    kMapInsert,    ///< agents' own maps: inserting each scan
    kMapQuery,     ///< agents' own maps: their nearest occupied cells (inputs, guard, rewards)
    kSight,        ///< limited sight: sight tests of the opponents
    kObservation,  ///< percepts: opponents, distance-field queries, angle errors
    kRewards,      ///< the reward terms
    kFiring,       ///< fuzzy rule firing of the learners
    kActorCritic,  ///< the actor's output with exploration noise
    kLearning,     ///< the TD update of actor and critic
    kPartCount
  };
  static const char* name(Part p);

  /// A tick of the time-stamp counter (elsewhere a steady-clock nanosecond).
  static std::uint64_t now() {
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc();
#else
    return std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
  }

  std::array<std::uint64_t, kPartCount> ticks{};

  /// The profile the calling thread records into (null: none).
  static StepProfile*& current() {
    // initial-exec: the library is linked into executables, where this is one fs-relative load.
    static thread_local StepProfile* p __attribute__((tls_model("initial-exec"))) = nullptr;
    return p;
  }

  /// Adds the time from construction to destruction to `part` of the thread's profile, if it has one, less the
  /// time of the scopes opened within it.
  class Scope {
   public:
    explicit Scope(Part part) : profile_(current()), part_(part) {
      if (profile_ != nullptr) {
        outer_ = profile_->open_;
        profile_->open_ = this;
        start_ = now();
      }
    }
    ~Scope() {
      if (profile_ == nullptr) return;
      const std::uint64_t spent = now() - start_;
      profile_->ticks[std::size_t(part_)] += spent - inner_;
      if (outer_ != nullptr) outer_->inner_ += spent;
      profile_->open_ = outer_;
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StepProfile* profile_;
    Part part_;
    std::uint64_t start_ = 0;
    std::uint64_t inner_ = 0;  // ticks of the scopes opened within this one
    Scope* outer_ = nullptr;   // the scope this one was opened in
  };

 private:
  Scope* open_ = nullptr;  // the innermost open scope
};

inline const char* StepProfile::name(Part p) {
  switch (p) {
    case kConstraints: return "constraints";
    case kCollisions: return "collisions";
    case kMovers: return "movers";
    case kSensing: return "sensing_cast";
    case kMapInsert: return "sensing_integrate";
    case kMapQuery: return "sensing_query";
    case kSight: return "sight";
    case kObservation: return "observation";
    case kRewards: return "rewards";
    case kFiring: return "firing";
    case kActorCritic: return "actor_critic";
    case kLearning: return "learning";
    case kPartCount: break;
  }
  return "?";
}

}  // namespace peg3d
