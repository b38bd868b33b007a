// A module's state as named arrays of doubles and named texts: what a checkpoint holds of it.
//
// Each module fills one with everything that decides its next bit (DemSystem::save_state,
// PorePressureModel::save_state, the coupler's own clock), the wire carries it as raw array frames
// (SaveState / LoadState in proto/rockcut/wire.proto) and the coupler stores it in the checkpoint
// file without looking inside. Doubles carry integers exactly up to 2^53 (indices, counters, flags)
// and floats exactly, so one element type serves every member and the bits survive the round trip.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace rockcut::state {

/// A state that does not fit the program reading it (a missing member, a wrong length): the
/// checkpoint belongs to another scene or another version.
class StateError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct StateArray {
  std::string name;
  std::uint32_t components = 1;  ///< values per item (2 for interleaved x, y)
  std::vector<double> values;
};

class StateArchive {
 public:
  /// Largest integer a double holds exactly: counters beyond it cannot be archived.
  static constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53

  void put(std::string_view name, std::span<const double> values, std::uint32_t components = 1) {
    StateArray& a = slot(name);
    a.components = components;
    a.values.assign(values.begin(), values.end());
  }
  void put(std::string_view name, std::vector<double>&& values, std::uint32_t components = 1) {
    StateArray& a = slot(name);
    a.components = components;
    a.values = std::move(values);
  }
  /// Integers, floats or flags of any arithmetic type, converted exactly to doubles.
  template <class T>
  void put_values(std::string_view name, const std::vector<T>& values, std::uint32_t components = 1) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    StateArray& a = slot(name);
    a.components = components;
    a.values.resize(values.size());
    for (std::size_t k = 0; k < values.size(); ++k) a.values[k] = static_cast<double>(values[k]);
  }
  void put_scalar(std::string_view name, double value) { put(name, std::span<const double>(&value, 1)); }
  void put_text(std::string_view name, std::string value) { texts_[std::string(name)] = std::move(value); }

  bool has(std::string_view name) const { return find(name) != nullptr; }
  const StateArray& array(std::string_view name) const {
    const StateArray* a = find(name);
    if (!a) throw StateError("the state has no member \"" + std::string(name) + "\"");
    return *a;
  }
  /// The values of `name`; with `expected_size` set, refuses any other length.
  std::span<const double> values(std::string_view name,
                                 std::size_t expected_size = kAnySize) const {
    const StateArray& a = array(name);
    if (expected_size != kAnySize && a.values.size() != expected_size) {
      throw StateError("state member \"" + std::string(name) + "\" has " +
                       std::to_string(a.values.size()) + " values, this scene needs " +
                       std::to_string(expected_size));
    }
    return a.values;
  }
  void get(std::string_view name, std::vector<double>& out,
           std::size_t expected_size = kAnySize) const {
    const auto v = values(name, expected_size);
    out.assign(v.begin(), v.end());
  }
  /// The values of `name` converted back to T, refusing values T cannot hold exactly.
  template <class T>
  void get_values(std::string_view name, std::vector<T>& out,
                  std::size_t expected_size = kAnySize) const {
    const auto v = values(name, expected_size);
    out.resize(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) out[k] = to<T>(name, v[k]);
  }
  double scalar(std::string_view name) const { return values(name, 1)[0]; }
  template <class T>
  T scalar_as(std::string_view name) const {
    return to<T>(name, scalar(name));
  }
  const std::string& text(std::string_view name) const {
    const auto it = texts_.find(std::string(name));
    if (it == texts_.end()) throw StateError("the state has no text \"" + std::string(name) + "\"");
    return it->second;
  }

  const std::vector<StateArray>& arrays() const { return arrays_; }
  const std::map<std::string, std::string>& texts() const { return texts_; }
  /// Bytes of array payload.
  std::size_t payload_bytes() const {
    std::size_t n = 0;
    for (const StateArray& a : arrays_) n += a.values.size() * sizeof(double);
    return n;
  }
  void clear() {
    arrays_.clear();
    texts_.clear();
  }

  static constexpr std::size_t kAnySize = static_cast<std::size_t>(-1);

 private:
  StateArray& slot(std::string_view name) {
    for (StateArray& a : arrays_) {
      if (a.name == name) return a;
    }
    arrays_.push_back({std::string(name), 1, {}});
    return arrays_.back();
  }
  const StateArray* find(std::string_view name) const {
    for (const StateArray& a : arrays_) {
      if (a.name == name) return &a;
    }
    return nullptr;
  }
  template <class T>
  static T to(std::string_view name, double v) {
    if constexpr (std::is_floating_point_v<T>) {
      return static_cast<T>(v);
    } else if constexpr (std::is_enum_v<T>) {
      return static_cast<T>(to<std::underlying_type_t<T>>(name, v));
    } else {
      using L = std::numeric_limits<T>;
      if (!(v == std::floor(v)) || v < static_cast<double>(L::lowest()) ||
          v > static_cast<double>(L::max())) {
        throw StateError("state member \"" + std::string(name) + "\" holds " + std::to_string(v) +
                         ", not an integer of its type");
      }
      return static_cast<T>(v);
    }
  }

  std::vector<StateArray> arrays_;
  std::map<std::string, std::string> texts_;
};

}  // namespace rockcut::state
