-- Magnet: a point that pulls the handle in and holds it. Position-based and conservative.
--   |d| <= ds:      F = -Fmax d / ds                         (snapped: a stiff spring)
--   ds < |d| < R:   F = -sign(d) Fmax ((ds/|d|)^2 - (ds/R)^2) / (1 - (ds/R)^2)
--   |d| >= R:       F = 0                                    (d = x - position)
-- The pull grows like 1/d^2 as the handle approaches, is continuous everywhere, and is
-- zero from the range R outwards.
-- Feels like: a fridge magnet. Far away nothing; closer, a growing tug; then it snaps
-- onto the point and takes a firm push (Fmax) to pull it off.
params = {
  position = "0 mm",       -- where the magnet sits
  max_force = "2 N",       -- Fmax, the pull at the snap distance
  snap_distance = "3 mm",  -- ds, inside this a spring of Fmax / ds holds the handle
  range = "25 mm",         -- R, no pull beyond this
}
needs = { velocity = false, time = false }

local xm, Fmax, ds, R = params.position, params.max_force, params.snap_distance, params.range
if ds <= 0 or R <= ds or Fmax < 0 then
  error("magnet: need 0 < snap_distance < range and max_force >= 0")
end
local edge = (ds / R) ^ 2
local scale = Fmax / (1 - edge)

function force(s)
  local d = s.x - xm
  local distance = d < 0 and -d or d
  if distance <= ds then
    return -Fmax * d / ds
  end
  if distance >= R then
    return 0
  end
  local pull = scale * ((ds / distance) ^ 2 - edge)
  return d > 0 and -pull or pull
end
