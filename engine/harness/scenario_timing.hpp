#pragma once
// The timings and distances of validate's virtual-hand scenarios that every device kind
// shares (engine/harness/scenario.cpp for 1-D, planar_validate_scenario.cpp for 2-D): how
// fast the hand gets into place and presses, how long it holds, shakes and lets go.
namespace hapscene::scenario_timing {

inline constexpr double kMoveSpeed_m_per_s = 0.05;             // getting into position
inline constexpr double kWorkspaceMargin_m = 0.003;            // the hand stays this far inside
inline constexpr double kApproachGap_m = 0.003;                // press: start this far in front
inline constexpr double kPressSpeeds_m_per_s[] = {0.02, 0.08, 0.2};
inline constexpr double kPressHold_s = 0.3;
inline constexpr double kReleaseHold_s = 0.5;
inline constexpr double kReleaseWatch_s = 1.5;
inline constexpr double kHoldDepth_m = 0.002;                  // hold: this far into the solid
inline constexpr double kHoldSettle_s = 0.5;
inline constexpr double kHoldWatch_s = 1.0;
inline constexpr double kShakeAmplitude_m = 0.002;
inline constexpr double kShakeFrequency_Hz = 8.0;
inline constexpr double kShakeDuration_s = 1.5;
inline constexpr double kFreeDuration_s = 1.5;
inline constexpr double kSettle_s = 0.3;                       // 2-D: after a path, before the run ends

}  // namespace hapscene::scenario_timing
