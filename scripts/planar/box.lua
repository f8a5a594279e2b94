-- Box: the course's 2-D box, written as a script: the twin of the built-in
-- {"type": "box"}, equal to its open loop to the bit (tests/lua/planar_script_test.cpp).
-- A box [min_x, max_x] x [min_y, max_y] with a spring of stiffness K:
--   F = (K (px - x), K (py - y))
-- where (px, py) is the nearest point of the box's outline when the handle is in the
-- solid, else the handle itself (no force):
--   solid = "inside":  the box is solid; inside it the handle is pushed out through the
--                      nearest side (the first of left, right, bottom, top on a tie);
--   solid = "outside": the box is a cage; outside it (px, py) is the handle clamped
--                      into the box (a corner beyond a corner).
-- No history: this is the built-in's open loop. Closed loop the built-in keeps a proxy
-- (a god object), so a handle pushed deep into a solid box is not flung out through the
-- far side; this script is, past the middle: keep the stiffness modest (the lab's 200 N/m).
-- Feels like: a block on the table you slide round (inside), or a tray you are held in
-- (outside).
params = {
  min_x = "-40 mm", min_y = "110 mm",   -- the lower left corner
  max_x = "0 mm",   max_y = "135 mm",   -- the upper right corner
  stiffness = "200 N/m",                -- K
  solid = "inside",                     -- "inside" (a block) or "outside" (a cage)
}
needs = { velocity = false, time = false }

local x0, y0, x1, y1 = params.min_x, params.min_y, params.max_x, params.max_y
local K = params.stiffness
local solid_inside = params.solid == "inside"
if not solid_inside and params.solid ~= "outside" then
  error('box: params.solid must be "inside" or "outside", got "' .. params.solid .. '"')
end
if not (x0 < x1 and y0 < y1) then error("box: need min_x < max_x and min_y < max_y") end
if K < 0 then error("box: need stiffness >= 0") end
-- The box as validate sees it (docs/reference/lua.md, "Scripts in 2-D"): it presses into its
-- edges and corners as it does into the built-in box's.
shapes = { { type = "box", min = { x0, y0 }, max = { x1, y1 }, solid = params.solid } }
local min = math.min

function force(s)
  local x, y = s.x, s.y
  local px, py = x, y
  if solid_inside then
    if x0 < x and x < x1 and y0 < y and y < y1 then
      local left, right, bottom, top = x - x0, x1 - x, y - y0, y1 - y
      local nearest = min(left, right, bottom, top)
      if left == nearest then px = x0
      elseif right == nearest then px = x1
      elseif bottom == nearest then py = y0
      else py = y1 end
    end
  else
    if x < x0 then px = x0 elseif x1 < x then px = x1 end
    if y < y0 then py = y0 elseif y1 < y then py = y1 end
  end
  return K * (px - x), K * (py - y)
end
