#pragma once
// The JSON image of a configuration, driven by its field table (core/config_fields.hpp): to_json writes every
// field; from_json reads a document back, rejecting unknown keys and wrong types with an error that names
// the file and the dotted field. `--set key=value` and `flatten` (core/config_overrides.hpp) work on this
// image, so the command line, configuration files, saved policies and result files all agree on one set of
// names.

#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/config_fields.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"

namespace peg3d::config {

/// A configuration document or override that cannot be applied; what() names the file (when there is one)
/// and the dotted key.
class ConfigError : public InputError {
 public:
  using InputError::InputError;
  /// The dotted key the error is about (its field()).
  const std::string& key() const noexcept { return field(); }
};

/// How from_json reads.
struct ReadOptions {
  std::filesystem::path file;  ///< named in error messages (empty: none)
  bool complete = false;       ///< every field must be present (saved documents); else absent ones keep c's value
  std::string_view text = {};  ///< the document's source text, for the line of an error (empty: no line)
  /// The line of `field` in `text` (0 when unknown).
  int line_of(const std::string& field) const;
};

/// Writes each field of a table into a JSON object.
class JsonWriter {
 public:
  explicit JsonWriter(nlohmann::json& out) : out_(out) { out_ = nlohmann::json::object(); }

  void number(const char* key, const double& v, Range, const char*, const char*) { out_[key] = v; }
  void integer(const char* key, const int& v, long long, long long, const char*, const char*) { out_[key] = v; }
  void flag(const char* key, const bool& v, const char*) { out_[key] = v; }
  template <class E, std::size_t N>
  void choice(const char* key, const E& v, const EnumNames<E, N>& names, const char*) {
    out_[key] = enum_name(names, v);
  }
  void name(const char* key, const std::string& v, const char*, const char*) { out_[key] = v; }
  void names(const char* key, const std::vector<std::string>& v, const char*, const char*) { out_[key] = v; }
  template <class S>
  void section(const char* key, const S& v, const char*) {
    JsonWriter sub(out_[key]);
    visit_fields(sub, v);
  }
  template <class S>
  void sections(const char* key, const std::vector<S>& v, const S&, const char*) {
    nlohmann::json& list = out_[key] = nlohmann::json::array();
    for (const S& element : v) {
      nlohmann::json item;
      JsonWriter sub(item);
      visit_fields(sub, element);
      list.push_back(std::move(item));
    }
  }
  template <class S>
  void embed(const S& v) {
    visit_fields(*this, v);
  }
  template <class... A>
  void require(A&&...) {}

 private:
  nlohmann::json& out_;
};

/// Reads the fields of a table from a JSON object. finish() rejects the keys no field took.
class JsonReader {
 public:
  JsonReader(const nlohmann::json& in, std::string prefix, const ReadOptions& options);

  void number(const char* key, double& v, Range, const char*, const char*);
  void integer(const char* key, int& v, long long, long long, const char*, const char*);
  void flag(const char* key, bool& v, const char*);
  void name(const char* key, std::string& v, const char* valid, const char*);
  void names(const char* key, std::vector<std::string>& v, const char* valid, const char*);
  template <class E, std::size_t N>
  void choice(const char* key, E& v, const EnumNames<E, N>& names, const char*) {
    const nlohmann::json* j = take(key);
    if (j == nullptr) return;
    if (!j->is_string()) fail(key, "expects one of: " + enum_choices(names) + "; got " + brief(*j));
    const auto& text = j->get_ref<const std::string&>();
    const E* value = enum_value(names, text);
    if (value == nullptr) fail(key, brief(*j) + " is not one of: " + enum_choices(names));
    v = *value;
  }
  template <class S>
  void section(const char* key, S& v, const char*) {
    const nlohmann::json* j = take(key);
    if (j == nullptr) return;
    if (!j->is_object()) fail(key, "expects a section {...}, got " + brief(*j));
    JsonReader sub(*j, field(key) + ".", options_);
    visit_fields(sub, v);
    sub.finish();
  }
  template <class S>
  void sections(const char* key, std::vector<S>& v, const S& element_default, const char*) {
    const nlohmann::json* j = take(key);
    if (j == nullptr) return;
    if (!j->is_array()) fail(key, "expects a list [...], got " + brief(*j));
    if (j->size() > kMaxSections) {
      fail(key, "lists " + std::to_string(j->size()) + " entries, more than 256: one per agent of a role, and a role has at "
                "most 256 agents");
    }
    std::vector<S> out;
    for (std::size_t i = 0; i < j->size(); ++i) {
      const std::string element = field(key) + "." + std::to_string(i);
      if (!(*j)[i].is_object()) throw ConfigError(options_.file, options_.line_of(element), element, "expects a section {...}");
      S item = element_default;
      // Elements start from the default and change what they list, so they are never "complete".
      ReadOptions partial = options_;
      partial.complete = false;
      JsonReader sub((*j)[i], element + ".", partial);
      visit_fields(sub, item);
      sub.finish();
      out.push_back(std::move(item));
    }
    v = std::move(out);
  }
  template <class S>
  void embed(S& v) {
    visit_fields(*this, v);
  }
  template <class... A>
  void require(A&&...) {}

  /// Throws ConfigError for the first key of the object that no field took (or for a non-object).
  void finish() const;

 private:
  const nlohmann::json* take(const char* key);
  [[noreturn]] void fail(const char* key, const std::string& message) const;
  std::string field(const char* key) const { return prefix_ + key; }

  const nlohmann::json& in_;
  std::string prefix_;
  const ReadOptions& options_;
  std::vector<std::string> taken_;
};

/// The JSON image of a configuration.
template <class T>
nlohmann::json to_json(const T& c) {
  nlohmann::json j;
  JsonWriter w(j);
  visit_fields(w, c);
  return j;
}

/// Reads `j` (an object) into `c`. Throws ConfigError naming the file and field for unknown keys, wrong types
/// and (with options.complete) missing fields. Values are not range-checked: call config::validate.
template <class T>
void from_json(const nlohmann::json& j, T& c, const ReadOptions& options = {}) {
  if (!j.is_object()) throw ConfigError(options.file, 0, "", "expects a JSON object {...}, got " + brief(j));
  JsonReader r(j, "", options);
  visit_fields(r, c);
  r.finish();
}

/// Reads a configuration file (JSON, through read_input_file's bounds) over `c`, then calls `check(c)`
/// (config::validate and any rule of the caller's). ConfigError names the file, line and field of a key that does
/// not fit; an InvalidParameter from the check comes back as an InputError naming the file and the field's line.
template <class T, class Check>
void read_config_file(const std::filesystem::path& file, T& c, const Check& check) {
  const std::string text = read_input_file(file, "configuration file");
  const nlohmann::json j = parse_json_text(text, file);
  from_json(j, c, {file, false, text});
  try {
    check(c);
  } catch (const InvalidParameter& e) {
    throw InputError(file, json_line_of(text, e.parameter()), e.parameter(), e.message());
  }
}

/// One row of a field listing (`--list-config`).
struct FieldInfo {
  std::string key;    ///< dotted path, as `--set` takes it
  std::string kind;   ///< number, integer, flag, choice, name, names, list
  std::string unit;   ///< m, s, rad, ...; empty when none
  std::string valid;  ///< the range or the choices
  std::string value;  ///< the value in the listed configuration
  std::string doc;    ///< what the field means
};

/// Lists the fields of a table with their current values.
class FieldLister {
 public:
  FieldLister(std::vector<FieldInfo>& out, std::string prefix) : out_(out), prefix_(std::move(prefix)) {}

  void number(const char* key, const double& v, Range r, const char* unit, const char* doc);
  void integer(const char* key, const int& v, long long lo, long long hi, const char* unit, const char* doc);
  void flag(const char* key, const bool& v, const char* doc);
  template <class E, std::size_t N>
  void choice(const char* key, const E& v, const EnumNames<E, N>& names, const char* doc) {
    out_.push_back({prefix_ + key, "choice", "", enum_choices(names), enum_name(names, v), doc});
  }
  void name(const char* key, const std::string& v, const char* valid, const char* doc);
  void names(const char* key, const std::vector<std::string>& v, const char* valid, const char* doc);
  template <class S>
  void section(const char* key, const S& v, const char*) {
    FieldLister sub(out_, prefix_ + key + ".");
    visit_fields(sub, v);
  }
  template <class S>
  void sections(const char* key, const std::vector<S>& v, const S&, const char* doc) {
    out_.push_back({prefix_ + key, "list", "", "", std::to_string(v.size()) + " entries", doc});
    for (std::size_t i = 0; i < v.size(); ++i) {
      FieldLister sub(out_, prefix_ + key + "." + std::to_string(i) + ".");
      visit_fields(sub, v[i]);
    }
  }
  template <class S>
  void embed(const S& v) {
    visit_fields(*this, v);
  }
  template <class... A>
  void require(A&&...) {}

 private:
  std::vector<FieldInfo>& out_;
  std::string prefix_;
};

template <class T>
std::vector<FieldInfo> list_fields(const T& c) {
  std::vector<FieldInfo> out;
  FieldLister l(out, "");
  visit_fields(l, c);
  return out;
}

/// The listing as an aligned text table, one field per line.
std::string format_field_list(const std::vector<FieldInfo>& fields);

}  // namespace peg3d::config
