#pragma once
// One table of fields per configuration struct. A struct T lists its fields once, in a function template
//
//   template <class V, class C> requires same_as<remove_const_t<C>, T>
//   void visit_fields(V& v, C& c) {
//     v.number("actor_rate", c.actor_rate, Range::open_closed(0, 1), "", "alpha_a, the actor's learning rate");
//     v.choice("reading", c.reading, kReadingNames, "how max_turn is read");
//     v.name("policy", c.policy, "a player (--list-players)", "who drives the agent");   // a word, checked elsewhere
//     v.names("pursuers", c.pursuers, "players (--list-players)", "the pool's pursuers");  // a list of words
//     v.section("facl", c.facl, "the learner");
//     v.require(c.hi > c.lo, "hi", c.hi, "must be > lo");   // a rule between fields
//   }
//
// and every generic operation is a visitor walking that table: validation (config::validate, here),
// JSON in and out (core/config_json.hpp, which `--set` and `flatten` work on), the field listing behind
// `--list-config`, and a field count that tests compare with the struct's member count, so a member the
// table forgets is a failing test rather than a silently unsaved setting.
//
// A visitor provides number, integer, flag, choice, name, names, section, sections, embed and require with the
// signatures the Validator below shows. `embed` lists another struct's fields at this level, as if they were the
// struct's own (an agent's sensors' sections sit beside its other sections). A name is a word a table elsewhere gives the meaning of (a player's name,
// from players/registry.hpp): the table here checks only that it is a word; its user checks that it is known. Keys are plain words; nested fields are addressed "section.key" and list
// elements "list.3.key", the same paths `--set` takes.

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/validation.hpp"

namespace peg3d::config {

/// The longest name (Validator::name) and the most names in a list (Validator::names).
inline constexpr std::size_t kMaxNameLength = 64;
inline constexpr std::size_t kMaxNames = 64;
/// Whether `text` is a name: 1 to kMaxNameLength characters of a-z, 0-9, '-' and '_'.
bool is_name(std::string_view text);

/// The valid values of a number: an interval of finite reals, each end open or closed.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static constexpr Range any() { return {}; }
  static constexpr Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static constexpr Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static constexpr Range closed(double a, double b) { return {a, b, false, false}; }
  static constexpr Range open_closed(double a, double b) { return {a, b, true, false}; }
  static constexpr Range closed_open(double a, double b) { return {a, b, false, true}; }

  /// Finite and inside the interval.
  bool contains(double v) const;
  /// "> 0", ">= 0", "in (0, 1]", "finite" ...: how messages and listings state the range.
  std::string text() const;
};

/// One name of an enumeration, as configuration files and `--set` spell it.
template <class E>
struct EnumName {
  E value;
  const char* name;
};

/// The name table of an enumeration: every value once, with its name.
template <class E, std::size_t N>
using EnumNames = std::array<EnumName<E>, N>;

/// The name of `value` in `names` ("?" when missing, which a complete table never is).
template <class E, std::size_t N>
const char* enum_name(const EnumNames<E, N>& names, E value) {
  for (const auto& n : names)
    if (n.value == value) return n.name;
  return "?";
}

/// "a, b, c": the valid names, for messages.
template <class E, std::size_t N>
std::string enum_choices(const EnumNames<E, N>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + std::string(n.name);
  return out;
}

/// The value called `name`, or nullptr.
template <class E, std::size_t N>
const E* enum_value(const EnumNames<E, N>& names, std::string_view name) {
  for (const auto& n : names)
    if (name == n.name) return &n.value;
  return nullptr;
}

/// The most entries a list of sections may hold. The lists are per-agent settings, and a role has at most 256
/// agents (world::kMaxAgentsPerRole): more could never be used, and a small file of empty entries would
/// otherwise grow into gigabytes of copied settings.
inline constexpr std::size_t kMaxSections = 256;

/// Checks every field of a configuration against its table: ranges, enumerations, and the rules between
/// fields. Throws InvalidParameter naming the dotted field, e.g. "pursuer.facl.actor_rate".
class Validator {
 public:
  explicit Validator(std::string prefix = {}) : prefix_(std::move(prefix)) {}

  void number(const char* key, const double& value, Range range, const char* unit, const char* doc);
  void integer(const char* key, const int& value, long long lo, long long hi, const char* unit, const char* doc);
  void flag(const char*, const bool&, const char*) {}
  template <class E, std::size_t N>
  void choice(const char* key, const E& value, const EnumNames<E, N>& names, const char* doc);
  void name(const char* key, const std::string& value, const char* valid, const char* doc);
  void names(const char* key, const std::vector<std::string>& value, const char* valid, const char* doc);
  template <class S>
  void section(const char* key, const S& value, const char* doc);
  template <class S>
  void sections(const char* key, const std::vector<S>& values, const S& element_default, const char* doc);
  template <class S>
  void embed(const S& value) {
    visit_fields(*this, value);
  }
  void require(bool ok, std::string_view key, double value, const char* requirement) const;
  void require(bool ok, std::string_view key, std::string_view value, const char* requirement) const;

  std::string field(std::string_view key) const { return prefix_ + std::string(key); }

 private:
  std::string prefix_;
};

/// Validates `c` by its table; `prefix` is prepended to field names ("pursuer." for an agent).
template <class T>
void validate(const T& c, std::string prefix = {}) {
  Validator v(std::move(prefix));
  visit_fields(v, c);
}

/// Counts the fields a table lists at its own level (not inside sections). Tests compare the count with the
/// struct's number of members (config::member_count) so that no member is left out of the table.
struct FieldCounter {
  int count = 0;
  template <class... A>
  void number(A&&...) { ++count; }
  template <class... A>
  void integer(A&&...) { ++count; }
  template <class... A>
  void flag(A&&...) { ++count; }
  template <class... A>
  void choice(A&&...) { ++count; }
  template <class... A>
  void name(A&&...) { ++count; }
  template <class... A>
  void names(A&&...) { ++count; }
  template <class... A>
  void section(A&&...) { ++count; }
  template <class... A>
  void sections(A&&...) { ++count; }
  template <class... A>
  void embed(A&&...) { ++count; }  // one member, whose own table is counted by its own test
  template <class... A>
  void require(A&&...) {}
};

template <class T>
int table_field_count() {
  FieldCounter counter;
  const T value{};
  visit_fields(counter, value);
  return counter.count;
}

namespace detail {
struct AnyField {
  template <class U>
  operator U() const;  // never defined: used in unevaluated aggregate initialisation only
};
template <class T, std::size_t... I>
constexpr bool initializable(std::index_sequence<I...>) {
  return requires { T{(static_cast<void>(I), AnyField{})...}; };
}
template <class T, std::size_t N>
constexpr std::size_t member_count_from() {
  if constexpr (N > 64) {
    return N;
  } else if constexpr (initializable<T>(std::make_index_sequence<N + 1>{})) {
    return member_count_from<T, N + 1>();
  } else {
    return N;
  }
}
}  // namespace detail

/// Number of members of an aggregate struct (the largest brace initialiser it accepts).
template <class T>
constexpr std::size_t member_count() {
  static_assert(std::is_aggregate_v<T>, "configuration structs are aggregates");
  return detail::member_count_from<T, 0>();
}

// ---- Validator members that are templates ----

template <class E, std::size_t N>
void Validator::choice(const char* key, const E& value, const EnumNames<E, N>& names, const char*) {
  for (const auto& n : names)
    if (n.value == value) return;
  throw InvalidParameter(field(key), std::to_string(static_cast<long long>(value)),
                         "must be one of: " + enum_choices(names));
}

template <class S>
void Validator::section(const char* key, const S& value, const char*) {
  Validator sub(prefix_ + key + ".");
  visit_fields(sub, value);
}

template <class S>
void Validator::sections(const char* key, const std::vector<S>& values, const S&, const char*) {
  require(values.size() <= kMaxSections, key, double(values.size()), "must list at most 256 entries, one per agent");
  for (std::size_t i = 0; i < values.size(); ++i) {
    Validator sub(prefix_ + key + "." + std::to_string(i) + ".");
    visit_fields(sub, values[i]);
  }
}

}  // namespace peg3d::config
