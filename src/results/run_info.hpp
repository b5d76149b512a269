#pragma once
// How to reproduce a sweep's results: the peg3d version that made them, the content hashes of the maps (and
// their meshes) they were played on, and the configuration and seeds. A sweep's journal header compares the
// same facts on --resume, and run_info.json (docs/results.md) keeps them beside the results.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "world/arena.hpp"

namespace peg3d::results {

/// peg3d's version number (the CMake project version).
std::string peg3d_version();
/// The git commit of the source tree when CMake last configured the build; "unknown" when it was not a git
/// checkout (or git was missing). CMake configures again whenever HEAD moves.
std::string peg3d_git_commit();
/// {"version": ..., "git_commit": ...}
nlohmann::json peg3d_build_json();

/// "fnv1a64:<16 hex digits>" of a file's bytes. Throws InputError naming the file when it cannot be read.
std::string file_content_hash(const std::filesystem::path& file);

/// Content hash of everything a map's results depend on: the bytes of the map file and of every mesh file
/// it imports, in order ("fnv1a64:..."). A map built in code (no file) is hashed by its map_to_json image.
std::string map_content_hash(const world::Arena& arena);

/// The map's file, its hash and each mesh file with its hash, for run_info.json:
/// {"file": ..., "hash": map_content_hash, "file_hash": ..., "meshes": [{"file": ..., "hash": ...}]}.
nlohmann::json map_record(const world::Arena& arena);

/// Writes run_info.json: {"format": "peg3d-run-info", "version": 1, "experiment": ..., "peg3d": {version,
/// git_commit}, "maps": [{"use": ..., map_record...}], then the fields of `details` (the experiment's
/// configuration and seeds, or the result files that hold them)}. No wall-clock value: the same sweep writes
/// the same file.
void write_run_info(const std::filesystem::path& file, const std::string& experiment,
                    const std::vector<std::pair<std::string, const world::Arena*>>& maps,
                    const nlohmann::ordered_json& details);

}  // namespace peg3d::results
