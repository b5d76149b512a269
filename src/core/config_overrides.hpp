#pragma once
// `--set key=value` overrides of configuration fields. A configuration is the nlohmann::json image of a
// config struct (its to_json); an override replaces one existing leaf, checked against the leaf's current
// type, and the struct is rebuilt with from_json. Unknown keys are errors, never silently added: a typo in
// a sweep must stop the run, not run the default.

#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/config_json.hpp"  // ConfigError

namespace peg3d::config {


/// Applies one "a.b.c=value" assignment to `config` (a JSON object), replacing the existing leaf a.b.c.
/// - Path: dot-separated object keys; an array element is addressed by its index ("agents.0.speed").
///   Every key must exist already.
/// - Value: parsed as JSON when it parses (3, -1.5, 1e3, true, [1,2], "quoted"), else taken as the raw
///   string. When the leaf is a string, unparsable or non-string text is kept verbatim (name=123 sets
///   "123"). When the leaf is a list of strings (names), text that is not a JSON list is split at commas
///   (pool.evaders=flee,random sets ["flee", "random"]; an empty value empties it).
/// - Type: the new value must have the old one's JSON type. Integers and floats are interchangeable, except
///   that an integer leaf only accepts integral values (2.0 or 2e3, not 2.5) and an unsigned leaf no
///   negative ones; an integer written into a float leaf is stored as a float. Array elements are checked
///   the same way against the old array's first element. A null leaf (an unset optional) accepts any value.
///   A leaf that is an object (a whole section) cannot be replaced: set its keys one by one.
/// Throws ConfigError on a missing '=', an empty or unknown key, or a type mismatch; `config` is unchanged
/// then.
void apply_override(nlohmann::json& config, std::string_view assignment);

/// apply_override for each assignment in order (later ones win).
void apply_overrides(nlohmann::json& config, std::span<const std::string> assignments);

/// Every leaf of `config` as a "dotted.key=value" line, sorted by key, for writing the effective
/// configuration next to the results. Values print as apply_override reads them back: strings verbatim
/// (JSON-quoted only when they contain a control character such as a newline), numbers and booleans as
/// JSON (floats keep a ".0": 1.0, shortest round-trip digits otherwise), null as null. Arrays of scalars
/// print as one JSON value ([1,2]); arrays holding objects or arrays are flattened by index (agents.0.x).
/// Empty objects and arrays print as {} and [].
std::vector<std::string> flatten(const nlohmann::json& config);

}  // namespace peg3d::config
