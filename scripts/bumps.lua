-- Bumps and valleys: a surface profile h(x) with one bump and one valley, felt through
-- a finger pressing down with a constant load W. Position-based and conservative: the
-- force is minus the slope of the potential U(x) = W h(x), so a round trip costs no work
-- and nothing depends on speed or time.
-- Feels like: pushing the handle over a hill (resistance on the way up, a push on the
-- way down) and then into a dip that holds the handle at its bottom.
--   h(x) = H (g(x - xb) - g(x - xv)),  g(u) = exp(-u^2 / (2 sigma^2))
--   F(x) = -W h'(x) = W H / sigma^2 ((x - xb) g(x - xb) - (x - xv) g(x - xv))
-- The largest force is W H / sigma * exp(-1/2), about 1.2 N with the defaults.
params = {
  height = "3 mm",        -- H, height of the bump and depth of the valley
  width = "6 mm",         -- sigma, half width of each (Gaussian standard deviation)
  load = "4 N",           -- W, how hard the virtual finger presses on the surface
  bump_at = "-20 mm",     -- xb, top of the bump
  valley_at = "20 mm",    -- xv, bottom of the valley
}
needs = { velocity = false, time = false }

local H, sigma, W = params.height, params.width, params.load
local xb, xv = params.bump_at, params.valley_at
if sigma <= 0 then error("bumps: width must be positive") end
local exp = math.exp
local gain = W * H / (sigma * sigma)
local inv_two_sigma2 = 1 / (2 * sigma * sigma)

function force(s)
  local ub, uv = s.x - xb, s.x - xv
  return gain * (ub * exp(-ub * ub * inv_two_sigma2) - uv * exp(-uv * uv * inv_two_sigma2))
end
