// vgroove validation: an outcome written to JSON field by field and read back bit for bit, for the
// items that travel between processes as they are (item_work.h: a shard part, an MPI rank).
//
// A struct takes part by a `fields` function next to it, listing its members once for both ways:
//   template <class F> void fields(FurnaceOutcome& o, F&& f) { f("albedo_sim", o.albedo_sim); ... }
// (the writer calls it on a const_cast copy it never modifies). Members are doubles (written
// exactly: partial_report.h exact_json), integers, bools, strings, std::vector and std::optional
// of members, and structs with their own `fields`. Members the suite already fixes (the case, its
// spec) are left out and set again by the reader's caller.
//
// The reader is as strict as a suite file (support::JsonObject): every field present and of its
// type, integers in their type's range, no other keys, the file and the JSON path of the first
// damaged value in its message. Values cannot be checked against a count of rays (an outcome is
// not a tally): item_work.h adds a digest of the written outcome, so a damaged part is refused.
#pragma once

#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/partial_report.h"

#include <nlohmann/json.hpp>

#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace vgroove::validation::outcome_fields {

template <class T>
nlohmann::json to_json(const T& v);

template <class T>
struct IsVector : std::false_type {};
template <class T>
struct IsVector<std::vector<T>> : std::true_type {};
template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

struct Writer {
  nlohmann::json* out;
  template <class T>
  void operator()(const char* key, const T& v) const {
    if constexpr (IsOptional<T>::value) {
      if (v) (*out)[key] = to_json(*v);
    } else {
      (*out)[key] = to_json(v);
    }
  }
};

template <class T>
nlohmann::json to_json(const T& v) {
  if constexpr (std::same_as<T, bool> || std::same_as<T, std::string>) {
    return v;
  } else if constexpr (std::floating_point<T>) {
    return exact_json(static_cast<double>(v));
  } else if constexpr (std::integral<T>) {
    return v;
  } else if constexpr (IsVector<T>::value) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& e : v) a.push_back(to_json(e));
    return a;
  } else {
    nlohmann::json o = nlohmann::json::object();
    fields(const_cast<T&>(v), Writer{&o});
    return o;
  }
}

[[noreturn]] inline void fail(const std::string& file, const std::string& pointer, const nlohmann::json& j,
                              const std::string& what) {
  throw support::UserError(file + ": " + pointer + " = " + support::value_text(j) + " " + what);
}

template <class T>
void read(const nlohmann::json& j, const std::string& file, const std::string& pointer, T& v);

struct Reader {
  support::JsonObject* in;
  template <class T>
  void operator()(const char* key, T& v) const {
    if constexpr (IsOptional<T>::value) {
      v.reset();
      if (!in->has(key)) return;
      v.emplace();
      read(in->raw(key), in->file(), in->path(key), *v);
    } else {
      read(in->raw(key), in->file(), in->path(key), v);
    }
  }
};

template <class T>
void read(const nlohmann::json& j, const std::string& file, const std::string& pointer, T& v) {
  if constexpr (std::same_as<T, bool>) {
    if (!j.is_boolean()) fail(file, pointer, j, "must be true or false");
    v = j.get<bool>();
  } else if constexpr (std::same_as<T, std::string>) {
    if (!j.is_string()) fail(file, pointer, j, "must be a string");
    v = j.get<std::string>();
  } else if constexpr (std::floating_point<T>) {
    const bool special = j.is_string() && (j == "nan" || j == "inf" || j == "-inf");
    if (!j.is_number() && !special) fail(file, pointer, j, "must be a number (or \"nan\", \"inf\", \"-inf\")");
    v = static_cast<T>(exact_double(j));
  } else if constexpr (std::integral<T>) {
    using Limits = std::numeric_limits<T>;
    bool fits = false;
    if (j.is_number_unsigned())
      fits = j.get<std::uint64_t>() <= static_cast<std::uint64_t>(Limits::max());
    else if (j.is_number_integer())
      fits = j.get<std::int64_t>() >= 0
                 ? Limits::max() >= 0 &&
                       static_cast<std::uint64_t>(j.get<std::int64_t>()) <= static_cast<std::uint64_t>(Limits::max())
                 : std::is_signed_v<T> && j.get<std::int64_t>() >= static_cast<std::int64_t>(Limits::min());
    if (!fits)
      fail(file, pointer, j,
           "must be an integer in [" + std::to_string(Limits::min()) + ", " + std::to_string(Limits::max()) + "]");
    v = j.is_number_unsigned() ? static_cast<T>(j.get<std::uint64_t>()) : static_cast<T>(j.get<std::int64_t>());
  } else if constexpr (IsVector<T>::value) {
    if (!j.is_array()) fail(file, pointer, j, "must be an array");
    v.assign(j.size(), {});
    for (std::size_t i = 0; i < j.size(); ++i) read(j[i], file, pointer + "/" + std::to_string(i), v[i]);
  } else {
    if (!j.is_object()) fail(file, pointer, j, "must be an object");
    support::JsonObject o(j, file, pointer);
    fields(v, Reader{&o});
    o.finish();
  }
}

}  // namespace vgroove::validation::outcome_fields
