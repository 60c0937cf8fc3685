#pragma once
// Typed settings structs whose YAML schema, defaults and reader come from one list of their fields (Drake's
// Serialize pattern): a struct declares `template <class Archive> void visit(Archive& a)` calling
// `a.field(key, member, schema, help)` (or `a.required` / `a.optional`) once per member; its member initialisers are
// the defaults. `settings_schema<T>()` builds the map schema from that list and `read_settings<T>(node)` fills a
// struct from a node the schema validated (`read_unvalidated_settings<T>(node, path)` validates it first). An enum
// member is written with `to_string(value)` and read with `from_string(text, value)`, the one name/value pair its
// library declares next to it (found by argument-dependent lookup); `enum_names` lists the names its schema allows.
// A std::array member given a `named_map` schema is a value per name (element i under key names[i]; a name a
// `KeyCoverage::Some` map leaves out reads as zero). `a.section(key, visit_keys)` declares a required sub-map whose
// keys a lambda lists (for keys that need context, such as a loop over names). `write_settings<T>(settings)` writes
// a struct back as YAML through the same list (WriteArchive), so each key is named once in the code.
// A member that is itself a settings struct, a `std::optional` of one or a `std::vector` of them is read through its
// own `visit`; its schema is given as `settings_schema<Nested>()` (a list: `Schema::list(settings_schema<Nested>())`,
// declared with `a.optional` or `a.required`: an absent optional list keeps the member's initialiser). A std::array
// member given a fixed-length `Schema::list` schema is read and written as that list. A std::optional member
// declared with `a.optional` and no default is read and written as its value type, an enum included.

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <concepts>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "freeplay/core/enum_names.hpp"
#include "freeplay/core/yaml_schema.hpp"

namespace freeplay {

/// The YAML text of a default value: the shortest text that reads back the same value.
template <typename T>
std::string default_yaml_text(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_enum_v<T>) {
    return std::string(to_string(value));
  } else if constexpr (std::is_same_v<T, YAML::Node>) {
    YAML::Emitter out;
    out << YAML::Flow << value;
    return out.c_str();
  } else {
    return fmt::format("{}", value);
  }
}

/// True for std::optional members (read as their value type).
template <typename T>
struct IsOptional : std::false_type {};
/// True for std::optional members (read as their value type).
template <typename T>
struct IsOptional<std::optional<T>> : std::true_type {};

/// True for std::array members (read and written as a value per name of their `named_map` schema).
template <typename T>
struct IsStdArray : std::false_type {};
/// True for std::array members (read and written as a value per name of their `named_map` schema).
template <typename T, std::size_t N>
struct IsStdArray<std::array<T, N>> : std::true_type {};
/// True for std::vector members (read element by element, so a list of settings structs reads each through its
/// `visit`).
template <typename T>
struct IsVector : std::false_type {};
/// True for std::vector members (read element by element).
template <typename T, typename Allocator>
struct IsVector<std::vector<T, Allocator>> : std::true_type {};

/// Collects the schema fields of a settings struct, with the defaults of a default-constructed instance.
class SchemaArchive {
 public:
  /// An optional key; absent, it takes the member's current (default) value.
  template <typename T>
  void field(const char* key, const T& value, std::shared_ptr<const Schema> schema, std::string help = {}) {
    fields_.push_back(with_default(key, std::move(schema), default_yaml_text(value), std::move(help)));
  }
  /// A key the document must give.
  template <typename T>
  void required(const char* key, const T&, std::shared_ptr<const Schema> schema, std::string help = {}) {
    fields_.push_back(freeplay::required(key, std::move(schema), std::move(help)));
  }
  /// An optional key without a default (the member stays empty when it is absent).
  template <typename T>
  void optional(const char* key, const T&, std::shared_ptr<const Schema> schema, std::string help = {}) {
    fields_.push_back(freeplay::optional(key, std::move(schema), std::move(help)));
  }
  /// A required sub-map whose keys `visit_keys(archive)` declares on the archive it is given.
  template <typename VisitKeys>
  void section(const std::string& key, VisitKeys&& visit_keys, std::string help = {}) {
    SchemaArchive nested;
    visit_keys(nested);
    fields_.push_back(freeplay::required(key, Schema::map(nested.take()), std::move(help)));
  }
  /// The collected fields, in declaration order.
  std::vector<Field> take() { return std::move(fields_); }
  /// The fields of settings struct `T`, with the defaults of a default-constructed instance.
  template <typename T, typename... Context>
  static std::vector<Field> fields_of(const Context&... context) {
    T defaults;
    SchemaArchive archive;
    defaults.visit(archive, context...);
    return archive.take();
  }

 private:
  std::vector<Field> fields_;
};

/// Fills a settings struct from a node its schema validated (defaults already inserted).
class ReadArchive {
 public:
  /// Reads from `node` (a map).
  explicit ReadArchive(YAML::Node node) : node_(std::move(node)) {}
  /// Reads a key that validation filled in.
  template <typename T>
  void field(const char* key, T& value, const std::shared_ptr<const Schema>& schema = {}, const std::string& = {}) {
    read(node_[key], value, schema.get());
  }
  /// Reads a required key.
  template <typename T>
  void required(const char* key, T& value, const std::shared_ptr<const Schema>& schema = {}, const std::string& = {}) {
    read(node_[key], value, schema.get());
  }
  /// Reads an optional key when it is present and not null.
  template <typename T>
  void optional(const char* key, T& value, const std::shared_ptr<const Schema>& schema = {}, const std::string& = {}) {
    const YAML::Node child = node_[key];
    if (child.IsDefined() && !child.IsNull()) read(child, value, schema.get());
  }
  /// Reads the keys of sub-map `key` that `visit_keys(archive)` declares.
  template <typename VisitKeys>
  void section(const std::string& key, VisitKeys&& visit_keys, const std::string& = {}) {
    ReadArchive nested(node_[key]);
    visit_keys(nested);
  }

 private:
  template <typename T>
  static void read(const YAML::Node& node, T& value, const Schema* schema) {
    if constexpr (std::is_same_v<T, YAML::Node>) {
      value = node;
    } else if constexpr (requires(T& t, ReadArchive& a) { t.visit(a); }) {  // a nested settings struct
      ReadArchive nested(node);
      value.visit(nested);
    } else if constexpr (std::is_enum_v<T>) {
      if (!from_string(node.Scalar(), value)) {
        throw std::invalid_argument(fmt::format("'{}' is none of the allowed names (the schema lets it through)",
                                                node.Scalar()));
      }
    } else if constexpr (IsOptional<T>::value) {  // e.g. an optional nested settings struct
      typename T::value_type inner{};
      read(node, inner, schema);
      value = std::move(inner);
    } else if constexpr (IsVector<T>::value) {  // e.g. a list of settings structs
      value.clear();
      value.reserve(node.size());
      for (const auto& element : node) {
        typename T::value_type item{};
        read(element, item, schema != nullptr ? schema->element() : nullptr);
        value.push_back(std::move(item));
      }
    } else if constexpr (IsStdArray<T>::value) {
      if (schema != nullptr && schema->kind() == Schema::Kind::List) {  // a list whose schema fixed its length
        for (std::size_t i = 0; i < value.size(); ++i) read(node[i], value[i], schema->element());
        return;
      }
      // a value per name of its named_map schema
      if (schema == nullptr || schema->kind() != Schema::Kind::Map || schema->fields().size() > value.size()) {
        throw std::logic_error("a std::array setting needs a named_map schema with at most as many names as elements");
      }
      for (std::size_t i = 0; i < schema->fields().size(); ++i) {
        const Field& f = schema->fields()[i];
        const YAML::Node child = node[f.key];
        value[i] = {};
        if (child.IsDefined() && !child.IsNull()) read(child, value[i], f.schema.get());
      }
    } else {
      value = node.as<T>();
    }
  }
  YAML::Node node_;
};

/// Writes a settings struct as YAML through its `visit` list: nested structs and maps of maps as blocks, a value
/// per name of scalars as one flow line, numbers as the shortest text that reads back the same value. An empty
/// std::optional and a zero value under an optional name of a `named_map` are left out.
class WriteArchive {
 public:
  /// Writes into `out`, which is inside a map.
  explicit WriteArchive(YAML::Emitter& out) : out_(out) {}
  /// Writes a key.
  template <typename T>
  void field(const char* key, T& value, const std::shared_ptr<const Schema>& schema = {}, const std::string& = {}) {
    out_ << YAML::Key << key << YAML::Value;
    write(value, schema.get());
  }
  /// Writes a required key.
  template <typename T>
  void required(const char* key, T& value, const std::shared_ptr<const Schema>& schema = {}, const std::string& = {}) {
    field(key, value, schema);
  }
  /// Writes an optional key unless it is an empty std::optional.
  template <typename T>
  void optional(const char* key, T& value, const std::shared_ptr<const Schema>& schema = {}, const std::string& = {}) {
    if constexpr (IsOptional<T>::value) {
      if (!value) return;
    }
    field(key, value, schema);
  }
  /// Writes sub-map `key` with the keys `visit_keys(archive)` declares.
  template <typename VisitKeys>
  void section(const std::string& key, VisitKeys&& visit_keys, const std::string& = {}) {
    out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
    visit_keys(*this);
    out_ << YAML::EndMap;
  }

 private:
  template <typename T>
  void write(T& value, const Schema* schema) {
    if constexpr (std::is_same_v<T, YAML::Node>) {
      out_ << value;
    } else if constexpr (requires(T& t, WriteArchive& a) { t.visit(a); }) {  // a nested settings struct
      out_ << YAML::BeginMap;
      value.visit(*this);
      out_ << YAML::EndMap;
    } else if constexpr (std::is_enum_v<T>) {
      out_ << std::string(to_string(value));
    } else if constexpr (IsOptional<T>::value) {
      if (value) {
        write(*value, schema);
      } else {
        out_ << YAML::Null;
      }
    } else if constexpr (IsVector<T>::value) {
      write_list(value, schema);
    } else if constexpr (IsStdArray<T>::value) {
      using Element = typename T::value_type;
      if (schema != nullptr && schema->kind() == Schema::Kind::List) {  // a fixed-length list
        write_list(value, schema);
        return;
      }
      if (schema == nullptr || schema->kind() != Schema::Kind::Map || schema->fields().size() > value.size()) {
        throw std::logic_error("a std::array setting needs a named_map schema with at most as many names as elements");
      }
      if constexpr (std::is_arithmetic_v<Element>) out_ << YAML::Flow;
      out_ << YAML::BeginMap;
      for (std::size_t i = 0; i < schema->fields().size(); ++i) {
        const Field& f = schema->fields()[i];
        if constexpr (std::equality_comparable<Element>) {
          if (!f.required && value[i] == Element{}) continue;  // what reading the absent name gives back
        }
        out_ << YAML::Key << f.key << YAML::Value;
        write(value[i], f.schema.get());
      }
      out_ << YAML::EndMap;
    } else if constexpr (std::is_floating_point_v<T>) {
      out_ << fmt::format("{}", value);
    } else {
      out_ << value;
    }
  }
  // A list: numbers on one line, structs as blocks.
  template <typename List>
  void write_list(List& list, const Schema* schema) {
    if constexpr (std::is_arithmetic_v<typename List::value_type>) out_ << YAML::Flow;
    out_ << YAML::BeginSeq;
    for (auto& element : list) write(element, schema != nullptr ? schema->element() : nullptr);
    out_ << YAML::EndSeq;
  }
  YAML::Emitter& out_;
};

/// The map schema of settings struct `T` (its `visit` may take extra context, e.g. the accepted names).
template <typename T, typename... Context>
std::shared_ptr<const Schema> settings_schema(const Context&... context) {
  return Schema::map(SchemaArchive::fields_of<T>(context...));
}

/// A settings struct read from `node`, which `settings_schema<T>()` validated.
template <typename T, typename... Context>
T read_settings(const YAML::Node& node, const Context&... context) {
  T settings;
  ReadArchive archive(node);
  settings.visit(archive, context...);
  return settings;
}

/// Settings struct `T` as YAML text (a block map) that `read_settings<T>` reads back to the same values.
template <typename T, typename... Context>
std::string write_settings(const T& settings, const Context&... context) {
  T copy = settings;  // `visit` hands out its members as mutable references
  YAML::Emitter out;
  WriteArchive archive(out);
  out << YAML::BeginMap;
  copy.visit(archive, context...);
  out << YAML::EndMap;
  return out.c_str();
}

/// Settings struct `T` from a node nothing validated yet (absent or null: every default), such as a policy's
/// `robot.params`: validated against `settings_schema<T>()` with keys named under `path` (one InputError listing every
/// problem), then read.
template <typename T, typename... Context>
T read_unvalidated_settings(const YAML::Node& node, const std::string& path, const Context&... context) {
  YAML::Node copy = node.IsDefined() && !node.IsNull() ? YAML::Clone(node) : YAML::Node(YAML::NodeType::Map);
  ValidationErrors errors;
  settings_schema<T>(context...)->validate(copy, path, "", errors);
  errors.throw_if_any();
  return read_settings<T>(copy, context...);
}

}  // namespace freeplay
