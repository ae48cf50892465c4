// Declarative parameter tables: one row per parameter of a struct gives its JSON output, its
// JSON / `--set` input with the value checks, and the list of known keys, so that no parameter
// struct needs a hand-written if-chain.
//
//   const ParameterTable<MyParams>& Table() {
//     static const ParameterTable<MyParams> table({
//         IntField<MyParams>("particles", [](auto& p) -> auto& { return p.particles; },
//         AtLeast(1)), NumberField<MyParams>("gate", [](auto& p) -> auto& { return p.gate; },
//         Above(0.0)), BoolField<MyParams>("resampling", [](auto& p) -> auto& { return
//         p.resampling; }),
//     });
//     return table;
//   }
//
// The accessor is a generic lambda returning a reference to the member, so one accessor serves
// both reading (const) and writing; members of nested structs are reached the same way.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "src/core/utf8.h"

namespace phdslam::params {

/// `s` as a JSON string literal for an error message, except that each byte that is not part of
/// well-formed UTF-8 (a string read from a hostile file) is written \xNN: the message stays UTF-8
/// and shows the bytes, and cannot be confused with the text's own backslashes (written \\).
inline std::string ShownString(std::string_view s) {
  std::string out = "\"";
  ForEachUtf8Run(
      s,
      [&](std::string_view run) {
        const std::string literal = nlohmann::json(std::string(run)).dump();
        out.append(literal, 1, literal.size() - 2);
      },
      [&](char byte) { out += EscapedByte(byte); });
  return out + "\"";
}

/// `v` as compact JSON text for an error message, its strings (and keys) quoted by ShownString,
/// so that building the message never throws on bytes that are not UTF-8.
inline std::string Shown(const nlohmann::json& v) {
  if (v.is_string()) return ShownString(v.get_ref<const std::string&>());
  if (!v.is_array() && !v.is_object()) return v.dump();
  std::string out;
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (it != v.begin()) out += ",";
    if (v.is_object()) out += ShownString(it.key()) + ":";
    out += Shown(*it);
  }
  return v.is_array() ? "[" + out + "]" : "{" + out + "}";
}

/// Thrown for a bad parameter value or an unknown key; the message names the key.
inline void Fail(const std::string& key, const std::string& what) {
  throw std::invalid_argument("parameter '" + EscapeNonUtf8(key) + "': " + what);
}

/// The closed or open interval a number must lie in.
struct Bounds {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;

  [[nodiscard]] bool Contains(double v) const {
    const bool above = min_exclusive ? v > min : v >= min;
    const bool below = max_exclusive ? v < max : v <= max;
    return above && below;
  }
  [[nodiscard]] std::string Describe() const {
    auto num = [](double v) {
      if (v == std::floor(v) && std::abs(v) < 1e15) {
        return std::to_string(static_cast<long long>(v));
      }
      return nlohmann::json(v).dump();
    };
    std::string s;
    if (std::isfinite(min)) s += std::string(min_exclusive ? "> " : ">= ") + num(min);
    if (std::isfinite(max)) {
      s += (s.empty() ? "" : " and ") + std::string(max_exclusive ? "< " : "<= ") + num(max);
    }
    return s.empty() ? "any finite number" : s;
  }
};

inline Bounds AnyValue() { return {}; }
inline Bounds AtLeast(double v) { return {v}; }
inline Bounds Above(double v) { return {v, std::numeric_limits<double>::infinity(), true}; }
inline Bounds Between(double lo, double hi) { return {lo, hi}; }
/// A probability in [0, 1].
inline Bounds Probability() { return {0.0, 1.0}; }

/// A finite JSON number, checked against `bounds`.
inline double ReadNumber(const nlohmann::json& v, const std::string& key, const Bounds& bounds) {
  if (!v.is_number()) Fail(key, "expected a number, got " + Shown(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) Fail(key, "not finite");
  if (!bounds.Contains(d)) Fail(key, "must be " + bounds.Describe() + ", got " + Shown(v));
  return d;
}

/// A whole JSON number of modest size (|v| <= 1e9), checked against `bounds`.
inline int ReadInt(const nlohmann::json& v, const std::string& key, const Bounds& bounds) {
  if (!v.is_number()) Fail(key, "expected an integer, got " + Shown(v));
  const double d = v.get<double>();
  if (!std::isfinite(d) || d != std::floor(d) || std::abs(d) > 1e9) {
    Fail(key, "expected an integer, got " + Shown(v));
  }
  if (!bounds.Contains(d)) Fail(key, "must be " + bounds.Describe() + ", got " + Shown(v));
  return static_cast<int>(d);
}

inline bool ReadBool(const nlohmann::json& v, const std::string& key) {
  if (!v.is_boolean()) Fail(key, "expected true or false, got " + Shown(v));
  return v.get<bool>();
}

/// `v` as written after `key=` in a message: a string without its quotes, else compact JSON.
inline std::string PlainValue(const nlohmann::json& v) {
  return v.is_string() ? EscapeNonUtf8(v.get<std::string>()) : Shown(v);
}

/// The mode a parameter is used in: the parameter `key` holds one of `values` (with `except`:
/// none of them). In any other mode the parameter has no effect.
struct UseCondition {
  std::string key;
  std::vector<nlohmann::json> values;
  bool except = false;

  /// True when `all` (every parameter by key) is in this mode.
  [[nodiscard]] bool Holds(const nlohmann::json& all) const {
    const auto it = all.find(key);
    if (it == all.end()) return true;  // a mode the table does not have restricts nothing
    bool listed = false;
    for (const nlohmann::json& v : values) listed = listed || v == *it;
    return listed != except;
  }
  /// "initialisation=incremental", "birth_rule=thresholded or gates-best", "x other than 0".
  [[nodiscard]] std::string Describe() const {
    std::string text;
    for (const nlohmann::json& v : values) {
      text += (text.empty() ? "" : " or ") + PlainValue(v);
    }
    return except ? key + " other than " + text : key + "=" + text;
  }
};

/// What a row says about its parameter to a reader (`phdslam list`).
struct FieldDescription {
  std::string key;
  std::string accepted;          ///< the accepted values (Field::help)
  std::string meaning;           ///< one line: what the parameter does
  std::string used_only_with{};  ///< the mode it is used in (UseCondition::Describe); empty: all
};

/// One row: a named parameter with its reader and writer.
template <class T>
struct Field {
  std::string key;
  std::string help;  ///< the accepted values, for error messages and --help
  std::function<nlohmann::json(const T&)> write;
  std::function<void(const nlohmann::json&, T&)> read;  ///< throws naming the key
  std::string meaning{};                                ///< one line of what it does (Means)
  std::vector<UseCondition> used_only_with{};  ///< the modes it has an effect in (all must hold)

  /// The row with its one line of meaning, for a table written as one expression per row.
  [[nodiscard]] Field Means(std::string text) && {
    meaning = std::move(text);
    return std::move(*this);
  }
  /// The row of a parameter used only when parameter `mode` holds one of `values`: a value
  /// given in another mode is refused (ParameterTable::RequireUsed).
  [[nodiscard]] Field UsedOnlyWith(std::string mode, std::vector<nlohmann::json> values) && {
    used_only_with.push_back({std::move(mode), std::move(values)});
    return std::move(*this);
  }
  /// The row of a parameter used only when parameter `mode` is not `value` (e.g. 0: off).
  [[nodiscard]] Field UsedOnlyWithout(std::string mode, nlohmann::json value) && {
    used_only_with.push_back({std::move(mode), {std::move(value)}, true});
    return std::move(*this);
  }
  /// The modes of used_only_with, for a reader.
  [[nodiscard]] std::string DescribeUse() const {
    std::string text;
    for (const UseCondition& c : used_only_with) {
      text += (text.empty() ? "" : " and ") + c.Describe();
    }
    return text;
  }
};

/// The rows of one parameter struct.
template <class T>
class ParameterTable {
 public:
  explicit ParameterTable(std::vector<Field<T>> fields) : fields_(std::move(fields)) {}

  /// Every parameter by key (a flat object).
  [[nodiscard]] nlohmann::json ToJson(const T& params) const {
    nlohmann::json j = nlohmann::json::object();
    for (const Field<T>& f : fields_) j[f.key] = f.write(params);
    return j;
  }

  /// Applies every key of `overrides`. Throws std::invalid_argument naming the key when it is
  /// unknown (listing the known keys) or its value is of the wrong type or out of range.
  void Apply(const nlohmann::json& overrides, T& params) const {
    if (!overrides.is_object()) {
      throw std::invalid_argument("parameters: expected an object, got " + Shown(overrides));
    }
    for (const auto& [key, value] : overrides.items()) {
      const Field<T>* field = Find(key);
      if (field == nullptr) {
        throw std::invalid_argument("unknown parameter '" + EscapeNonUtf8(key) +
                                    "' (known: " + KnownKeys() + ")");
      }
      field->read(value, params);
    }
  }

  [[nodiscard]] const Field<T>* Find(const std::string& key) const {
    for (const Field<T>& f : fields_) {
      if (f.key == key) return &f;
    }
    return nullptr;
  }

  [[nodiscard]] std::string KnownKeys() const {
    std::string s;
    for (const Field<T>& f : fields_) s += (s.empty() ? "" : ", ") + f.key;
    return s;
  }

  [[nodiscard]] const std::vector<Field<T>>& fields() const { return fields_; }

  /// Throws std::invalid_argument naming the first key of `overrides` that has no effect in the
  /// mode of `resolved` (its row's used_only_with does not hold), naming the mode that would use
  /// it; a key whose value is that of `baseline` (the parameters before the overrides: e.g. a
  /// recorded configuration read back) is accepted, as it changes nothing.
  void RequireUsed(const nlohmann::json& overrides, const T& baseline, const T& resolved) const {
    if (!overrides.is_object()) return;
    const nlohmann::json now = ToJson(resolved);
    const nlohmann::json before = ToJson(baseline);
    for (const auto& [key, value] : overrides.items()) {
      const Field<T>* field = Find(key);
      if (field == nullptr || before.at(key) == now.at(key)) continue;
      for (const UseCondition& c : field->used_only_with) {
        if (c.Holds(now)) continue;
        const std::string shown = EscapeNonUtf8(key);
        throw std::invalid_argument("parameter '" + shown + "' has no effect with " + c.key + "=" +
                                    PlainValue(now.at(c.key)) + "; it is used only with " +
                                    c.Describe() + " (set that too, or drop '" + shown + "')");
      }
    }
  }

  /// Every row's key, accepted values and meaning, in table order.
  [[nodiscard]] std::vector<FieldDescription> Descriptions() const {
    std::vector<FieldDescription> rows;
    rows.reserve(fields_.size());
    for (const Field<T>& f : fields_) rows.push_back({f.key, f.help, f.meaning, f.DescribeUse()});
    return rows;
  }

 private:
  std::vector<Field<T>> fields_;
};

template <class T, class Access>
Field<T> NumberField(std::string key, Access access, Bounds bounds = {}) {
  return {key, bounds.Describe(), [access](const T& p) { return nlohmann::json(access(p)); },
          [access, key, bounds](const nlohmann::json& v, T& p) {
            access(p) = ReadNumber(v, key, bounds);
          }};
}

template <class T, class Access>
Field<T> IntField(std::string key, Access access, Bounds bounds = {}) {
  return {key, "an integer " + bounds.Describe(),
          [access](const T& p) { return nlohmann::json(access(p)); },
          [access, key, bounds](const nlohmann::json& v, T& p) {
            access(p) = ReadInt(v, key, bounds);
          }};
}

template <class T, class Access>
Field<T> BoolField(std::string key, Access access) {
  return {key, "true or false", [access](const T& p) { return nlohmann::json(access(p)); },
          [access, key](const nlohmann::json& v, T& p) { access(p) = ReadBool(v, key); }};
}

/// An enumeration written and read by name.
template <class T, class E, class Access>
Field<T> EnumField(std::string key, Access access, std::vector<std::pair<E, std::string>> names) {
  std::string help;
  for (const auto& [value, name] : names) help += (help.empty() ? "\"" : ", \"") + name + "\"";
  return {key, "one of " + help,
          [access, names](const T& p) {
            for (const auto& [value, name] : names) {
              if (value == access(p)) return nlohmann::json(name);
            }
            return nlohmann::json(nullptr);
          },
          [access, key, names, help](const nlohmann::json& v, T& p) {
            if (v.is_string()) {
              for (const auto& [value, name] : names) {
                if (name == v.get<std::string>()) {
                  access(p) = value;
                  return;
                }
              }
            }
            Fail(key, "expected one of " + help + ", got " + Shown(v));
          }};
}

/// A diagonal matrix written and read as the array of its diagonal entries, each in `bounds`.
template <class T, int N, class Access>
Field<T> DiagonalField(std::string key, Access access, Bounds bounds = {}) {
  return {key, "an array of " + std::to_string(N) + " numbers " + bounds.Describe(),
          [access](const T& p) {
            nlohmann::json j = nlohmann::json::array();
            for (int i = 0; i < N; ++i) j.push_back(access(p)(i, i));
            return j;
          },
          [access, key, bounds](const nlohmann::json& v, T& p) {
            if (!v.is_array() || v.size() != static_cast<std::size_t>(N)) {
              Fail(key, "expected an array of " + std::to_string(N) + " numbers, got " + Shown(v));
            }
            Eigen::Matrix<double, N, N> m = Eigen::Matrix<double, N, N>::Zero();
            for (int i = 0; i < N; ++i) m(i, i) = ReadNumber(v[i], key, bounds);
            access(p) = m;
          }};
}

/// A free-form UTF-8 string (its values, if restricted, are checked by the struct's own
/// validation). Text that is not UTF-8 is refused here: it could not be written back as JSON.
template <class T, class Access>
Field<T> StringField(std::string key, Access access) {
  return {key, "a string", [access](const T& p) { return nlohmann::json(access(p)); },
          [access, key](const nlohmann::json& v, T& p) {
            if (!v.is_string()) Fail(key, "expected a string, got " + Shown(v));
            if (!IsUtf8(v.get_ref<const std::string&>())) {
              Fail(key, "expected UTF-8 text, got " + Shown(v));
            }
            access(p) = v.get<std::string>();
          }};
}

/// A std::optional<double> written and read as a number in `bounds`, or null when unset.
template <class T, class Access>
Field<T> OptionalNumberField(std::string key, Access access, Bounds bounds = {}) {
  return {key, "null or a number " + bounds.Describe(),
          [access](const T& p) {
            return access(p).has_value() ? nlohmann::json(*access(p)) : nlohmann::json(nullptr);
          },
          [access, key, bounds](const nlohmann::json& v, T& p) {
            if (v.is_null()) {
              access(p).reset();
            } else {
              access(p) = ReadNumber(v, key, bounds);
            }
          }};
}

/// A fixed-size Eigen vector written and read as the array of its entries, each in `bounds`.
template <class T, int N, class Access>
Field<T> VectorField(std::string key, Access access, Bounds bounds = {}) {
  return {key, "an array of " + std::to_string(N) + " numbers " + bounds.Describe(),
          [access](const T& p) {
            nlohmann::json j = nlohmann::json::array();
            for (int i = 0; i < N; ++i) j.push_back(access(p)(i));
            return j;
          },
          [access, key, bounds](const nlohmann::json& v, T& p) {
            if (!v.is_array() || v.size() != static_cast<std::size_t>(N)) {
              Fail(key, "expected an array of " + std::to_string(N) + " numbers, got " + Shown(v));
            }
            Eigen::Matrix<double, N, 1> x;
            for (int i = 0; i < N; ++i) x(i) = ReadNumber(v[i], key, bounds);
            access(p) = x;
          }};
}

/// A struct of numbers written and read as an array in the order of `members`, each in `bounds`
/// (e.g. a noise floor as [position_std, heading_std]).
template <class T, class S, class Access>
Field<T> StructArrayField(std::string key, Access access,
                          std::vector<std::pair<std::string, double S::*>> members,
                          Bounds bounds = {}) {
  std::string names;
  for (const auto& [name, member] : members) names += (names.empty() ? "" : ", ") + name;
  names = "[" + names + "]";
  return {key, names + ", each " + bounds.Describe(),
          [access, members](const T& p) {
            nlohmann::json j = nlohmann::json::array();
            for (const auto& [name, member] : members) j.push_back(access(p).*member);
            return j;
          },
          [access, key, members, names, bounds](const nlohmann::json& v, T& p) {
            if (!v.is_array() || v.size() != members.size()) {
              Fail(key, "expected " + names + ", got " + Shown(v));
            }
            S s = access(p);
            for (std::size_t i = 0; i < members.size(); ++i) {
              s.*members[i].second = ReadNumber(v[i], key, bounds);
            }
            access(p) = s;
          }};
}

/// `field` for a value that is fixed elsewhere (e.g. by an estimator's name): written as usual;
/// an input equal to the current value is accepted (so that a written configuration reads back)
/// and any other value is rejected, the message giving `reason` and the current value.
template <class T>
Field<T> Fixed(Field<T> field, const std::string& reason) {
  field.help = "fixed: " + reason;
  field.read = [key = field.key, read = field.read, write = field.write, reason](
                   const nlohmann::json& v, T& p) {
    T candidate = p;
    read(v, candidate);
    if (write(candidate) != write(p)) {
      Fail(key, reason + ": expected " + Shown(write(p)) + ", got " + Shown(v));
    }
  };
  return field;
}

/// A number that may also be the string `automatic` (stored as NaN: derived elsewhere).
template <class T, class Access>
Field<T> NumberOrAutomaticField(std::string key, Access access, const std::string& automatic) {
  return {key, "a number or \"" + automatic + "\"",
          [access, automatic](const T& p) {
            return std::isnan(access(p)) ? nlohmann::json(automatic) : nlohmann::json(access(p));
          },
          [access, key, automatic](const nlohmann::json& v, T& p) {
            if (v.is_string() && v.get<std::string>() == automatic) {
              access(p) = std::numeric_limits<double>::quiet_NaN();
            } else {
              access(p) = ReadNumber(v, key, {});
            }
          }};
}

/// The rows of `table` for a member struct, re-keyed under the same names and reached through
/// `access` (e.g. the map parameters inside every filter's parameters).
template <class T, class Inner, class Access>
std::vector<Field<T>> Embed(const ParameterTable<Inner>& table, Access access) {
  std::vector<Field<T>> rows;
  for (const Field<Inner>& f : table.fields()) {
    rows.push_back({f.key, f.help, [access, w = f.write](const T& p) { return w(access(p)); },
                    [access, r = f.read](const nlohmann::json& v, T& p) { r(v, access(p)); },
                    f.meaning, f.used_only_with});
  }
  return rows;
}

/// Concatenates row lists.
template <class T>
std::vector<Field<T>> Rows(std::initializer_list<std::vector<Field<T>>> parts) {
  std::vector<Field<T>> all;
  for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

}  // namespace phdslam::params
