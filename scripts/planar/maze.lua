-- Maze: a small labyrinth of solid walls (axis-aligned bars, one of them only 0.5 mm
-- thin) rendered with a proxy written in the script (a god object): the proxy is a point
-- that never enters a wall, pulled towards the handle every call, and the handle feels
--   F = K (proxy - p).
-- Each call the proxy moves from where it was straight towards the handle; the first
-- wall face the move would cross stops it on that face, the rest of the move is
-- projected onto the face (it slides along), and the move goes on from there (at most
-- four faces a call). So it holds in a concave corner (two faces stop it) and never
-- crosses a wall, however thin and however far the handle jumps in one tick.
-- The first call after reset() (and every open-loop point, each a fresh instance) puts
-- the proxy at the nearest point outside every wall, as the built-in shapes' open loop
-- does: inside a wall F pushes out through its nearest free face; elsewhere F = 0.
-- Walls meeting at a junction overlap by 1 mm, so no seam between them is free.
-- Feels like: a wooden labyrinth board with the handle as the ball; slide along the
-- walls, rest in the corners, and the thin fin holds like the thick ones.
params = {
  stiffness = "200 N/m",  -- K, the lab's box stiffness (2 N at 10 mm)
}
needs = { velocity = false, time = false }

local K = params.stiffness
if K < 0 then error("maze: need stiffness >= 0") end

-- The walls in mm: min x, min y, max x, max y (solid strictly between).
local walls_mm = {
  { -60, 100,  30,   102 },     -- 1 the frame: bottom
  { -60, 158,  30,   160 },     -- 2 top
  { -60, 100, -58,   160 },     -- 3 left
  {  28, 100,  30,   160 },     -- 4 right
  { -59, 120,   0,   122 },     -- 5 a shelf from the left wall
  { -30, 121, -28,   145 },     -- 6 a post standing on the shelf
  {  -5, 138,  29,   140 },     -- 7 a ledge from the right wall
  {  10, 101,  12,   125 },     -- 8 a pillar from the bottom
  { -45.25, 135, -44.75, 159 }, -- 9 a thin fin (0.5 mm) hanging from the top
}
local n = #walls_mm
local X0, Y0, X1, Y1 = {}, {}, {}, {}
for i = 1, n do
  local w = walls_mm[i]
  X0[i], Y0[i], X1[i], Y1[i] = w[1] * 1e-3, w[2] * 1e-3, w[3] * 1e-3, w[4] * 1e-3
end

-- The walls as validate sees them (docs/reference/lua.md, "Scripts in 2-D"): it presses into
-- their faces and corners and swipes across the thin ones, as for built-in boxes.
shapes = {}
for i = 1, n do
  shapes[i] = { type = "box", min = { X0[i], Y0[i] }, max = { X1[i], Y1[i] }, solid = "inside" }
end

local huge = math.huge

local function inside_any(x, y)
  for i = 1, n do
    if X0[i] < x and x < X1[i] and Y0[i] < y and y < Y1[i] then return true end
  end
  return false
end

-- The nearest point to (x, y) outside every wall: (x, y) itself when free, else the
-- nearest point of a wall face not inside another wall (ties: the first wall, and of
-- its faces left, right, bottom, top).
local function nearest_free(x, y)
  if not inside_any(x, y) then return x, y end
  local best, bx, by = huge, x, y
  for i = 1, n do
    local cx = x < X0[i] and X0[i] or (x > X1[i] and X1[i] or x)
    local cy = y < Y0[i] and Y0[i] or (y > Y1[i] and Y1[i] or y)
    for face = 1, 4 do
      local px, py
      if face == 1 then px, py = X0[i], cy
      elseif face == 2 then px, py = X1[i], cy
      elseif face == 3 then px, py = cx, Y0[i]
      else px, py = cx, Y1[i] end
      local dx, dy = px - x, py - y
      local d = dx * dx + dy * dy
      if d < best and not inside_any(px, py) then best, bx, by = d, px, py end
    end
  end
  return bx, by
end

local qx, qy, started

function reset()
  qx, qy, started = 0, 0, false
end
reset()

-- Moves the proxy from (qx, qy) towards the goal (gx, gy), stopping on faces.
local function move(gx, gy)
  for _ = 1, 4 do
    local dx, dy = gx - qx, gy - qy
    if dx == 0 and dy == 0 then return end
    local t_hit, hit_x, face = 1, false, 0
    for i = 1, n do
      -- Where the move enters and leaves the wall's open box, per axis (slabs).
      local enter_x, leave_x, face_x, enter_y, leave_y, face_y
      if dx > 0 then enter_x, leave_x, face_x = (X0[i] - qx) / dx, (X1[i] - qx) / dx, X0[i]
      elseif dx < 0 then enter_x, leave_x, face_x = (X1[i] - qx) / dx, (X0[i] - qx) / dx, X1[i]
      elseif X0[i] < qx and qx < X1[i] then enter_x, leave_x = -huge, huge
      else enter_x, leave_x = huge, -huge end
      if dy > 0 then enter_y, leave_y, face_y = (Y0[i] - qy) / dy, (Y1[i] - qy) / dy, Y0[i]
      elseif dy < 0 then enter_y, leave_y, face_y = (Y1[i] - qy) / dy, (Y0[i] - qy) / dy, Y1[i]
      elseif Y0[i] < qy and qy < Y1[i] then enter_y, leave_y = -huge, huge
      else enter_y, leave_y = huge, -huge end
      local enter = enter_x > enter_y and enter_x or enter_y
      local leave = leave_x < leave_y and leave_x or leave_y
      -- A hit: the move really goes into the wall (not grazing a face or a corner, not
      -- moving off a face it sits on). A proxy a rounding error inside a wall (it stopped
      -- exactly at a corner) counts as on the face it is nearest to crossing: t = 0.
      if enter < leave and leave > 0 then
        local t = enter > 0 and enter or 0
        if t < t_hit then
          t_hit = t
          if enter_x >= enter_y then hit_x, face = true, face_x else hit_x, face = false, face_y end
        end
      end
    end
    if t_hit >= 1 then
      qx, qy = gx, gy
      return
    end
    -- Stop on the face (exactly on it), and slide: the goal projected onto the face.
    if hit_x then
      qx, qy = face, qy + t_hit * dy
      gx = face
    else
      qx, qy = qx + t_hit * dx, face
      gy = face
    end
  end
end

function force(s)
  local x, y = s.x, s.y
  if not started then
    qx, qy = nearest_free(x, y)
    started = true
  else
    move(x, y)
  end
  return K * (qx - x), K * (qy - y)
end
