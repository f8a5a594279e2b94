-- Stick-slip friction (the Karnopp model). While the handle is (nearly) still, it sticks:
-- a stiff damper holds it with up to the static friction force Fs. Once it moves faster
-- than the stick velocity it slides, against the smaller Coulomb force Fc plus viscous b v.
--   |v| <  dv:  F = -(Fs / dv) v                (stick, |F| < Fs)
--   |v| >= dv:  F = -(Fc sign(v) + b v)         (slip)
-- Feels like: dragging a rubber eraser. It holds, breaks away with a small lurch (the
-- force drops from Fs to Fc), then slides with steady drag.
-- Stability: the stick damper Fs / dv (40 N*s/m by default) must stay below about 2 m / T
-- (80 N*s/m for a 40 g handle at 1 kHz); lower stick_velocity with care.
params = {
  static_force = "0.8 N",      -- Fs, breakaway force
  kinetic_force = "0.5 N",     -- Fc, Coulomb force while sliding
  viscous = "0.2 N*s/m",       -- b, extra damping while sliding
  stick_velocity = "20 mm/s",  -- dv, below this speed the handle counts as stuck
}
needs = { time = false }

local Fs, Fc, b, dv = params.static_force, params.kinetic_force, params.viscous, params.stick_velocity
if dv <= 0 or Fc < 0 or Fs < Fc then
  error("friction: need stick_velocity > 0 and static_force >= kinetic_force >= 0")
end
local stick_damping = Fs / dv

function force(s)
  local v = s.v
  if v < dv and v > -dv then
    return -stick_damping * v
  end
  if v > 0 then
    return -(Fc + b * v)
  end
  return Fc - b * v
end
