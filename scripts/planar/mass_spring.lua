-- Virtual mass on a 2-D spring: a puck of mass m tied by a spring k to an anchor, that
-- the hand holds through a coupling spring kc (a virtual coupling). The hand feels
--   F = -kc (p - q)            (p the handle, q the puck, both 2-D)
-- and the puck obeys
--   m q'' = kc (p - q) - k (q - anchor) - b q'
-- integrated with semi-implicit (symplectic) Euler, which does not gain energy, in
-- substeps of at most 0.1 / omega (omega = sqrt((k + kc) / m)), per axis alike.
-- State: the puck's position and velocity, reset by reset(); on the first call the puck
-- starts where it would rest with the hand where it is, so a run begins without a jolt.
-- Feels like: a heavy puck on a rubber band. Push and it lags behind, then swings back;
-- circle the handle near the natural frequency (about 7 Hz) and it whirls round.
params = {
  mass = "0.2 kg",                        -- m
  stiffness = "100 N/m",                  -- k, from the puck to the anchor
  coupling = "300 N/m",                   -- kc, from the handle to the puck
  damping = "0.5 N*s/m",                  -- b, on the puck
  anchor_x = "-15 mm", anchor_y = "127 mm",
}
needs = { velocity = false, time = false }

local m, k, kc, b = params.mass, params.stiffness, params.coupling, params.damping
local ax, ay = params.anchor_x, params.anchor_y
if m <= 0 or k < 0 or kc <= 0 or b < 0 then
  error("mass_spring: need mass > 0, coupling > 0, stiffness >= 0, damping >= 0")
end
local max_step = 0.1 / math.sqrt((k + kc) / m)
local ceil = math.ceil

local qx, qy, wx, wy, started

function reset()
  qx, qy, wx, wy, started = ax, ay, 0, 0, false
end
reset()

function force(s)
  local x, y = s.x, s.y
  if not started then
    qx, qy = (kc * x + k * ax) / (kc + k), (kc * y + k * ay) / (kc + k)
    wx, wy, started = 0, 0, true
  end
  local steps = ceil(s.dt / max_step)
  if steps < 1 then steps = 1 end
  local h = s.dt / steps
  for _ = 1, steps do
    local fx = (kc * (x - qx) - k * (qx - ax) - b * wx) / m
    local fy = (kc * (y - qy) - k * (qy - ay) - b * wy) / m
    wx, wy = wx + fx * h, wy + fy * h
    qx, qy = qx + wx * h, qy + wy * h
  end
  return -kc * (x - qx), -kc * (y - qy)
end
