#pragma once

// One hash of everything a role's FACL agents learned (every model's actor and critic tables), for tests that compare
// trainings.

#include <cstdint>

#include "core/hash.hpp"
#include "players/lineup.hpp"

namespace peg3d::testing {

inline std::uint64_t tables_hash(const players::RoleModels& models) {
  Fnv1a h;
  for (const auto& m : models.models) {
    for (int c = 0; c < m->channels(); ++c) {
      h.add_span(m->tables(c).actor_table());
      h.add_span(m->tables(c).critic_table());
    }
  }
  return h.value();
}

}  // namespace peg3d::testing
