-- Vortex: a whirlpool that pushes the handle round a centre, anticlockwise for a
-- positive strength. A Rankine vortex: with d = p - centre, r = |d| and t = (-dy, dx)
-- (d turned by 90 degrees),
--   r <= R:  F = (F0 / R) t                (grows linearly from 0 at the centre)
--   r > R:   F = (F0 R / r^2) t            (|F| = F0 R / r, fading outwards)
-- so |F| peaks at F0 on the core's rim r = R. Not conservative (its curl is 2 F0 / R in
-- the core): a handle let go drifts round and round, the device's damping balancing the
-- push; it also pushes a held handle sideways, never towards or away from the centre.
-- Feels like: stirring a pot; the spoon is carried round.
params = {
  center_x = "-15 mm", center_y = "127 mm",
  core_radius = "10 mm",   -- R
  strength = "0.8 N",      -- F0, the push at the core's rim (negative: clockwise)
}
needs = { velocity = false, time = false }

local cx, cy, R, F0 = params.center_x, params.center_y, params.core_radius, params.strength
if R <= 0 then error("vortex: need core_radius > 0") end
local inner = F0 / R
local outer = F0 * R

function force(s)
  local dx, dy = s.x - cx, s.y - cy
  local r2 = dx * dx + dy * dy
  local gain
  if r2 <= R * R then gain = inner else gain = outer / r2 end
  return -gain * dy, gain * dx
end
