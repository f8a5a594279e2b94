// The Haply stock firmware's frames as hapscene writes and reads them, against the
// published setup example and the profiles' port assignments.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/devices/builtin_profiles.hpp"
#include "engine/devices/haply/haply_protocol.hpp"
#include "engine/devices/planar/planar_profile.hpp"

using namespace hapscene;

namespace {

std::vector<std::uint8_t> bytes_of(const HaplyFrame& frame) {
  return std::vector<std::uint8_t>(frame.bytes.begin(), frame.bytes.begin() + static_cast<long>(frame.size));
}

std::vector<std::uint8_t> float_bytes(float value) {
  std::uint8_t b[4];
  put_float_le(value, b);
  return {b, b + 4};
}

}  // namespace

TEST_CASE("haply protocol: the v3 setup is the published example byte for byte") {
  const HaplySetup setup = haply_setup_for(load_planar_profile("haply2diy_v3", "."));
  CHECK(setup.port[0] == 2);  // joint 1 on port 2, joint 2 on port 1, as hAPI's examples wire them
  CHECK(setup.port[1] == 1);
  std::vector<std::uint8_t> expected{0x01, 0x05, 0x03, 0x01, 0x01, 0x03, 0x01, 0x01, 0x00, 0x00};
  for (const float f : {12.0f, 4880.0f, 168.0f, 4880.0f}) {
    const std::vector<std::uint8_t> b = float_bytes(f);
    expected.insert(expected.end(), b.begin(), b.end());
  }
  CHECK(bytes_of(encode_setup(setup)) == expected);
  CHECK(bytes_of(encode_reset()) == std::vector<std::uint8_t>{0x00, 0x00});
}

TEST_CASE("haply protocol: v2's clockwise joint 2 is told so on its port") {
  const HaplySetup setup = haply_setup_for(load_planar_profile("haply2diy_v2", "."));
  const std::vector<std::uint8_t> frame = bytes_of(encode_setup(setup));
  // Port 1 carries joint 2 (CW: 0), port 2 joint 1 (CCW: 1), for the motors and encoders.
  CHECK(frame[3] == 0x00);
  CHECK(frame[4] == 0x01);
  CHECK(frame[6] == 0x00);
  CHECK(frame[7] == 0x01);
  CHECK(get_float_le(&frame[10]) == doctest::Approx(-61.0));  // joint 2's offset first (port 1)
  CHECK(get_float_le(&frame[18]) == doctest::Approx(241.0));
}

TEST_CASE("haply protocol: torques go out in port order and replies come back per joint") {
  const HaplySetup setup = haply_setup_for(load_planar_profile("haply2diy_v3", "."));
  const HaplyFrame frame = encode_torques(setup, Vec2{{0.01, -0.02}});
  REQUIRE(frame.size == kHaplyTorqueFrameBytes);
  CHECK(frame.bytes[0] == 0x02);
  CHECK(frame.bytes[1] == 0x05);
  CHECK(get_float_le(&frame.bytes[2]) == -0.02f);  // port 1: joint 2
  CHECK(get_float_le(&frame.bytes[6]) == 0.01f);   // port 2: joint 1

  // A non-finite torque never reaches the wire.
  const HaplyFrame bad = encode_torques(setup, Vec2{{std::numeric_limits<double>::quiet_NaN(), 0.0}});
  CHECK(get_float_le(&bad.bytes[6]) == 0.0f);

  std::uint8_t reply[kHaplyReplyBytes]{0x05};
  put_float_le(20.5f, &reply[1]);   // port 1: joint 2
  put_float_le(150.25f, &reply[5]); // port 2: joint 1
  const std::optional<Vec2> angles = decode_reply(setup, reply);
  REQUIRE(angles.has_value());
  CHECK((*angles)[0] == 150.25);
  CHECK((*angles)[1] == 20.5);

  reply[0] = 0x06;
  CHECK_FALSE(decode_reply(setup, reply).has_value());  // another id
  reply[0] = 0x05;
  put_float_le(std::numeric_limits<float>::infinity(), &reply[1]);
  const std::optional<Vec2> unjudged = decode_reply(setup, reply);  // the link judges it
  REQUIRE(unjudged.has_value());
  CHECK(std::isinf((*unjudged)[1]));
}

TEST_CASE("haply protocol: only Haply-style profiles, each joint on its own port") {
  CHECK_THROWS_WITH_AS(haply_setup_for(load_planar_profile("haplink", ".")),
                       doctest::Contains("profile \"haplink\", joint 1 is not a Haply-style joint"), InputError);
  PlanarProfile v3 = load_planar_profile("haply2diy_v3", ".");
  v3.joints[1].board_port = 2;
  CHECK_THROWS_WITH_AS(haply_setup_for(v3), doctest::Contains("both joints on board port 2"), InputError);
}

namespace {

std::string builtin_text(std::string_view name) {
  for (const BuiltinProfile& profile : builtin_profiles()) {
    if (profile.name == name) return std::string(profile.json_text);
  }
  FAIL("no builtin profile " << name);
  return {};
}

std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("planar profile: board ports are checked where they are written") {
  // Both joints on port 2.
  const std::string v3 = builtin_text("haply2diy_v3");
  const std::string same = replace_once(v3, "\"board_port\": 1", "\"board_port\": 2");
  CHECK_THROWS_WITH_AS(parse_planar_profile(same, "same.json"),
                       doctest::Contains("/joints/1/board_port"), InputError);
  CHECK_THROWS_WITH_AS(parse_planar_profile(replace_once(v3, "\"board_port\": 1", "\"board_port\": 5"), "five.json"),
                       doctest::Contains("/joints/1/board_port"), InputError);
  // A Haplink joint has no board port (its board is the Hapkit's: duty and direction).
  const std::string haplink = builtin_text("haplink");
  const std::string with_port = replace_once(haplink, "\"sensor\"", "\"board_port\": 1, \"sensor\"");
  CHECK_THROWS_WITH_AS(parse_planar_profile(with_port, "haplink.json"),
                       doctest::Contains("only a joint with an \"angle\" sensor and a \"torque\" drive"), InputError);
  // Without the key, joint i is on port i (v1, as hAPI's first examples wire it).
  const PlanarProfile v1 = load_planar_profile("haply2diy_v1", ".");
  CHECK(v1.joints[0].board_port == 1);
  CHECK(v1.joints[1].board_port == 2);
}
