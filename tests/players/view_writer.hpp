#pragma once
// A stand-in for the game's ObservationWriter (game/observation.hpp) in unit tests of players that read an
// observation: it writes a hand-made view's base entries and, where the table has them, its sight entries, and
// binds any recorded table as it is. Tests of the real feed against the batch are in tests/python/test_policy_feed.py.

#include <span>

#include "game/observation.hpp"

namespace peg3d::testing {

class ViewWriter final : public game::ObservationWriter {
 public:
  /// Writes `view`, which must outlive it; attach it with view.observation = &writer.
  explicit ViewWriter(const game::AgentView& view) : view_(&view) {}
  void write(int, const game::ObservationTable& table, std::span<float> out) const override {
    game::observation_base(*view_, out.data());
    for (const sense::Segment& s : table.segments) {
      if (s.name == "sight.visible") out[std::size_t(s.offset)] = view_->other_visible ? 1.0f : 0.0f;
      if (s.name == "sight.age") out[std::size_t(s.offset)] = float(view_->other_age);
    }
  }
  game::ObservationTable bind(int, std::span<const sense::Segment> recorded) const override {
    game::ObservationTable t;
    t.segments.assign(recorded.begin(), recorded.end());
    return t;
  }
  const void* model() const override { return this; }

 private:
  const game::AgentView* view_;
};

/// `view` with a writer of its own attached (kept beside it).
struct WrittenView {
  game::AgentView view;
  ViewWriter writer{view};
  WrittenView() { view.observation = &writer; }
  explicit WrittenView(const game::AgentView& v) : view(v) { view.observation = &writer; }
  WrittenView(const WrittenView& other) : WrittenView(other.view) {}
};

}  // namespace peg3d::testing
