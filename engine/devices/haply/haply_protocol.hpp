#pragma once
// The Haply 2DIY stock firmware's serial protocol, as bytes (no I/O here). Every frame is
// [command byte][device id][byte payload...][float32 little-endian payload...], with no
// length, no checksum and no start byte:
//   reset    00 00
//   setup    01 id, motor port mask, a direction byte per motor port (0 CW, 1 CCW),
//            encoder port mask, a direction byte per encoder port, the number of analog
//            sensors (0 here), the number of PWM outputs (0 here), then per encoder port
//            in port order its offset (deg) and counts per revolution (floats). The board
//            presets each encoder so it reads the offset now: the linkage must be at its
//            reference pose when setup is sent.
//   torques  02 id, a torque (N m) per motor port in port order (floats); the board
//            applies them, keeps them until the next command (it has no timeout), and
//            answers once: the id, then an angle (deg) per encoder port in port order.
// The setup and reset are not answered. hapscene uses no analog sensors or PWM outputs.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "engine/base/axes.hpp"
#include "engine/devices/planar/planar_profile.hpp"

namespace hapscene {

inline constexpr int kHaplyPorts = 4;                  // the board's actuator and encoder ports
inline constexpr std::uint8_t kHaplyDefaultId = 5;     // the id hAPI's examples use
inline constexpr std::size_t kHaplyTorqueFrameBytes = 2 + 2 * 4;
inline constexpr std::size_t kHaplyReplyBytes = 1 + 2 * 4;
inline constexpr std::size_t kHaplyMaxSetupBytes = 2 + 1 + kHaplyPorts + 1 + kHaplyPorts + 2 + kHaplyPorts * 8;

enum class HaplyCommand : std::uint8_t { reset = 0, setup = 1, torques = 2 };

// What setup tells the board, per joint (joint i is on port ports[i]).
struct HaplySetup {
  std::uint8_t id{kHaplyDefaultId};
  std::array<int, 2> port{1, 2};                    // 1..4, distinct
  std::array<bool, 2> motor_counter_clockwise{};
  std::array<bool, 2> encoder_counter_clockwise{};
  std::array<float, 2> encoder_offset_deg{};
  std::array<float, 2> counts_per_revolution{};
};

// The setup a planar profile asks for. Throws InputError (naming the profile) when a joint
// does not read an angle from the board or does not take a torque (not a Haply-style
// device), or when two joints share a port.
HaplySetup haply_setup_for(const PlanarProfile& profile, std::uint8_t id = kHaplyDefaultId);

// A frame to send: its bytes and how many.
struct HaplyFrame {
  std::array<std::uint8_t, kHaplyMaxSetupBytes> bytes{};
  std::size_t size{};
};

HaplyFrame encode_reset() noexcept;
HaplyFrame encode_setup(const HaplySetup& setup) noexcept;
// Torques per joint (N m, the sign as the board's motor direction); placed in port order.
HaplyFrame encode_torques(const HaplySetup& setup, const Vec2& joint_torque_N_m) noexcept;

// A reply's angles per joint (deg), from kHaplyReplyBytes starting at `reply`, as the board
// sent them (not judged: HaplyLink does that, infinities and NaN included); empty when the
// first byte is not the device id.
std::optional<Vec2> decode_reply(const HaplySetup& setup, const std::uint8_t* reply) noexcept;

// Little-endian float32, as the board's ARM core stores them.
void put_float_le(float value, std::uint8_t* out) noexcept;
float get_float_le(const std::uint8_t* in) noexcept;

}  // namespace hapscene
