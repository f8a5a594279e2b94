-- Detents: notches every `spacing`, like a rotary knob with clicks, on a straight line.
-- Position-based and conservative. Near a notch centre c (within the capture radius r)
--   F = -K d (1 - (d/r)^2)^2,  d = x - c
-- which is the slope of U = -K r^2 / 6 (1 - (d/r)^2)^3; between notches F = 0.
-- Feels like: the handle drops into a notch with a click and has to be pushed out of it
-- (peak 0.69 N at d = r / sqrt(5) with the defaults), then slides freely to the next.
params = {
  spacing = "10 mm",      -- distance between notch centres
  capture = "4 mm",       -- r, how far a notch reaches (at most spacing / 2)
  stiffness = "600 N/m",  -- K, how firmly the centre holds
  origin = "0 mm",        -- one notch centre
}
needs = { velocity = false, time = false }

local p, r, K, x0 = params.spacing, params.capture, params.stiffness, params.origin
if p <= 0 or r <= 0 or r > p / 2 then
  error("detents: capture must be positive and at most half the spacing")
end
local floor = math.floor

function force(s)
  local u = s.x - x0
  local d = u - p * floor(u / p + 0.5)  -- offset from the nearest notch centre
  if d >= r or d <= -r then
    return 0
  end
  local q = 1 - (d / r) ^ 2
  return -K * d * q * q
end
