#include "freeplay/core/yaml_schema.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

namespace freeplay {

namespace {

std::string join_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string kind_name(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Scalar: return fmt::format("'{}'", node.Scalar());
    case YAML::NodeType::Null: return "nothing (null)";
    default: return "an undefined value";
  }
}

}  // namespace

SourceLocation location_of(const YAML::Node& node, const std::string& file) {
  if (!node.IsDefined()) return {file, 0, 0};  // an absent key (or an invalid node) has no position
  const auto mark = node.Mark();
  if (mark.is_null()) return {file, 0, 0};
  return {file, mark.line + 1, mark.column + 1};
}

YamlDocument parse_yaml(const std::string& text, const std::string& file) {
  try {
    return {file, YAML::Load(text)};
  } catch (const YAML::Exception& e) {  // syntax errors, unknown aliases, nesting too deep
    const bool located = !e.mark.is_null();
    throw InputError(fmt::format("YAML syntax error: {}", e.msg), {}, {},
                     {file, located ? e.mark.line + 1 : 0, located ? e.mark.column + 1 : 0});
  }
}

YamlDocument load_yaml_file(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError("is a folder, not a file", {}, {}, {path.string()});
  std::ifstream in(path);
  if (!in) throw InputError("cannot open file", {}, {}, {path.string(), 0, 0});
  std::ostringstream text;
  text << in.rdbuf();
  return parse_yaml(text.str(), path.string());
}

std::string ValidationErrors::message() const {
  std::string out;
  for (const auto& e : errors_) {
    if (!out.empty()) out += '\n';
    out += e.what();
  }
  return out;
}

void ValidationErrors::throw_if_any() const {
  if (errors_.empty()) return;
  if (errors_.size() == 1) throw errors_.front();
  const auto& first = errors_.front();
  throw InputError(fmt::format("{}\n({} problems in all)", message(), errors_.size()), first.key(), {}, {});
}

// The factories build a Schema through a private-access helper: Schema has no public setters.
struct SchemaBuilder {
  static std::shared_ptr<Schema> of(Schema::Kind kind) {
    auto s = std::make_shared<Schema>();
    s->kind_ = kind;
    return s;
  }
};

std::shared_ptr<const Schema> Schema::map(std::vector<Field> fields, bool open) {
  auto s = SchemaBuilder::of(Kind::Map);
  s->fields_ = std::move(fields);
  s->open_ = open;
  return s;
}

std::shared_ptr<const Schema> Schema::dictionary(std::shared_ptr<const Schema> value) {
  auto s = SchemaBuilder::of(Kind::Map);
  s->open_ = true;
  s->element_ = std::move(value);
  return s;
}

std::shared_ptr<const Schema> Schema::list(std::shared_ptr<const Schema> element, std::size_t min_size,
                                           std::size_t max_size) {
  auto s = SchemaBuilder::of(Kind::List);
  s->element_ = std::move(element);
  s->min_size_ = min_size;
  s->max_size_ = max_size;
  return s;
}

std::shared_ptr<const Schema> Schema::string() { return SchemaBuilder::of(Kind::String); }

std::shared_ptr<const Schema> Schema::enumeration(std::vector<std::string> allowed) {
  auto s = SchemaBuilder::of(Kind::Enum);
  s->allowed_ = std::move(allowed);
  return s;
}

std::shared_ptr<const Schema> Schema::integer(long long min, long long max) {
  auto s = SchemaBuilder::of(Kind::Integer);
  s->int_min_ = min;
  s->int_max_ = max;
  return s;
}

std::shared_ptr<const Schema> Schema::number(double min, double max) {
  auto s = SchemaBuilder::of(Kind::Number);
  s->num_min_ = min;
  s->num_max_ = max;
  return s;
}

std::shared_ptr<const Schema> Schema::boolean() { return SchemaBuilder::of(Kind::Boolean); }

std::shared_ptr<const Schema> Schema::any() { return SchemaBuilder::of(Kind::Any); }

std::shared_ptr<const Schema> Schema::one_of(std::vector<std::shared_ptr<const Schema>> alternatives,
                                             std::string description) {
  auto s = SchemaBuilder::of(Kind::OneOf);
  s->alternatives_ = std::move(alternatives);
  s->description_ = std::move(description);
  return s;
}

const Schema* Schema::field(const std::string& key) const {
  for (const auto& f : fields_) {
    if (f.key == key) return f.schema.get();
  }
  return nullptr;
}

std::string Schema::describe() const {
  switch (kind_) {
    case Kind::Map: {
      if (element_) return "a map of names to " + element_->describe();
      std::vector<std::string> keys;
      for (const auto& f : fields_) keys.push_back(f.key);
      return fmt::format("a map with keys {}", fmt::join(keys, ", "));
    }
    case Kind::List: return "a list of " + element_->describe();
    case Kind::String: return "a string";
    case Kind::Enum: return fmt::format("one of {}", fmt::join(allowed_, ", "));
    case Kind::Integer: return fmt::format("an integer in [{}, {}]", int_min_, int_max_);
    case Kind::Number: return fmt::format("a number in [{}, {}]", num_min_, num_max_);
    case Kind::Boolean: return "true or false";
    case Kind::Any: return "any value";
    case Kind::OneOf: return description_;
  }
  return "?";
}

void Schema::validate(YAML::Node node, const std::string& path, const std::string& file,
                      ValidationErrors& errors) const {
  const auto where = location_of(node, file);
  auto wrong = [&](const std::string& problem) { errors.add(InputError(problem, path, describe(), where)); };
  switch (kind_) {
    case Kind::Any: return;
    case Kind::Map: {
      if (!node.IsMap()) return wrong(fmt::format("expected a map, found {}", kind_name(node)));
      // yaml-cpp keeps every repeat of a key and answers lookups with the first: a repeat would be ignored silently.
      std::map<std::string, YAML::Mark> seen;
      for (auto it = node.begin(); it != node.end(); ++it) {
        if (!it->first.IsScalar()) {
          errors.add(InputError(fmt::format("a key must be a name, found {}", kind_name(it->first)), path,
                                "name: value", location_of(it->first, file)));
          continue;
        }
        const auto key = it->first.Scalar();
        if (const auto [first, inserted] = seen.emplace(key, it->first.Mark()); !inserted) {
          errors.add(InputError(fmt::format("key '{}' appears twice (first at line {})", key, first->second.line + 1),
                                join_path(path, key), "each key once", location_of(it->first, file)));
          continue;
        }
        if (element_) {
          element_->validate(it->second, join_path(path, key), file, errors);
          continue;
        }
        if (field(key) == nullptr && !open_) {
          std::vector<std::string> keys;
          for (const auto& f : fields_) keys.push_back(f.key);
          errors.add(InputError(fmt::format("unknown key '{}'", key), join_path(path, key),
                                fmt::format("{}", fmt::join(keys, ", ")), location_of(it->first, file)));
        }
      }
      for (const auto& f : fields_) {
        const YAML::Node& const_node = node;
        const YAML::Node child = const_node[f.key];
        if (!child.IsDefined()) {
          if (f.required) {
            errors.add(InputError(fmt::format("missing required key '{}'", f.key), join_path(path, f.key),
                                  f.schema->describe(), where));
          } else if (f.fallback) {
            node[f.key] = YAML::Clone(*f.fallback);
            f.schema->validate(node[f.key], join_path(path, f.key), file, errors);  // fills nested defaults
          }
          continue;
        }
        f.schema->validate(node[f.key], join_path(path, f.key), file, errors);
      }
      return;
    }
    case Kind::List: {
      if (!node.IsSequence()) return wrong(fmt::format("expected a list, found {}", kind_name(node)));
      if (node.size() < min_size_ || node.size() > max_size_) {
        return wrong(fmt::format("list has {} element(s); needs between {} and {}", node.size(), min_size_,
                                 max_size_ == static_cast<std::size_t>(-1) ? std::string("any number")
                                                                           : std::to_string(max_size_)));
      }
      for (std::size_t i = 0; i < node.size(); ++i) {
        element_->validate(node[i], fmt::format("{}[{}]", path, i), file, errors);
      }
      return;
    }
    case Kind::String:
      if (!node.IsScalar()) wrong(fmt::format("expected a string, found {}", kind_name(node)));
      return;
    case Kind::Enum: {
      if (!node.IsScalar()) return wrong(fmt::format("expected a name, found {}", kind_name(node)));
      const auto value = node.Scalar();
      for (const auto& a : allowed_) {
        if (a == value) return;
        if (a.ends_with('*') && value.size() >= a.size() && value.starts_with(std::string_view(a).substr(0, a.size() - 1))) {
          return;
        }
      }
      return wrong(fmt::format("unknown value '{}'", value));
    }
    case Kind::Integer: {
      long long value = 0;
      if (!node.IsScalar() || !YAML::convert<long long>::decode(node, value)) {
        return wrong(fmt::format("expected an integer, found {}", kind_name(node)));
      }
      if (value < int_min_ || value > int_max_) wrong(fmt::format("{} is out of range", value));
      return;
    }
    case Kind::Number: {
      double value = 0.0;
      if (!node.IsScalar() || !YAML::convert<double>::decode(node, value) || !std::isfinite(value)) {
        return wrong(fmt::format("expected a finite number, found {}", kind_name(node)));
      }
      if (value < num_min_ || value > num_max_) wrong(fmt::format("{} is out of range", node.Scalar()));
      return;
    }
    case Kind::Boolean: {
      bool value = false;
      if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
        wrong(fmt::format("expected true or false, found {}", kind_name(node)));
      }
      return;
    }
    case Kind::OneOf: {
      for (const auto& alternative : alternatives_) {
        ValidationErrors trial;
        YAML::Node copy = YAML::Clone(node);
        alternative->validate(copy, path, file, trial);
        if (trial.empty()) {
          alternative->validate(node, path, file, trial);  // insert the defaults into the real node
          return;
        }
      }
      // A map or a list fits only the one map or list form there is: its own errors name the key inside.
      const auto same_kind = [&](const std::shared_ptr<const Schema>& a) {
        return (node.IsMap() && a->kind_ == Kind::Map) || (node.IsSequence() && a->kind_ == Kind::List);
      };
      if (std::count_if(alternatives_.begin(), alternatives_.end(), same_kind) == 1) {
        return (*std::find_if(alternatives_.begin(), alternatives_.end(), same_kind))->validate(node, path, file, errors);
      }
      return wrong(fmt::format("found {}, which matches none of the accepted forms", kind_name(node)));
    }
  }
}

Field required(std::string key, std::shared_ptr<const Schema> schema, std::string help) {
  return Field{std::move(key), std::move(schema), true, std::nullopt, std::move(help)};
}

Field with_default(std::string key, std::shared_ptr<const Schema> schema, const std::string& default_yaml,
               std::string help) {
  return Field{std::move(key), std::move(schema), false, YAML::Load(default_yaml), std::move(help)};
}

Field optional(std::string key, std::shared_ptr<const Schema> schema, std::string help) {
  return Field{std::move(key), std::move(schema), false, std::nullopt, std::move(help)};
}

std::shared_ptr<const Schema> named_map(const std::vector<std::string>& names, std::shared_ptr<const Schema> value,
                                        KeyCoverage coverage) {
  std::vector<Field> fields;
  fields.reserve(names.size());
  for (const auto& name : names) {
    fields.push_back(coverage == KeyCoverage::All ? required(name, value) : optional(name, value));
  }
  return Schema::map(std::move(fields));
}

namespace {

std::vector<std::string> split_key_path(const std::string& key_path) {
  std::vector<std::string> parts;
  std::string current;
  for (const char c : key_path) {
    if (c == '.' || c == '[') {
      if (!current.empty()) parts.push_back(current);
      current.clear();
    } else if (c != ']') {
      current += c;
    }
  }
  if (!current.empty()) parts.push_back(current);
  return parts;
}

/// The list index `s` names, or nullopt when it is not a decimal number below `size`.
std::optional<std::size_t> index_in(const std::string& s, std::size_t size) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const auto index = static_cast<std::size_t>(std::stoul(s));
  if (index >= size) return std::nullopt;
  return index;
}

}  // namespace

void apply_override(YAML::Node root, const std::string& assignment, const std::string& origin) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(fmt::format("'{}' is not an assignment", assignment), origin, "KEY.PATH=VALUE");
  }
  const auto key_path = assignment.substr(0, eq);
  const auto parts = split_key_path(key_path);
  if (parts.empty()) throw InputError("empty key path", origin, "KEY.PATH=VALUE");
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("value of '{}' is not valid YAML: {}", key_path, e.msg), origin);
  }
  YAML::Node node = root;
  std::string walked;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto& part = parts[i];
    const bool last = i + 1 == parts.size();
    walked = walked.empty() ? part : walked + "." + part;
    if (node.IsSequence()) {
      const auto index = index_in(part, node.size());
      if (!index) {
        throw InputError(fmt::format("'{}' is not an index of the list at '{}'", part, walked), origin,
                         fmt::format("0…{}", node.size() == 0 ? 0 : node.size() - 1));
      }
      if (last) {
        node[*index] = value;
        return;
      }
      node.reset(node[*index]);
      continue;
    }
    if (!node.IsMap() && !node.IsNull() && node.IsDefined()) {
      throw InputError(fmt::format("cannot set '{}': '{}' is not a map", key_path, walked), origin);
    }
    if (last) {
      node[part] = value;
      return;
    }
    YAML::Node child = node[part];
    if (!child.IsDefined() || child.IsNull()) {
      node[part] = YAML::Node(YAML::NodeType::Map);
    }
    node.reset(node[part]);
  }
}

}  // namespace freeplay
