#pragma once
// JSON codecs of what runs produce: episodes, agent summaries, traces and trained models. They are exact to
// the bit for finite doubles (shortest round-trip text) and keep NaN and infinities (as the strings "nan",
// "-nan", "inf", "-inf"), so that a run read back from a journal, or received from another rank, is the run
// that was computed (sweep/run_journal.hpp, sweep/distributed_sweep.hpp). Decoders throw nlohmann::json
// exceptions or std::invalid_argument on malformed input (RunJournal::restore turns them into InputErrors).

#include <vector>

#include <nlohmann/json.hpp>

#include "game/episode.hpp"
#include "players/lineup.hpp"

namespace peg3d::results {

nlohmann::json number_to_json(double v);
double number_from_json(const nlohmann::json& j);

nlohmann::json episode_to_json(const game::EpisodeResult& e);
game::EpisodeResult episode_from_json(const nlohmann::json& j);
nlohmann::json episodes_to_json(const std::vector<game::EpisodeResult>& episodes);
std::vector<game::EpisodeResult> episodes_from_json(const nlohmann::json& j);

nlohmann::json agent_summary_to_json(const game::AgentSummary& a);
game::AgentSummary agent_summary_from_json(const nlohmann::json& j);

/// Every frame, collision and capture of a trace.
nlohmann::json trace_to_json(const game::Trace& t);
game::Trace trace_from_json(const nlohmann::json& j);

/// A role's trained models (policy documents, players/policy_io.hpp) and which one each agent plays. Decoding
/// rebuilds each model; a model of the other role is an error.
nlohmann::json role_models_to_json(const players::RoleModels& m);
players::RoleModels role_models_from_json(const nlohmann::json& j, game::Role role);

}  // namespace peg3d::results
