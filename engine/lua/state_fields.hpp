#pragma once
// Internal: the fields of `s` that force(s) reads, the one place they are named. A scene
// of N axes gives each axis a position and a velocity, then the run time and the period:
//   1 axis   x, v, t, dt
//   N axes   x, y, z (kAxisNames) and vx, vy, vz, then t, dt
// and force(s) returns N numbers (fx; fx, fy; ...). The sandbox's key slots, the `s`
// table, the translation of force (force_program.hpp) and every message that lists the
// fields follow from this list, so a new N needs nothing here.
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <iterator>

#include "engine/base/axes.hpp"

namespace hapscene::detail {

// A field's index: t, dt, then a position per axis, then a velocity per axis (kMaxAxes
// of each, whether or not a scene has them all).
inline constexpr int kFieldT = 0;
inline constexpr int kFieldDt = 1;
constexpr int position_field(int axis) noexcept { return 2 + axis; }
constexpr int velocity_field(int axis) noexcept { return 2 + kMaxAxes + axis; }
inline constexpr int kFieldCount = 2 + 2 * kMaxAxes;

inline constexpr const char* kVelocityFieldNames[] = {"vx", "vy", "vz"};
static_assert(kMaxAxes <= static_cast<int>(std::size(kVelocityFieldNames)), "every axis has a velocity name");

// The numbers of axes scenes have (HAPSCENE_FOR_EACH_AXES), for the messages below.
#define HAPSCENE_AXES_ENTRY(N) N,
inline constexpr int kSceneAxes[] = {HAPSCENE_FOR_EACH_AXES(HAPSCENE_AXES_ENTRY)};
#undef HAPSCENE_AXES_ENTRY

constexpr bool scene_axes_supported(int axes) noexcept {
  for (const int n : kSceneAxes) {
    if (n == axes) return true;
  }
  return false;
}

// The name of field `field` in a scene of `axes` axes; nullptr when that scene has none.
constexpr const char* state_field_name(int field, int axes) noexcept {
  if (field == kFieldT) return "t";
  if (field == kFieldDt) return "dt";
  if (field >= position_field(0) && field < position_field(axes)) return kAxisNames[field - position_field(0)];
  if (field >= velocity_field(0) && field < velocity_field(axes)) {
    return axes == 1 ? "v" : kVelocityFieldNames[field - velocity_field(0)];
  }
  return nullptr;
}

// Whether `name` is a field of a scene of `axes` axes; its index in *field when it is.
inline bool find_state_field(const char* name, int axes, int* field) noexcept {
  for (int f = 0; f < kFieldCount; ++f) {
    const char* known = state_field_name(f, axes);
    if (known != nullptr && std::strcmp(known, name) == 0) {
      *field = f;
      return true;
    }
  }
  return false;
}

constexpr bool is_velocity_field(int field) noexcept {
  return field >= velocity_field(0) && field < velocity_field(kMaxAxes);
}

// Text for messages, written into out (size bytes, always terminated); no allocation, so
// the sandbox's C functions may call them where a Lua error can follow.

// Appends printf-style text at out + *used (out holds size bytes, *used of them written
// so far): cut at the end, always terminated. The one writer of the texts below.
template <typename... Values>
void append_text(char* out, std::size_t size, std::size_t* used, const char* pattern, Values... values) noexcept {
  if (*used >= size) return;
  const int written = std::snprintf(out + *used, size - *used, pattern, values...);
  if (written > 0) *used += static_cast<std::size_t>(written);
}

// "x, v, t, dt" or "x, y, vx, vy, t, dt": the fields of a scene of `axes` axes.
inline void write_state_field_list(int axes, char* out, std::size_t size) noexcept {
  std::size_t used = 0;
  out[0] = '\0';
  for (const int f : {position_field(0), velocity_field(0), kFieldT, kFieldDt}) {
    const int count = f == kFieldT || f == kFieldDt ? 1 : axes;
    for (int i = 0; i < count; ++i) append_text(out, size, &used, "%s%s", used == 0 ? "" : ", ", state_field_name(f + i, axes));
  }
}

// The scenes that have a field called `name`, as messages say them ("2-D", "2-D or 3-D";
// joined by `joint`); empty when no scene has it.
inline void write_scenes_with_field(const char* name, const char* joint, char* out, std::size_t size) noexcept {
  std::size_t used = 0;
  out[0] = '\0';
  for (const int n : kSceneAxes) {
    int field = 0;
    if (find_state_field(name, n, &field)) append_text(out, size, &used, "%s%d-D", used == 0 ? "" : joint, n);
  }
}

// "x = 0 m, v = 0 m/s, t = 0 s": the state of the load check's call.
inline void write_state_at_rest(int axes, char* out, std::size_t size) noexcept {
  std::size_t used = 0;
  out[0] = '\0';
  for (const int f : {position_field(0), velocity_field(0)}) {
    for (int i = 0; i < axes; ++i) {
      append_text(out, size, &used, "%s%s = 0 %s", used == 0 ? "" : ", ", state_field_name(f + i, axes),
                  is_velocity_field(f) ? "m/s" : "m");
    }
  }
  append_text(out, size, &used, "%s", ", t = 0 s");
}

}  // namespace hapscene::detail
