#pragma once
// The handle state's vector type: one value per axis of a device's task (or joint) space,
// fixed in size when the scene is compiled. Axes<1> is a plain double, so the 1-DOF tick
// keeps its values in registers and compiles to the same instructions it always did;
// Axes<2> and Axes<3> are small arrays with the arithmetic effects and safety need.
// Generic code uses dot(), norm() and component() so it reads the same for every N.
#include <cmath>
#include <cstddef>
#include <iterator>
#include <tuple>
#include <type_traits>
#include <variant>

namespace hapscene {

// A vector of N doubles (N >= 2; Axes<1> is a double).
template <int N>
struct AxisVector {
  static_assert(N >= 2, "one axis is a plain double: Axes<1>");
  double value[N]{};

  constexpr double& operator[](int i) noexcept { return value[i]; }
  constexpr double operator[](int i) const noexcept { return value[i]; }
  // Named components for the planar case (task space x, y or joints 1, 2).
  constexpr double x() const noexcept { return value[0]; }
  constexpr double y() const noexcept { return value[1]; }

  constexpr AxisVector& operator+=(const AxisVector& other) noexcept {
    for (int i = 0; i < N; ++i) value[i] += other.value[i];
    return *this;
  }
  constexpr AxisVector& operator-=(const AxisVector& other) noexcept {
    for (int i = 0; i < N; ++i) value[i] -= other.value[i];
    return *this;
  }
  constexpr AxisVector& operator*=(double scale) noexcept {
    for (int i = 0; i < N; ++i) value[i] *= scale;
    return *this;
  }
  friend constexpr AxisVector operator+(AxisVector a, const AxisVector& b) noexcept { return a += b; }
  friend constexpr AxisVector operator-(AxisVector a, const AxisVector& b) noexcept { return a -= b; }
  friend constexpr AxisVector operator-(AxisVector a) noexcept { return a *= -1.0; }
  friend constexpr AxisVector operator*(AxisVector a, double scale) noexcept { return a *= scale; }
  friend constexpr AxisVector operator*(double scale, AxisVector a) noexcept { return a *= scale; }
  friend constexpr AxisVector operator/(AxisVector a, double divisor) noexcept {
    for (int i = 0; i < N; ++i) a.value[i] /= divisor;
    return a;
  }
  friend constexpr bool operator==(const AxisVector&, const AxisVector&) = default;
};

namespace detail {
template <int N> struct AxesOf { using type = AxisVector<N>; };
template <> struct AxesOf<1> { using type = double; };
}  // namespace detail

// One value per axis: double for N = 1, AxisVector<N> otherwise.
template <int N>
using Axes = typename detail::AxesOf<N>::type;

using Vec2 = AxisVector<2>;

// The numbers of axes a scene can have: the one list that every explicit instantiation of
// the engine's templates follows. HAPSCENE_FOR_EACH_AXES(X) expands X(N) once for each N;
// a device kind of a new N adds its N here (and its parts in SceneParts<N>), nothing else.
#define HAPSCENE_FOR_EACH_AXES(X) X(1) X(2)
// The same list as a variant over a template of N: AxesVariant<T> is
// std::variant<T<1>, T<2>> (checked against the list below).
template <template <int> class T>
using AxesVariant = std::variant<T<1>, T<2>>;

// One T<N> for each N of the list, side by side: AxesTuple<T> is std::tuple<T<1>, T<2>>;
// axes_get<N>(tuple) is the T<N> (checked against the list below).
template <template <int> class T>
using AxesTuple = std::tuple<T<1>, T<2>>;
template <int N, typename Tuple>
constexpr auto& axes_get(Tuple& tuple) noexcept {
  return std::get<N - 1>(tuple);
}

// The names of the task-space axes, in order (labels, CSV columns, messages).
inline constexpr const char* kAxisNames[] = {"x", "y", "z"};
// The largest N of the list: the size of buffers that hold one value per axis of any scene.
inline constexpr int kMaxAxes = 2;
static_assert(kMaxAxes <= static_cast<int>(std::size(kAxisNames)), "every axis has a name");
namespace detail {
template <int N> struct AxesTag {};
#define HAPSCENE_COUNT_AXES(N) +1
static_assert(std::variant_size_v<AxesVariant<AxesTag>> == 0 HAPSCENE_FOR_EACH_AXES(HAPSCENE_COUNT_AXES),
              "AxesVariant names every N of HAPSCENE_FOR_EACH_AXES");
static_assert(std::tuple_size_v<AxesTuple<AxesTag>> == 0 HAPSCENE_FOR_EACH_AXES(HAPSCENE_COUNT_AXES),
              "AxesTuple names every N of HAPSCENE_FOR_EACH_AXES");
#define HAPSCENE_IN_ORDER(N) &&std::is_same_v<std::tuple_element_t<(N) - 1, AxesTuple<AxesTag>>, AxesTag<N>>
static_assert(true HAPSCENE_FOR_EACH_AXES(HAPSCENE_IN_ORDER), "AxesTuple holds T<N> at N - 1");
#undef HAPSCENE_IN_ORDER
#undef HAPSCENE_COUNT_AXES
#define HAPSCENE_WITHIN_MAX(N) &&(N) >= 1 && (N) <= kMaxAxes
#define HAPSCENE_IS_MAX(N) || (N) == kMaxAxes
static_assert(true HAPSCENE_FOR_EACH_AXES(HAPSCENE_WITHIN_MAX), "every N of the list is within 1..kMaxAxes");
static_assert(false HAPSCENE_FOR_EACH_AXES(HAPSCENE_IS_MAX), "kMaxAxes is the largest N of the list");
#undef HAPSCENE_WITHIN_MAX
#undef HAPSCENE_IS_MAX
}  // namespace detail

// Component i of an axis value (for N = 1, the value itself).
constexpr double component(double value, int) noexcept { return value; }
template <int N>
constexpr double component(const AxisVector<N>& value, int i) noexcept { return value[i]; }
// Sets component i of an axis value (for N = 1, the value itself).
constexpr void set_component(double& value, int, double c) noexcept { value = c; }
template <int N>
constexpr void set_component(AxisVector<N>& value, int i, double c) noexcept { value[i] = c; }

constexpr double dot(double a, double b) noexcept { return a * b; }
template <int N>
constexpr double dot(const AxisVector<N>& a, const AxisVector<N>& b) noexcept {
  double sum = 0.0;
  for (int i = 0; i < N; ++i) sum += a.value[i] * b.value[i];
  return sum;
}

inline double norm(double value) noexcept { return std::fabs(value); }
template <int N>
inline double norm(const AxisVector<N>& value) noexcept { return std::sqrt(dot(value, value)); }

// True when every component is finite.
inline bool all_finite(double value) noexcept { return std::isfinite(value); }
template <int N>
inline bool all_finite(const AxisVector<N>& value) noexcept {
  for (int i = 0; i < N; ++i) {
    if (!std::isfinite(value.value[i])) return false;
  }
  return true;
}

namespace detail {
// v scaled by 2^-e, e the exponent of its largest component (exact: std::scalbn), so its
// largest component lies in [1, 2); the zero vector stays zero.
template <int N>
inline AxisVector<N> scaled_to_unit_exponent(const AxisVector<N>& v, int* exponent) noexcept {
  double largest = 0.0;
  for (int i = 0; i < N; ++i) largest = std::fmax(largest, std::fabs(v.value[i]));
  *exponent = largest > 0.0 ? std::ilogb(largest) : 0;
  AxisVector<N> scaled;
  for (int i = 0; i < N; ++i) scaled.value[i] = std::scalbn(v.value[i], -*exponent);
  return scaled;
}
}  // namespace detail

// The length of a finite v without underflow or overflow: v is scaled by a power of two
// first (exact), so components that are subnormal, or whose squares would overflow, still
// give the length to rounding. Where the squares are normal numbers the result is
// norm(v) to the bit: a power of two changes no rounding there. (Not finite v: norm(v).)
template <int N>
inline double stable_norm(const AxisVector<N>& v) noexcept {
  if (!all_finite(v)) return norm(v);
  int exponent = 0;
  const AxisVector<N> scaled = detail::scaled_to_unit_exponent(v, &exponent);
  return std::scalbn(std::sqrt(dot(scaled, scaled)), exponent);
}

// The unit vector along v: the one way a direction read from a file (a 2-D wall's normal,
// a texture's direction, a polygon's edges, a shake direction) is normalised. v is scaled
// as in stable_norm first, so the result is v / norm(v) to the bit wherever that is exact,
// and keeps v's direction where the squares would underflow or overflow. False (*unit
// untouched) when v is zero or not finite: the caller refuses it, naming where it was read.
template <int N>
inline bool unit_vector(const AxisVector<N>& v, AxisVector<N>* unit) noexcept {
  if (!all_finite(v)) return false;
  int exponent = 0;
  const AxisVector<N> scaled = detail::scaled_to_unit_exponent(v, &exponent);
  const double length = std::sqrt(dot(scaled, scaled));
  if (!(length > 0.0)) return false;
  *unit = scaled / length;
  return true;
}

// The z component of the cross product of two planar vectors (which side b lies of a).
constexpr double cross(const Vec2& a, const Vec2& b) noexcept { return a[0] * b[1] - a[1] * b[0]; }

}  // namespace hapscene
