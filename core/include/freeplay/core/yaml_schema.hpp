#pragma once
// Declarative validation of YAML documents: every problem is reported with file:line:column, key path and
// the allowed values, all at once, before anything runs.

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/error.hpp"

namespace freeplay {

/// A parsed YAML document and the name of the file it came from.
struct YamlDocument {
  std::string file;   ///< path as given by the user (used in error messages)
  YAML::Node root;    ///< the document's root node
};

/// Parses a YAML file; syntax errors become InputError with file:line:column.
YamlDocument load_yaml_file(const std::filesystem::path& path);
/// Parses YAML text (`file` names it in errors).
YamlDocument parse_yaml(const std::string& text, const std::string& file);

/// The 1-based location of a node in its file.
SourceLocation location_of(const YAML::Node& node, const std::string& file);

/// Every problem found while validating one document.
class ValidationErrors {
 public:
  /// Records one problem.
  void add(InputError error) { errors_.push_back(std::move(error)); }
  /// True when nothing was recorded.
  bool empty() const { return errors_.empty(); }
  /// The recorded problems in the order found.
  const std::vector<InputError>& all() const { return errors_; }
  /// All problems, one per line.
  std::string message() const;
  /// Throws an InputError carrying every problem when any was recorded.
  void throw_if_any() const;

 private:
  std::vector<InputError> errors_;
};

class Schema;

/// One key of a map schema.
struct Field {
  std::string key;                       ///< the key
  std::shared_ptr<const Schema> schema;  ///< what its value must be
  bool required = false;                 ///< must be present
  std::optional<YAML::Node> fallback;    ///< default inserted when absent (not for required keys)
  std::string help;                      ///< one line for documentation
};

/// What a node must look like. Build with the static factories; schemas are immutable and shareable.
class Schema {
 public:
  /// The kinds of node a schema accepts.
  enum class Kind { Map, List, String, Enum, Integer, Number, Boolean, Any, OneOf };

  /// A map with the given fields; unknown keys are errors unless `open`.
  static std::shared_ptr<const Schema> map(std::vector<Field> fields, bool open = false);
  /// A map from free-form keys to values of one schema.
  static std::shared_ptr<const Schema> dictionary(std::shared_ptr<const Schema> value);
  /// A list whose elements match `element`, with a size range.
  static std::shared_ptr<const Schema> list(std::shared_ptr<const Schema> element, std::size_t min_size = 0,
                                            std::size_t max_size = static_cast<std::size_t>(-1));
  /// Any string.
  static std::shared_ptr<const Schema> string();
  /// One of the given strings; an allowed string ending in `*` accepts every name starting with what precedes it.
  static std::shared_ptr<const Schema> enumeration(std::vector<std::string> allowed);
  /// An integer in [min, max].
  static std::shared_ptr<const Schema> integer(long long min, long long max);
  /// A finite number in [min, max].
  static std::shared_ptr<const Schema> number(double min, double max);
  /// true or false.
  static std::shared_ptr<const Schema> boolean();
  /// Anything (validated elsewhere).
  static std::shared_ptr<const Schema> any();
  /// The first alternative that matches (alternatives are tried in order; the error lists them all).
  static std::shared_ptr<const Schema> one_of(std::vector<std::shared_ptr<const Schema>> alternatives,
                                              std::string description);

  /// Checks `node` (at key path `path`), records problems in `errors` and inserts defaults of absent keys.
  void validate(YAML::Node node, const std::string& path, const std::string& file, ValidationErrors& errors) const;
  /// A short human description of what is accepted (e.g. "integer in [1, 10000]").
  std::string describe() const;
  /// The kind of node accepted.
  Kind kind() const { return kind_; }
  /// The fields of a map schema.
  const std::vector<Field>& fields() const { return fields_; }
  /// The element schema of a list (or the value schema of a dictionary), or nullptr.
  const Schema* element() const { return element_.get(); }
  /// The schema of a map field, or nullptr when not a known key.
  const Schema* field(const std::string& key) const;

 private:
  friend struct SchemaBuilder;
  Kind kind_ = Kind::Any;
  std::vector<Field> fields_;
  bool open_ = false;
  std::shared_ptr<const Schema> element_;
  std::vector<std::shared_ptr<const Schema>> alternatives_;
  std::vector<std::string> allowed_;
  long long int_min_ = 0;
  long long int_max_ = 0;
  double num_min_ = 0.0;
  double num_max_ = 0.0;
  std::size_t min_size_ = 0;
  std::size_t max_size_ = 0;
  std::string description_;
};

/// Shorthand for a required field.
Field required(std::string key, std::shared_ptr<const Schema> schema, std::string help = {});
/// Shorthand for an optional field with a default value (YAML text, e.g. "0.5" or "[]").
Field with_default(std::string key, std::shared_ptr<const Schema> schema, const std::string& default_yaml,
               std::string help = {});
/// Shorthand for an optional field without a default.
Field optional(std::string key, std::shared_ptr<const Schema> schema, std::string help = {});

/// Whether a map of names (`named_map`) must give every name or may leave some out.
enum class KeyCoverage {
  All,   ///< every name is a required key
  Some,  ///< every name is an optional key (an absent one reads as zero)
};
/// A map whose keys are `names`, in that order, each with a value matching `value` (e.g. a value per label of an
/// axis); a std::array member read with it takes element i from key `names[i]` (core/settings_archive.hpp).
std::shared_ptr<const Schema> named_map(const std::vector<std::string>& names, std::shared_ptr<const Schema> value,
                                        KeyCoverage coverage);

/// Applies `KEY.PATH=VALUE` overrides (VALUE parsed as YAML) to `root`; list indices as `a.b[2].c` or `a.b.2.c`.
void apply_override(YAML::Node root, const std::string& assignment, const std::string& origin = "--set");

}  // namespace freeplay
