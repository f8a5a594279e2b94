-- Magnet: a point in the plane that pulls the handle in and holds it; position-based
-- and conservative (a central force of the distance alone). With d = p - position and
-- r = |d|:
--   r <= ds:      F = -Fmax d / ds                                    (snapped: a stiff spring)
--   ds < r < R:   F = -(d / r) Fmax ((ds/r)^2 - (ds/R)^2) / (1 - (ds/R)^2)
--   r >= R:       F = 0
-- The pull grows like 1/r^2 as the handle approaches, is continuous everywhere and zero
-- from the range R outwards: the 1-D magnet.lua, turned round its point.
-- Feels like: a fridge magnet on the table. Far away nothing; closer, a growing tug
-- towards the point from any side; then it snaps on and takes a firm pull (Fmax) to free.
params = {
  position_x = "-15 mm", position_y = "127 mm",  -- where the magnet sits
  max_force = "2 N",                             -- Fmax, the pull at the snap distance
  snap_distance = "3 mm",                        -- ds
  range = "25 mm",                               -- R
}
needs = { velocity = false, time = false }

local mx, my = params.position_x, params.position_y
local Fmax, ds, R = params.max_force, params.snap_distance, params.range
if ds <= 0 or R <= ds or Fmax < 0 then
  error("magnet: need 0 < snap_distance < range and max_force >= 0")
end
local edge = (ds / R) ^ 2
local scale = Fmax / (1 - edge)
local spring = Fmax / ds
local sqrt = math.sqrt

function force(s)
  local dx, dy = s.x - mx, s.y - my
  local r = sqrt(dx * dx + dy * dy)
  if r <= ds then
    return -spring * dx, -spring * dy
  end
  if r >= R then
    return 0, 0
  end
  local pull = scale * ((ds / r) ^ 2 - edge) / r
  return -pull * dx, -pull * dy
end
