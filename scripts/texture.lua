-- Texture: the Hapkit lab texture. Damping fields of width w separated by gaps s cover
-- the workspace; inside a field F = -B v, in a gap F = 0.
-- Feels like: sliding across corduroy. Moving through a field is sluggish, the gaps are
-- free, so a steady sweep feels like evenly spaced ridges; holding still feels like
-- nothing (damping only resists motion).
-- The fields are [x0 + k p, x0 + k p + w) for every integer k, with period p = w + s;
-- the lab uses s = w (fields at [0.020, 0.025) m for w = 5 mm).
params = {
  damping = "0.5 N*s/m",  -- B inside a field
  width = "5 mm",         -- w, width of a field
  gap = "5 mm",           -- s, width of a gap (the lab uses s = w)
  origin = "0 mm",        -- x0, where a field begins
}
needs = { time = false }

local B, w, x0 = params.damping, params.width, params.origin
local period = params.width + params.gap
if w <= 0 or params.gap < 0 then
  error("texture: width must be positive and gap must not be negative")
end

function force(s)
  -- Lua's % on floats is a floored modulo: the phase is in [0, period) for any x.
  if (s.x - x0) % period < w then
    return -B * s.v
  end
  return 0
end
