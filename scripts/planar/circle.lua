-- Circle: the course's 2-D circle, written as a script: the twin of the built-in
-- {"type": "circle"}, equal to its open loop to the bit (tests/lua/planar_script_test.cpp).
-- A circle of centre (cx, cy) and radius r with a spring of stiffness K. With
--   dx = x - cx, dy = y - cy, distance = sqrt(dx * dx + dy * dy),
-- the handle is in the solid when distance < r (solid = "inside", a disc) or
-- distance > r (solid = "outside", a round cage). There
--   F = (K (px - x), K (py - y)),  (px, py) = (cx + dx * (r / distance), cy + dy * (r / distance))
-- the nearest point of the rim (at the very centre of a disc: (cx + r, cy)); elsewhere
-- no force. No history: the built-in's open loop (see box.lua about closed loop).
-- Feels like: a coin on the table you feel round (inside), or the inside of a cup (outside).
params = {
  center_x = "-16 mm", center_y = "120 mm",  -- the centre
  radius = "15 mm",                          -- r
  stiffness = "200 N/m",                     -- K
  solid = "inside",                          -- "inside" (a disc) or "outside" (a cage)
}
needs = { velocity = false, time = false }

local cx, cy, r, K = params.center_x, params.center_y, params.radius, params.stiffness
local solid_inside = params.solid == "inside"
if not solid_inside and params.solid ~= "outside" then
  error('circle: params.solid must be "inside" or "outside", got "' .. params.solid .. '"')
end
if r <= 0 or K < 0 then error("circle: need radius > 0 and stiffness >= 0") end
-- The circle as validate sees it (docs/reference/lua.md, "Scripts in 2-D").
shapes = { { type = "circle", center = { cx, cy }, radius = r, solid = params.solid } }
local sqrt = math.sqrt

function force(s)
  local x, y = s.x, s.y
  local dx, dy = x - cx, y - cy
  local distance = sqrt(dx * dx + dy * dy)
  local in_solid
  if solid_inside then in_solid = distance < r else in_solid = distance > r end
  local px, py = x, y
  if in_solid then
    if distance == 0 then
      px, py = cx + r, cy
    else
      px, py = cx + dx * (r / distance), cy + dy * (r / distance)
    end
  end
  return K * (px - x), K * (py - y)
end
