#include "engine/devices/haply/haply_protocol.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>

#include "engine/base/errors.hpp"

namespace hapscene {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// The joints in port order: order[0] is the joint on the lower port.
std::array<int, 2> joints_in_port_order(const HaplySetup& setup) noexcept {
  return setup.port[0] < setup.port[1] ? std::array<int, 2>{0, 1} : std::array<int, 2>{1, 0};
}

std::uint8_t port_mask(const HaplySetup& setup) noexcept {
  return static_cast<std::uint8_t>((1u << (setup.port[0] - 1)) | (1u << (setup.port[1] - 1)));
}

}  // namespace

void put_float_le(float value, std::uint8_t* out) noexcept {
  const auto bits = std::bit_cast<std::uint32_t>(value);
  for (int i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(bits >> (8 * i));
}

float get_float_le(const std::uint8_t* in) noexcept {
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= static_cast<std::uint32_t>(in[i]) << (8 * i);
  return std::bit_cast<float>(bits);
}

HaplySetup haply_setup_for(const PlanarProfile& profile, std::uint8_t id) {
  HaplySetup setup;
  setup.id = id;
  for (std::size_t i = 0; i < 2; ++i) {
    const PlanarJoint& joint = profile.joints[i];
    const std::string where = "profile \"" + profile.name + "\", joint " + std::to_string(i + 1);
    if (joint.sensor.kind != PlanarSensorKind::angle || joint.drive.law != PlanarDriveLaw::torque) {
      throw InputError("--device haply: " + where +
                       " is not a Haply-style joint (it needs \"sensor\": {\"type\": \"angle\"} and "
                       "\"drive\": {\"law\": \"torque\"}, as haply2diy_v1..v3 have; in " +
                       profile_place(profile.source, "/joints/" + std::to_string(i)) + ")");
    }
    setup.port[i] = joint.board_port;
    setup.motor_counter_clockwise[i] = joint.drive.board_counter_clockwise;
    setup.encoder_counter_clockwise[i] = joint.sensor.board_counter_clockwise;
    setup.encoder_offset_deg[i] = static_cast<float>(joint.sensor.board_offset_rad * kDegPerRad);
    setup.counts_per_revolution[i] = static_cast<float>(joint.sensor.counts_per_revolution);
  }
  if (setup.port[0] == setup.port[1]) {
    throw InputError("--device haply: profile \"" + profile.name + "\" puts both joints on board port " +
                     std::to_string(setup.port[0]) + " (in " + profile_place(profile.source, "/joints/1/board_port") + ")");
  }
  return setup;
}

HaplyFrame encode_reset() noexcept {
  HaplyFrame frame;
  frame.bytes[0] = static_cast<std::uint8_t>(HaplyCommand::reset);
  frame.bytes[1] = 0;
  frame.size = 2;
  return frame;
}

HaplyFrame encode_setup(const HaplySetup& setup) noexcept {
  HaplyFrame frame;
  std::size_t n = 0;
  frame.bytes[n++] = static_cast<std::uint8_t>(HaplyCommand::setup);
  frame.bytes[n++] = setup.id;
  const std::array<int, 2> order = joints_in_port_order(setup);
  frame.bytes[n++] = port_mask(setup);
  for (const int j : order) frame.bytes[n++] = setup.motor_counter_clockwise[static_cast<std::size_t>(j)] ? 1 : 0;
  frame.bytes[n++] = port_mask(setup);
  for (const int j : order) frame.bytes[n++] = setup.encoder_counter_clockwise[static_cast<std::size_t>(j)] ? 1 : 0;
  frame.bytes[n++] = 0;  // analog sensors
  frame.bytes[n++] = 0;  // PWM outputs
  for (const int j : order) {
    put_float_le(setup.encoder_offset_deg[static_cast<std::size_t>(j)], &frame.bytes[n]);
    put_float_le(setup.counts_per_revolution[static_cast<std::size_t>(j)], &frame.bytes[n + 4]);
    n += 8;
  }
  frame.size = n;
  return frame;
}

HaplyFrame encode_torques(const HaplySetup& setup, const Vec2& joint_torque_N_m) noexcept {
  HaplyFrame frame;
  frame.bytes[0] = static_cast<std::uint8_t>(HaplyCommand::torques);
  frame.bytes[1] = setup.id;
  std::size_t n = 2;
  for (const int j : joints_in_port_order(setup)) {
    const double torque_N_m = joint_torque_N_m[j];
    put_float_le(std::isfinite(torque_N_m) ? static_cast<float>(torque_N_m) : 0.0f, &frame.bytes[n]);
    n += 4;
  }
  frame.size = n;
  return frame;
}

std::optional<Vec2> decode_reply(const HaplySetup& setup, const std::uint8_t* reply) noexcept {
  if (reply[0] != setup.id) return std::nullopt;
  Vec2 angle_deg{};
  std::size_t n = 1;
  for (const int j : joints_in_port_order(setup)) {
    angle_deg[j] = get_float_le(&reply[n]);
    n += 4;
  }
  return angle_deg;
}

}  // namespace hapscene
