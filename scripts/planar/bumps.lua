-- Bumps: a hill and a hollow on a flat table, the slope of a potential U (conservative:
-- no path gains or loses energy; tests/lua/planar_script_test.cpp checks F = -grad U
-- and a closed loop's work). Each is a Gaussian of width w (its standard deviation):
--   U(x, y) = E (exp(-|p - hill|^2 / (2 w^2)) - exp(-|p - hollow|^2 / (2 w^2)))
--   F = -grad U = (E / w^2) (g_hill (p - hill) - g_hollow (p - hollow)),
-- g = exp(-|p - c|^2 / (2 w^2)) for each centre c. E = peak_force * w * exp(1/2), so
-- the steepest slope of each, at distance w from its centre, pushes with peak_force.
-- Feels like: the handle rolls off the hill and into the hollow; rubbing over either
-- gives a smooth push then pull.
params = {
  hill_x = "-35 mm", hill_y = "127 mm",      -- the hill's centre
  hollow_x = "5 mm", hollow_y = "127 mm",    -- the hollow's centre
  width = "10 mm",                           -- w
  peak_force = "1 N",                        -- the steepest slope's push
}
needs = { velocity = false, time = false }

local hx, hy, vx, vy = params.hill_x, params.hill_y, params.hollow_x, params.hollow_y
local w, Fpeak = params.width, params.peak_force
if w <= 0 or Fpeak < 0 then error("bumps: need width > 0 and peak_force >= 0") end
local E = Fpeak * w * math.exp(0.5)  -- J
local gain = E / (w * w)             -- N/m
local spread = 2 * w * w
local exp = math.exp

function force(s)
  local x, y = s.x, s.y
  local ax, ay = x - hx, y - hy
  local bx, by = x - vx, y - vy
  local g_hill = exp(-(ax * ax + ay * ay) / spread)
  local g_hollow = exp(-(bx * bx + by * by) / spread)
  return gain * (g_hill * ax - g_hollow * bx), gain * (g_hill * ay - g_hollow * by)
end
