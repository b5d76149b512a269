#pragma once

// A policy played as no classic player is (game::Policy::scripted false): the game keeps its agent's motion space,
// whatever player it wraps. Tests use it to hold a classic player, or random steering, to the motion space.

#include <memory>
#include <utility>

#include "game/policy.hpp"

namespace peg3d::testing {

class Unscripted final : public game::Policy {
 public:
  explicit Unscripted(std::unique_ptr<game::Policy> inner) : inner_(std::move(inner)) {}
  void begin_episode(const game::AgentView& view, bool learning) override { inner_->begin_episode(view, learning); }
  Steering act(const game::AgentView& view) override { return inner_->act(view); }

 private:
  std::unique_ptr<game::Policy> inner_;
};

}  // namespace peg3d::testing
